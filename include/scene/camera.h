/* camera.h: where the eye is and how it projects.
 *
 * A camera is eye/target/up plus projection parameters; view and projection matrices are
 * derived on demand (never stored, so they cannot go stale). Defaults (conventions): eye
 * (0,0,3), target origin, up +Y, vertical fov 50 degrees, near 0.1, far 100, perspective.
 * ortho_height > 0 selects an orthographic projection of that view-volume height. */
#ifndef RASTTY_CAMERA_H
#define RASTTY_CAMERA_H

#include "vecmath.h"

struct camera {
    vec3 eye, target, up;
    double fov_deg;      /* vertical, perspective only */
    double near, far;    /* positive distances along the view direction */
    double ortho_height; /* 0 = perspective */
};

void camera_default(struct camera *c);
mat4 camera_view(const struct camera *c);
/* aspect = framebuffer width / height */
mat4 camera_proj(const struct camera *c, double aspect);
/* Unit vector from the scene toward the viewer for orthographic lighting (V is constant). */
vec3 camera_back(const struct camera *c);
/* Frame a world-space box: keep the view direction (but never edge-on onto a flat box: see
 * camera_flat_view), aim at the box centre and back off until all eight corners are inside
 * the vertical and horizontal fov (5% margin); near/far are set around the box.
 * Orthographic cameras get a view height that fits the box. */
void camera_frame_box(struct camera *c, vec3 lo, vec3 hi, double aspect);
/* The view direction (back: unit, from the scene toward the eye) for a box: back itself,
 * unless the box is flat (its thinnest side at most CAMERA_FLAT_RATIO of the next) and back
 * within 60 degrees of its plane — edge-on, a floor or a sheet is a line or nothing — then
 * turned to 45 degrees above the plane from the thin axis' + side (a 3/4 view from above a
 * floor). */
#define CAMERA_FLAT_RATIO 0.1
vec3 camera_flat_view(vec3 back, vec3 lo, vec3 hi);

/* Interactive control. Yaw turns about the camera's up vector, pitch about its right vector;
 * pitch stops CAMERA_PITCH_LIMIT degrees short of straight up or down. In fly mode the eye
 * stays and the target turns around it; in orbit mode the target stays and the eye moves
 * around it (distance kept). Positive yaw turns left, positive pitch looks up. */
#define CAMERA_PITCH_LIMIT 1.0
void camera_turn(struct camera *c, double yaw_deg, double pitch_deg, int orbit);
/* Move by distances along the view direction, the right vector and the world up vector; in
 * fly mode eye and target move together; in orbit mode `forward` changes the distance to
 * the target (never closer than 1e-3 of it). */
void camera_move(struct camera *c, double forward, double right, double up, int orbit);
/* Pan: eye and target move together by `right` along the view's right vector and `up`
 * along the view's own up (the picture's vertical, not the world's), in world units. */
void camera_pan(struct camera *c, double right, double up);
double camera_distance(const struct camera *c);

#endif
