/* vecmath.c: matrices (see vecmath.h for conventions). */
#include "vecmath.h"

mat4 m4_identity(void)
{
    mat4 r = {{{0}}};
    for (int i = 0; i < 4; i++)
        r.m[i][i] = 1;
    return r;
}

mat4 m4_mul(mat4 a, mat4 b)
{
    mat4 r;
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            r.m[i][j] = a.m[i][0] * b.m[0][j] + a.m[i][1] * b.m[1][j] + a.m[i][2] * b.m[2][j] +
                        a.m[i][3] * b.m[3][j];
    return r;
}

mat4 m4_translate(vec3 t)
{
    mat4 r = m4_identity();
    r.m[0][3] = t.x;
    r.m[1][3] = t.y;
    r.m[2][3] = t.z;
    return r;
}

mat4 m4_scale(vec3 s)
{
    mat4 r = m4_identity();
    r.m[0][0] = s.x;
    r.m[1][1] = s.y;
    r.m[2][2] = s.z;
    return r;
}

mat4 m4_rotate(vec3 axis, double deg)
{
    vec3 a = v3_norm(axis);
    double rad = deg * (M_PI / 180.0), c = cos(rad), s = sin(rad), t = 1 - c;
    mat4 r = m4_identity();
    r.m[0][0] = t * a.x * a.x + c;
    r.m[0][1] = t * a.x * a.y - s * a.z;
    r.m[0][2] = t * a.x * a.z + s * a.y;
    r.m[1][0] = t * a.x * a.y + s * a.z;
    r.m[1][1] = t * a.y * a.y + c;
    r.m[1][2] = t * a.y * a.z - s * a.x;
    r.m[2][0] = t * a.x * a.z - s * a.y;
    r.m[2][1] = t * a.y * a.z + s * a.x;
    r.m[2][2] = t * a.z * a.z + c;
    return r;
}

mat4 m4_lookat(vec3 eye, vec3 target, vec3 up)
{
    vec3 f = v3_norm(v3_sub(target, eye));
    vec3 s = v3_norm(v3_cross(f, up));
    vec3 u = v3_cross(s, f);
    mat4 r = m4_identity();
    if (v3_len(f) == 0 || v3_len(s) == 0)
        return m4_translate(v3_scale(eye, -1));
    r.m[0][0] = s.x, r.m[0][1] = s.y, r.m[0][2] = s.z;
    r.m[1][0] = u.x, r.m[1][1] = u.y, r.m[1][2] = u.z;
    r.m[2][0] = -f.x, r.m[2][1] = -f.y, r.m[2][2] = -f.z;
    r.m[0][3] = -v3_dot(s, eye);
    r.m[1][3] = -v3_dot(u, eye);
    r.m[2][3] = v3_dot(f, eye);
    return r;
}

mat4 m4_perspective(double fovy_deg, double aspect, double near, double far)
{
    double f = 1.0 / tan(fovy_deg * (M_PI / 360.0));
    mat4 r = {{{0}}};
    r.m[0][0] = f / aspect;
    r.m[1][1] = f;
    r.m[2][2] = (far + near) / (near - far);
    r.m[2][3] = 2.0 * far * near / (near - far);
    r.m[3][2] = -1;
    return r;
}

mat4 m4_ortho(double height, double aspect, double near, double far)
{
    mat4 r = m4_identity();
    r.m[0][0] = 2.0 / (height * aspect);
    r.m[1][1] = 2.0 / height;
    r.m[2][2] = -2.0 / (far - near);
    r.m[2][3] = -(far + near) / (far - near);
    return r;
}

mat4 m4_normal_matrix(mat4 a)
{
    /* inverse-transpose of the 3x3 = cofactor matrix / determinant */
    double (*m)[4] = a.m;
    double c00 = m[1][1] * m[2][2] - m[1][2] * m[2][1];
    double c01 = m[1][2] * m[2][0] - m[1][0] * m[2][2];
    double c02 = m[1][0] * m[2][1] - m[1][1] * m[2][0];
    double c10 = m[0][2] * m[2][1] - m[0][1] * m[2][2];
    double c11 = m[0][0] * m[2][2] - m[0][2] * m[2][0];
    double c12 = m[0][1] * m[2][0] - m[0][0] * m[2][1];
    double c20 = m[0][1] * m[1][2] - m[0][2] * m[1][1];
    double c21 = m[0][2] * m[1][0] - m[0][0] * m[1][2];
    double c22 = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    double det = m[0][0] * c00 + m[0][1] * c01 + m[0][2] * c02;
    mat4 r = {{{0}}};
    if (det == 0)
        return r;
    double inv = 1.0 / det;
    r.m[0][0] = c00 * inv, r.m[0][1] = c01 * inv, r.m[0][2] = c02 * inv;
    r.m[1][0] = c10 * inv, r.m[1][1] = c11 * inv, r.m[1][2] = c12 * inv;
    r.m[2][0] = c20 * inv, r.m[2][1] = c21 * inv, r.m[2][2] = c22 * inv;
    r.m[3][3] = 1;
    return r;
}
