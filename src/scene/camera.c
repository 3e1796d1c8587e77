/* camera.c: view and projection matrices from a camera (see camera.h). */
#include "camera.h"

void camera_default(struct camera *c)
{
    c->eye = v3(0, 0, 3);
    c->target = v3(0, 0, 0);
    c->up = v3(0, 1, 0);
    c->fov_deg = 50;
    c->near = 0.1;
    c->far = 100;
    c->ortho_height = 0;
}

mat4 camera_view(const struct camera *c)
{
    return m4_lookat(c->eye, c->target, c->up);
}

mat4 camera_proj(const struct camera *c, double aspect)
{
    if (c->ortho_height > 0)
        return m4_ortho(c->ortho_height, aspect, c->near, c->far);
    return m4_perspective(c->fov_deg, aspect, c->near, c->far);
}

vec3 camera_back(const struct camera *c)
{
    return v3_norm(v3_sub(c->eye, c->target));
}

vec3 camera_flat_view(vec3 back, vec3 lo, vec3 hi)
{
    double ext[3] = {hi.x - lo.x, hi.y - lo.y, hi.z - lo.z};
    int thin = 0;
    for (int k = 1; k < 3; k++)
        thin = ext[k] < ext[thin] ? k : thin;
    double mid = fmin(ext[(thin + 1) % 3], ext[(thin + 2) % 3]);
    double b[3] = {back.x, back.y, back.z};
    if (!(ext[thin] <= CAMERA_FLAT_RATIO * mid) || fabs(b[thin]) >= 0.5)
        return back;
    /* half way between the view direction and the thin axis (from its + side: above a
     * floor): 45 degrees onto the plane */
    b[thin] = 0;
    double l = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
    if (!(l > 0))
        b[(thin + 2) % 3] = 1, l = 1;
    for (int k = 0; k < 3; k++)
        b[k] /= l;
    b[thin] = 1;
    return v3_norm(v3(b[0], b[1], b[2]));
}

void camera_frame_box(struct camera *c, vec3 lo, vec3 hi, double aspect)
{
    vec3 back = v3_norm(v3_sub(c->eye, c->target));
    if (v3_len(back) == 0)
        back = v3(0, 0, 1);
    back = camera_flat_view(back, lo, hi);
    vec3 right = v3_norm(v3_cross(v3_scale(back, -1), c->up));
    vec3 up = v3_cross(right, v3_scale(back, -1));
    vec3 center = v3_scale(v3_add(lo, hi), 0.5);
    double tv = tan(c->fov_deg * (M_PI / 360.0)), th = tv * aspect;
    double dist = 0, extent = 0, half_w = 0, half_h = 0;
    for (int i = 0; i < 8; i++) {
        vec3 p = v3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
        vec3 d = v3_sub(p, center);
        double x = fabs(v3_dot(d, right)), y = fabs(v3_dot(d, up)), z = v3_dot(d, back);
        /* the corner must satisfy x <= th * (dist - z) and y <= tv * (dist - z) */
        dist = fmax(dist, fmax(z + x / th, z + y / tv));
        extent = fmax(extent, v3_len(d));
        half_w = fmax(half_w, x);
        half_h = fmax(half_h, y);
    }
    if (!(extent > 0))
        extent = 1, dist = 1 / tv;
    dist *= 1.05;
    if (c->ortho_height > 0) {
        c->ortho_height = 2.1 * fmax(half_h, half_w / aspect);
        dist = 2 * extent;
    }
    c->target = center;
    c->eye = v3_add(center, v3_scale(back, dist));
    c->near = fmax((dist - extent) * 0.5, extent * 1e-3);
    c->far = (dist + extent) * 2;
}

double camera_distance(const struct camera *c)
{
    return v3_len(v3_sub(c->target, c->eye));
}

static vec3 rotate_about(vec3 v, vec3 axis, double deg)
{
    return m4_mul_dir(m4_rotate(axis, deg), v);
}

void camera_turn(struct camera *c, double yaw_deg, double pitch_deg, int orbit)
{
    /* orbiting moves the eye the opposite way round, so dragging feels like turning the model */
    if (orbit) {
        yaw_deg = -yaw_deg;
        pitch_deg = -pitch_deg;
    }
    vec3 up = v3_norm(c->up);
    vec3 fwd = v3_sub(c->target, c->eye);
    double dist = v3_len(fwd);
    fwd = v3_scale(fwd, 1.0 / dist);
    /* clamp pitch: the angle between fwd and up stays within [limit, 180 - limit] */
    double angle = acos(fmax(-1.0, fmin(1.0, v3_dot(fwd, up)))) * (180.0 / M_PI);
    double lo = CAMERA_PITCH_LIMIT, hi = 180.0 - CAMERA_PITCH_LIMIT;
    pitch_deg = angle - fmin(hi, fmax(lo, angle - pitch_deg));
    vec3 right = v3_norm(v3_cross(fwd, up));
    fwd = rotate_about(fwd, right, pitch_deg);
    fwd = v3_norm(rotate_about(fwd, up, yaw_deg));
    if (orbit)
        c->eye = v3_sub(c->target, v3_scale(fwd, dist));
    else
        c->target = v3_add(c->eye, v3_scale(fwd, dist));
}

void camera_move(struct camera *c, double forward, double right, double up, int orbit)
{
    vec3 f = v3_norm(v3_sub(c->target, c->eye));
    vec3 r = v3_norm(v3_cross(f, c->up));
    vec3 u = v3_norm(c->up);
    if (orbit) {
        double dist = camera_distance(c);
        double nd = fmax(dist - forward, 1e-3 * dist);
        vec3 shift = v3_add(v3_scale(r, right), v3_scale(u, up));
        c->target = v3_add(c->target, shift);
        c->eye = v3_sub(c->target, v3_scale(f, nd));
        return;
    }
    vec3 d = v3_add(v3_add(v3_scale(f, forward), v3_scale(r, right)), v3_scale(u, up));
    c->eye = v3_add(c->eye, d);
    c->target = v3_add(c->target, d);
}

void camera_pan(struct camera *c, double right, double up)
{
    vec3 f = v3_norm(v3_sub(c->target, c->eye));
    vec3 r = v3_norm(v3_cross(f, c->up));
    vec3 u = v3_cross(r, f); /* unit: r and f are unit and perpendicular */
    vec3 d = v3_add(v3_scale(r, right), v3_scale(u, up));
    c->eye = v3_add(c->eye, d);
    c->target = v3_add(c->target, d);
}
