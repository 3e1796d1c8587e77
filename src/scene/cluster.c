/* cluster.c: spatially compact sets of a mesh's triangles, and its runs by cluster (see
 * cluster.h). */
#include "cluster.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

size_t cluster_bytes(const struct mesh *m)
{
    const struct mesh_clusters *cs = m->clusters;
    if (!cs)
        return 0;
    return sizeof *cs + cs->n * sizeof *cs->c;
}

/* the unit face normal of triangle t (file's winding), false when degenerate: the sine of
 * its corner angle under 1e-6, or not finite */
static bool face_normal(const struct mesh *m, uint32_t t, double n[3])
{
    const float *p0 = m->verts[m->tris[t][0]].pos, *p1 = m->verts[m->tris[t][1]].pos,
                *p2 = m->verts[m->tris[t][2]].pos;
    double a[3], b[3];
    for (int k = 0; k < 3; k++)
        a[k] = (double)p1[k] - p0[k], b[k] = (double)p2[k] - p0[k];
    n[0] = a[1] * b[2] - a[2] * b[1];
    n[1] = a[2] * b[0] - a[0] * b[2];
    n[2] = a[0] * b[1] - a[1] * b[0];
    double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    double la = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    double lb = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
    if (!isfinite(len) || !(len > 1e-6 * la * lb))
        return false;
    for (int k = 0; k < 3; k++)
        n[k] /= len;
    return true;
}

/* the oriented box of the corners of tri[0 .. n) on axes ax (rows; near orthonormal):
 * centre and half sizes such that every corner is inside in exact arithmetic */
static void oriented_box(const struct mesh *m, const uint32_t *tri, uint32_t n,
                         float ax[3][3], float center[3], float half[3])
{
    /* coordinates on the float axes: the inverse of the matrix of rows ax, in double */
    double a[3][3], inv[3][3];
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++)
            a[r][c] = ax[r][c];
    /* (columns of inv: ax's rows are the columns of a's transpose) */
    double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
                 a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                 a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    /* p - o = sum_i s_i ax[i]  =>  s = (A^T)^-1 (p - o) */
    double t[3][3];
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++)
            t[r][c] = a[c][r];
    inv[0][0] = (t[1][1] * t[2][2] - t[1][2] * t[2][1]) / det;
    inv[0][1] = (t[0][2] * t[2][1] - t[0][1] * t[2][2]) / det;
    inv[0][2] = (t[0][1] * t[1][2] - t[0][2] * t[1][1]) / det;
    inv[1][0] = (t[1][2] * t[2][0] - t[1][0] * t[2][2]) / det;
    inv[1][1] = (t[0][0] * t[2][2] - t[0][2] * t[2][0]) / det;
    inv[1][2] = (t[0][2] * t[1][0] - t[0][0] * t[1][2]) / det;
    inv[2][0] = (t[1][0] * t[2][1] - t[1][1] * t[2][0]) / det;
    inv[2][1] = (t[0][1] * t[2][0] - t[0][0] * t[2][1]) / det;
    inv[2][2] = (t[0][0] * t[1][1] - t[0][1] * t[1][0]) / det;
    const float *o = m->verts[m->tris[tri[0]][0]].pos;
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int pass = 0; pass < 2; pass++) {
        for (uint32_t i = 0; i < n; i++)
            for (int k = 0; k < 3; k++) {
                const float *p = m->verts[m->tris[tri[i]][k]].pos;
                double d[3] = {(double)p[0] - o[0], (double)p[1] - o[1], (double)p[2] - o[2]};
                for (int r = 0; r < 3; r++) {
                    double s = inv[r][0] * d[0] + inv[r][1] * d[1] + inv[r][2] * d[2];
                    if (pass == 0) {
                        lo[r] = s < lo[r] ? s : lo[r];
                        hi[r] = s > hi[r] ? s : hi[r];
                    } else {
                        s = fabs(s);
                        hi[r] = s > hi[r] ? s : hi[r];
                    }
                }
            }
        if (pass == 0) { /* the centre, in float; then the half sizes around it */
            double c[3];
            for (int k = 0; k < 3; k++)
                c[k] = o[k];
            for (int r = 0; r < 3; r++)
                for (int k = 0; k < 3; k++)
                    c[k] += 0.5 * (lo[r] + hi[r]) * a[r][k];
            for (int k = 0; k < 3; k++)
                center[k] = (float)c[k];
            o = center;
            for (int r = 0; r < 3; r++)
                hi[r] = 0;
        }
    }
    for (int r = 0; r < 3; r++) { /* widened for the rounding of the tests that use it */
        double h = hi[r] * (1 + 1e-6) + 1e-30;
        half[r] = (float)h;
        if ((double)half[r] < h)
            half[r] = nextafterf(half[r], INFINITY);
    }
}

/* axes for a patch with mean normal nrm (unit, or 0: the world's): the normal, and in its
 * plane the direction the corners spread most along and the one across it */
static void patch_axes(const struct mesh *m, const uint32_t *tri, uint32_t n, const double nrm[3],
                       float ax[3][3])
{
    double z[3] = {nrm[0], nrm[1], nrm[2]};
    if (!(z[0] * z[0] + z[1] * z[1] + z[2] * z[2] > 0.5)) {
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++)
                ax[r][c] = r == c;
        return;
    }
    /* any u perpendicular to z, v = z x u */
    double u[3] = {0, 0, 0};
    int k = fabs(z[0]) < fabs(z[1]) ? (fabs(z[0]) < fabs(z[2]) ? 0 : 2) : (fabs(z[1]) < fabs(z[2]) ? 1 : 2);
    u[k] = 1;
    double d = u[0] * z[0] + u[1] * z[1] + u[2] * z[2];
    for (int i = 0; i < 3; i++)
        u[i] -= d * z[i];
    double l = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    for (int i = 0; i < 3; i++)
        u[i] /= l;
    double v[3] = {z[1] * u[2] - z[2] * u[1], z[2] * u[0] - z[0] * u[2], z[0] * u[1] - z[1] * u[0]};
    /* the corners' spread in (u, v): its main direction */
    double su = 0, sv = 0, suu = 0, svv = 0, suv = 0, cnt = 0;
    for (uint32_t i = 0; i < n; i++)
        for (int c = 0; c < 3; c++) {
            const float *p = m->verts[m->tris[tri[i]][c]].pos;
            double pu = p[0] * u[0] + p[1] * u[1] + p[2] * u[2];
            double pv = p[0] * v[0] + p[1] * v[1] + p[2] * v[2];
            su += pu, sv += pv, suu += pu * pu, svv += pv * pv, suv += pu * pv, cnt++;
        }
    double cuu = suu / cnt - (su / cnt) * (su / cnt), cvv = svv / cnt - (sv / cnt) * (sv / cnt);
    double cuv = suv / cnt - (su / cnt) * (sv / cnt);
    double th = 0.5 * atan2(2 * cuv, cuu - cvv);
    double cs = cos(th), sn = sin(th);
    for (int i = 0; i < 3; i++) {
        ax[0][i] = (float)(cs * u[i] + sn * v[i]);
        ax[1][i] = (float)(-sn * u[i] + cs * v[i]);
        ax[2][i] = (float)z[i];
    }
}

/* bounds, cone and flags of the cluster of triangles tri[0 .. n) */
void cluster_bounds(const struct mesh *m, const uint32_t *tri, uint32_t n, struct mesh_cluster *c)
{
    bool finite = true, cone = true, one_sided = true;
    double axis[3] = {0, 0, 0}, sum[3] = {0, 0, 0};
    for (uint32_t i = 0; i < n; i++) {
        const uint32_t t = tri[i];
        for (int k = 0; k < 3; k++) {
            const float *p = m->verts[m->tris[t][k]].pos;
            for (int a = 0; a < 3; a++)
                finite &= isfinite(p[a]) != 0;
        }
        double nn[3];
        if (face_normal(m, t, nn)) {
            for (int a = 0; a < 3; a++)
                sum[a] += nn[a];
        } else {
            cone = false;
        }
        one_sided &= m->materials[m->tri_material[t]].sides == MAT_ONE_SIDED;
    }
    c->flags = (finite ? 0 : CLUSTER_NO_BOUNDS) | (one_sided ? CLUSTER_ONE_SIDED : 0);
    double len = sqrt(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]);
    if (len > 1e-9)
        for (int a = 0; a < 3; a++)
            axis[a] = sum[a] / len;
    if (finite) {
        patch_axes(m, tri, n, axis, c->axis);
        oriented_box(m, tri, n, c->axis, c->center, c->half);
    }
    double cmin = 1;
    if (cone && len > 1e-9) {
        for (uint32_t i = 0; i < n; i++) {
            double nn[3];
            face_normal(m, tri[i], nn);
            double d = nn[0] * axis[0] + nn[1] * axis[1] + nn[2] * axis[2];
            cmin = d < cmin ? d : cmin;
        }
    }
    if (!cone || !(len > 1e-9) || !(cmin >= CLUSTER_MIN_CONE_COS)) {
        c->flags |= CLUSTER_NO_CONE;
        cmin = 2;
    }
    for (int a = 0; a < 3; a++)
        c->cone_axis[a] = (float)axis[a];
    /* (rounded down: the float cone holds every normal the double one did; the axis's own
     * rounding is far inside the culling test's margin) */
    c->cone_cos = (float)cmin;
    if ((double)c->cone_cos > cmin)
        c->cone_cos = nextafterf(c->cone_cos, -1.0f);
}

/* 10 bits of x spread to every third bit */
static uint32_t spread3(uint32_t x)
{
    x &= 0x3ff;
    x = (x | (x << 16)) & 0x030000ff;
    x = (x | (x << 8)) & 0x0300f00f;
    x = (x | (x << 4)) & 0x030c30c3;
    x = (x | (x << 2)) & 0x09249249;
    return x;
}

uint32_t cluster_morton3(const uint32_t q[3])
{
    return spread3(q[0]) | spread3(q[1]) << 1 | spread3(q[2]) << 2;
}

/* cluster c: triangles first .. first+n-1 (n <= CLUSTER_MAX_TRIS), its bounds and the
 * end of its vertices (v_need is the caller's) */
static void leaf(const struct mesh *m, uint32_t first, uint32_t n, struct mesh_cluster *c)
{
    uint32_t tri[CLUSTER_MAX_TRIS] = {0};
    for (uint32_t k = 0; k < n; k++)
        tri[k] = first + k;
    memset(c, 0, sizeof *c);
    c->tri_first = first;
    c->n_tris = (uint8_t)n;
    cluster_bounds(m, tri, n, c);
    for (uint32_t k = 0; k < n; k++)
        for (int j = 0; j < 3; j++) {
            uint32_t v = m->tris[first + k][j];
            c->v_end = v + 1 > c->v_end ? v + 1 : c->v_end;
        }
}

int cluster_build(struct mesh *m)
{
    mesh_free_clusters(m);
    const uint32_t n = m->n_opaque;
    if (n == 0)
        return 0;
    const uint32_t nl = (n + CLUSTER_MAX_TRIS - 1) / CLUSTER_MAX_TRIS;
    struct mesh_clusters *cs = calloc(1, sizeof *cs);
    if (cs)
        cs->c = malloc((size_t)nl * sizeof *cs->c);
    if (!cs || !cs->c) {
        free(cs);
        return -1;
    }
    /* the clusters: runs of the file's triangles */
    for (uint32_t k = 0; k < nl; k++) {
        uint32_t first = k * CLUSTER_MAX_TRIS, cnt = n - first;
        leaf(m, first, cnt < CLUSTER_MAX_TRIS ? cnt : CLUSTER_MAX_TRIS, &cs->c[k]);
    }
    /* v_need: the least vertex of its triangles and every later cluster's, from the end */
    uint32_t need = UINT32_MAX;
    for (uint32_t k = nl; k-- > 0;) {
        const struct mesh_cluster *c = &cs->c[k];
        for (uint32_t t = c->tri_first; t < c->tri_first + c->n_tris; t++)
            for (int j = 0; j < 3; j++)
                need = m->tris[t][j] < need ? m->tris[t][j] : need;
        cs->c[k].v_need = need;
    }
    cs->n = nl;
    m->clusters = cs;
    return 0;
}
