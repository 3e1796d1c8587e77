/* vecmath.h: the small linear algebra every stage shares.
 *
 * Types are plain values: vec3/vec4 and column-vector 4x4 matrices, m[row][col], so a point
 * transforms as p' = M * p and transforms compose right to left (clip = P * V * M * p).
 * Everything on the CPU side of the vertex stage is double: clip-space positions then carry
 * ~1e-16 relative error, far below the 1/256-pixel snap, so vertex positions round to the
 * same fixed-point value any exact renderer would produce (see setup.h).
 *
 * Conventions (OpenGL): right-handed world, camera looks down -Z, vertical fov in degrees,
 * NDC in [-1,1]^3, window depth = 0.5 * z_ndc + 0.5. */
#ifndef RASTTY_VECMATH_H
#define RASTTY_VECMATH_H

#include <math.h>

typedef struct { double x, y, z; } vec3;
typedef struct { double x, y, z, w; } vec4;
typedef struct { double m[4][4]; } mat4;

static inline vec3 v3(double x, double y, double z) { return (vec3){x, y, z}; }
static inline vec3 v3_add(vec3 a, vec3 b) { return (vec3){a.x + b.x, a.y + b.y, a.z + b.z}; }
static inline vec3 v3_sub(vec3 a, vec3 b) { return (vec3){a.x - b.x, a.y - b.y, a.z - b.z}; }
static inline vec3 v3_scale(vec3 a, double s) { return (vec3){a.x * s, a.y * s, a.z * s}; }
static inline double v3_dot(vec3 a, vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline double v3_len(vec3 a) { return sqrt(v3_dot(a, a)); }
static inline vec3 v3_cross(vec3 a, vec3 b)
{
    return (vec3){a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
/* Unit vector along a; the zero vector stays zero (callers treat it as "no direction"). */
static inline vec3 v3_norm(vec3 a)
{
    double l = v3_len(a);
    return l > 0 ? v3_scale(a, 1.0 / l) : a;
}

mat4 m4_identity(void);
mat4 m4_mul(mat4 a, mat4 b);
static inline vec4 m4_mul_v4(mat4 a, vec4 v)
{
    return (vec4){a.m[0][0] * v.x + a.m[0][1] * v.y + a.m[0][2] * v.z + a.m[0][3] * v.w,
                  a.m[1][0] * v.x + a.m[1][1] * v.y + a.m[1][2] * v.z + a.m[1][3] * v.w,
                  a.m[2][0] * v.x + a.m[2][1] * v.y + a.m[2][2] * v.z + a.m[2][3] * v.w,
                  a.m[3][0] * v.x + a.m[3][1] * v.y + a.m[3][2] * v.z + a.m[3][3] * v.w};
}
/* w = 1, no divide */
static inline vec3 m4_mul_point(mat4 a, vec3 p)
{
    vec4 r = m4_mul_v4(a, (vec4){p.x, p.y, p.z, 1});
    return (vec3){r.x, r.y, r.z};
}
/* upper 3x3 only */
static inline vec3 m4_mul_dir(mat4 a, vec3 d)
{
    vec4 r = m4_mul_v4(a, (vec4){d.x, d.y, d.z, 0});
    return (vec3){r.x, r.y, r.z};
}
mat4 m4_translate(vec3 t);
mat4 m4_scale(vec3 s);
mat4 m4_rotate(vec3 axis, double deg); /* right-handed: counter-clockwise looking down -axis */

/* View matrix: eye at the origin looking down -Z, `up` projected to +Y. Returns identity
 * rotation if eye == target or up is parallel to the view direction (caller validates). */
mat4 m4_lookat(vec3 eye, vec3 target, vec3 up);
/* glFrustum-style perspective; fovy in degrees, aspect = width / height. */
mat4 m4_perspective(double fovy_deg, double aspect, double near, double far);
/* glOrtho-style; the view volume is `height` tall (width = height * aspect), centred. */
mat4 m4_ortho(double height, double aspect, double near, double far);
/* Inverse-transpose of the upper 3x3 (the normal matrix), in the upper 3x3 of the result.
 * A singular matrix yields all zeros. */
mat4 m4_normal_matrix(mat4 model);

#endif
