/* setup.c: viewport, snapping, edge equations, culling, interpolation planes (see setup.h). */
#include "setup.h"

#include <math.h>

static inline int64_t floor_div256(int64_t a)
{
    return a >> SETUP_SUBPIX_BITS; /* arithmetic shift: floor for negatives too */
}

enum setup_result setup_triangle(const struct vertex_out *v0, const struct vertex_out *v1,
                                 const struct vertex_out *v2, int fb_w, int fb_h,
                                 enum cull_mode cull, int n_var, struct setup_tri *t)
{
    const struct vertex_out *v[3] = {v0, v1, v2};
    struct vertex_out tmp[3];
    double wx[3], wy[3], wz[3];
    int64_t X[3], Y[3];
    for (int i = 0; i < 3; i++) {
        if (!v[i]->projected) { /* a vertex made by clipping */
            tmp[i] = *v[i];
            vertex_project(&tmp[i], fb_w, fb_h);
            v[i] = &tmp[i];
        }
        wx[i] = v[i]->win[0], wy[i] = v[i]->win[1], wz[i] = v[i]->win[2];
        X[i] = v[i]->fx, Y[i] = v[i]->fy;
    }
    int64_t area = (X[1] - X[0]) * (Y[2] - Y[0]) - (Y[1] - Y[0]) * (X[2] - X[0]);
    if (area == 0)
        return SETUP_EMPTY;
    t->front = area < 0;
    if ((cull == CULL_BACK && !t->front) || (cull == CULL_FRONT && t->front))
        return SETUP_CULLED;
    int i1 = 1, i2 = 2;
    if (area < 0) { /* make the interior the positive side of every edge */
        i1 = 2, i2 = 1;
        area = -area;
    }
    int idx[3] = {0, i1, i2};

    int64_t minx = X[0], maxx = X[0], miny = Y[0], maxy = Y[0];
    for (int i = 1; i < 3; i++) {
        minx = X[i] < minx ? X[i] : minx;
        maxx = X[i] > maxx ? X[i] : maxx;
        miny = Y[i] < miny ? Y[i] : miny;
        maxy = Y[i] > maxy ? Y[i] : maxy;
    }
    const int64_t half = SETUP_SUBPIX_ONE / 2;
    int64_t px0 = floor_div256(minx - half + SETUP_SUBPIX_ONE - 1);
    int64_t px1 = floor_div256(maxx - half);
    int64_t py0 = floor_div256(miny - half + SETUP_SUBPIX_ONE - 1);
    int64_t py1 = floor_div256(maxy - half);
    px0 = px0 < 0 ? 0 : px0;
    py0 = py0 < 0 ? 0 : py0;
    px1 = px1 > fb_w - 1 ? fb_w - 1 : px1;
    py1 = py1 > fb_h - 1 ? fb_h - 1 : py1;
    if (px0 > px1 || py0 > py1)
        return SETUP_EMPTY;
    t->x0 = (int)px0, t->y0 = (int)py0, t->x1 = (int)px1, t->y1 = (int)py1;

    int64_t cx = px0 * SETUP_SUBPIX_ONE + half, cy = py0 * SETUP_SUBPIX_ONE + half;
    for (int k = 0; k < 3; k++) {
        /* edge k runs from vertex k+1 to vertex k+2 (so it is opposite vertex k) */
        int a = idx[(k + 1) % 3], b = idx[(k + 2) % 3];
        int64_t dx = X[b] - X[a], dy = Y[b] - Y[a];
        int owns = dy < 0 || (dy == 0 && dx < 0);
        t->e[k] = dx * (cy - Y[a]) - dy * (cx - X[a]) - (owns ? 0 : 1);
        t->e_dx[k] = -dy * SETUP_SUBPIX_ONE;
        t->e_dy[k] = dx * SETUP_SUBPIX_ONE;
    }

    /* interpolation: the same edge functions on unsnapped positions, normalised */
    const double *px = wx, *py = wy;
    double sx[3], sy[3];
    double uarea = (px[1] - px[0]) * (py[2] - py[0]) - (py[1] - py[0]) * (px[2] - px[0]);
    if (!(uarea != 0 && (uarea < 0) == t->front)) {
        /* snapping changed the orientation or made it non-degenerate: use snapped positions */
        for (int i = 0; i < 3; i++) {
            sx[i] = (double)X[i] / SETUP_SUBPIX_ONE;
            sy[i] = (double)Y[i] / SETUP_SUBPIX_ONE;
        }
        px = sx, py = sy;
        uarea = (px[1] - px[0]) * (py[2] - py[0]) - (py[1] - py[0]) * (px[2] - px[0]);
    }
    double inv = 1.0 / uarea, ox = px0 + 0.5, oy = py0 + 0.5;
    for (int k = 0; k < 3; k++) {
        int a = (k + 1) % 3, b = (k + 2) % 3; /* original vertex order: the sign is in inv */
        double dx = px[b] - px[a], dy = py[b] - py[a];
        t->lam[k] = (dx * (oy - py[a]) - dy * (ox - px[a])) * inv;
        t->lam_dx[k] = -dy * inv;
        t->lam_dy[k] = dx * inv;
    }
    t->n_var = n_var;
    for (int i = 0; i < 3; i++) {
        t->z[i] = wz[i];
        t->rw[i] = 1.0 / v[i]->clip[3];
        for (int k = 0; k < n_var; k++)
            t->var[i][k] = v[i]->var[k];
    }
    return SETUP_DRAW;
}
