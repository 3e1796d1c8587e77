/* cluster_cull.c: dropping whole clusters that cannot reach a pixel (see cluster_cull.h). */
#include "cluster_cull.h"

#include <math.h>

void cluster_view_init(struct cluster_view *v, mat4 model, mat4 mvp, vec3 eye, bool ortho,
                       vec3 view_back, int fb_w, int fb_h, enum cull_mode cull,
                       bool by_material)
{
    v->mvp = mvp;
    v->ortho = ortho;
    v->fb_w = fb_w;
    v->fb_h = fb_h;
    /* object space: the inverse of the model's linear part is the normal matrix transposed */
    mat4 n = m4_normal_matrix(model);
    const double(*a)[4] = model.m;
    double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
                 a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                 a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    double e[3] = {eye.x - a[0][3], eye.y - a[1][3], eye.z - a[2][3]};
    double d[3] = {-view_back.x, -view_back.y, -view_back.z};
    double eo[3], dob[3];
    for (int r = 0; r < 3; r++) {
        eo[r] = n.m[0][r] * e[0] + n.m[1][r] * e[1] + n.m[2][r] * e[2];
        dob[r] = n.m[0][r] * d[0] + n.m[1][r] * d[1] + n.m[2][r] * d[2];
    }
    v->eye = v3(eo[0], eo[1], eo[2]);
    v->dir = v3(dob[0], dob[1], dob[2]);
    /* a mirroring model matrix turns every winding: the face culled turns with it */
    int sign = det > 0 ? 1 : det < 0 ? -1 : 0;
    v->facing = (cull == CULL_BACK ? 1 : cull == CULL_FRONT ? -1 : 0) * sign;
    v->by_material = by_material && sign != 0;
    v->det_sign = sign;
}

/* do all normals of the cone (axis a, unit; cos of its half-angle c) face away from an eye
 * anywhere in the view of the sphere (centre p, radius r)? */
static bool faces_away(const struct cluster_view *v, const float axis[3], float c, double sign,
                       vec3 p, double r)
{
    vec3 ax = v3(sign * axis[0], sign * axis[1], sign * axis[2]);
    vec3 d = v->ortho ? v->dir : v3_sub(p, v->eye);
    double len = v3_len(d);
    if (!(len > 0))
        return false;
    double spread = 0; /* the half-angle under which the sphere is seen */
    if (!v->ortho) {
        if (!(len > r))
            return false;
        spread = asin(r / len);
    }
    double cb = v3_dot(d, ax) / len;
    cb = cb > 1 ? 1 : cb < -1 ? -1 : cb;
    double beta = acos(cb), alpha = acos((double)c);
    return beta + spread + alpha < M_PI / 2 - CLUSTER_FACING_MARGIN;
}

enum cluster_verdict cluster_test(const struct cluster_view *v, const struct mesh_cluster *c,
                                  struct cluster_rect *out)
{
    if (out)
        out->valid = false;
    if (c->flags & CLUSTER_NO_BOUNDS)
        return CLUSTER_DRAW;
    const double(*m)[4] = v->mvp.m;
    double ctr[3] = {c->center[0], c->center[1], c->center[2]};
    /* the box's corners in clip space: centre +- the three half-axes (a linear map) */
    double C[4], A[3][4];
    for (int r = 0; r < 4; r++) {
        C[r] = m[r][0] * ctr[0] + m[r][1] * ctr[1] + m[r][2] * ctr[2] + m[r][3];
        for (int a = 0; a < 3; a++) {
            double h = c->half[a];
            A[a][r] = (m[r][0] * c->axis[a][0] + m[r][1] * c->axis[a][1] +
                       m[r][2] * c->axis[a][2]) * h;
        }
    }
    /* frustum: the largest value over the corners of each plane's w +- coordinate */
    for (int p = 0; p < 6; p++) {
        int row = p / 2;
        double s = (p & 1) ? -1 : 1;
        double val = C[3] + s * C[row], spread = 0, mag = fabs(C[3]) + fabs(C[row]);
        for (int a = 0; a < 3; a++) {
            double t = fabs(A[a][3] + s * A[a][row]);
            spread += t;
            mag += fabs(A[a][3]) + fabs(A[a][row]);
        }
        if (val + spread < -1e-9 * mag)
            return CLUSTER_FRUSTUM;
    }
    /* facing */
    int face = v->facing;
    if (!face && v->by_material && (c->flags & CLUSTER_ONE_SIDED))
        face = v->det_sign; /* (the back, turned by a mirroring model matrix) */
    if (face && !(c->flags & CLUSTER_NO_CONE)) {
        /* (the axes are unit to float rounding: 1e-6 more covers it) */
        double r = (1 + 1e-6) * sqrt((double)c->half[0] * c->half[0] +
                                     (double)c->half[1] * c->half[1] +
                                     (double)c->half[2] * c->half[2]);
        if (faces_away(v, c->cone_axis, c->cone_cos, face, v3(ctr[0], ctr[1], ctr[2]), r))
            return CLUSTER_FACING;
    }
    /* no pixel centre: only for a box wholly in front of the eye */
    double wmin = C[3], wmag = fabs(C[3]);
    for (int a = 0; a < 3; a++)
        wmin -= fabs(A[a][3]), wmag += fabs(A[a][3]);
    if (!(wmin > 1e-9 * wmag))
        return CLUSTER_DRAW;
    /* the eight corners, side by side (the compiler's vectors): corner k takes +A[a] where
     * bit a of k is set, -A[a] where not */
    static const double sg[3][8] = {{-1, 1, -1, 1, -1, 1, -1, 1},
                                    {-1, -1, 1, 1, -1, -1, 1, 1},
                                    {-1, -1, -1, -1, 1, 1, 1, 1}};
    double q[4][8], x[8], y[8], z[8];
    for (int r = 0; r < 4; r++)
        for (int k = 0; k < 8; k++)
            q[r][k] = C[r] + sg[0][k] * A[0][r] + sg[1][k] * A[1][r] + sg[2][k] * A[2][r];
    const double hw = 0.5 * v->fb_w, hh = 0.5 * v->fb_h;
    for (int k = 0; k < 8; k++) {
        double rw = 1.0 / q[3][k];
        x[k] = (q[0][k] * rw + 1.0) * hw;
        y[k] = (1.0 - q[1][k] * rw) * hh;
        z[k] = 0.5 * q[2][k] * rw + 0.5;
    }
    double x0 = x[0], x1 = x[0], y0 = y[0], y1 = y[0], z0 = z[0];
    for (int k = 1; k < 8; k++) {
        x0 = x[k] < x0 ? x[k] : x0, x1 = x[k] > x1 ? x[k] : x1;
        y0 = y[k] < y0 ? y[k] : y0, y1 = y[k] > y1 ? y[k] : y1;
        z0 = z[k] < z0 ? z[k] : z0;
    }
    if (!(x0 <= x1 && y0 <= y1)) /* (not finite) */
        return CLUSTER_DRAW;
    double mx = CLUSTER_SCREEN_MARGIN + 1e-9 * (fabs(x0) + fabs(x1));
    double my = CLUSTER_SCREEN_MARGIN + 1e-9 * (fabs(y0) + fabs(y1));
    /* the first and last pixel centre (k + 0.5) inside, clamped to the framebuffer */
    double px0 = ceil(x0 - mx - 0.5), px1 = floor(x1 + mx - 0.5);
    double py0 = ceil(y0 - my - 0.5), py1 = floor(y1 + my - 0.5);
    px0 = px0 < 0 ? 0 : px0, py0 = py0 < 0 ? 0 : py0;
    px1 = px1 > v->fb_w - 1 ? v->fb_w - 1 : px1, py1 = py1 > v->fb_h - 1 ? v->fb_h - 1 : py1;
    if (px0 > px1 || py0 > py1)
        return CLUSTER_NO_CENTRE;
    if (out) {
        out->x0 = (int)px0, out->y0 = (int)py0, out->x1 = (int)px1, out->y1 = (int)py1;
        /* the least of z/w over the box is at a corner (z/w is monotone along any segment
         * with w > 0): no point of a triangle, nor of a piece clipping makes of it, is
         * nearer; a corner's depth is that in float, rounded to nearest, after the vertex
         * stage's or the clipper's own roundings: 1e-6 below covers them */
        out->z_lo = (float)(z0 - 1e-6 * (1 + fabs(z0)));
        out->valid = true;
    }
    return CLUSTER_DRAW;
}
