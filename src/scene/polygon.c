/* polygon.c: fans for convex polygons, ear clipping for the rest (see polygon.h). */
#include "polygon.h"

#include <math.h>
#include <stdbool.h>
#include <stddef.h>

struct p2 {
    double x, y;
};

/* twice the signed area of (a, b, c) */
static double cross3(struct p2 a, struct p2 b, struct p2 c)
{
    return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

static bool same(struct p2 a, struct p2 b)
{
    return a.x == b.x && a.y == b.y;
}

/* p inside or on the triangle (a, b, c) of orientation s (+1 / -1) */
static bool inside(struct p2 p, struct p2 a, struct p2 b, struct p2 c, double s)
{
    return s * cross3(a, b, p) >= 0 && s * cross3(b, c, p) >= 0 && s * cross3(c, a, p) >= 0;
}

static void fan(uint32_t n, uint32_t (*out)[3])
{
    for (uint32_t i = 1; i + 1 < n; i++) {
        out[i - 1][0] = 0;
        out[i - 1][1] = i;
        out[i - 1][2] = i + 1;
    }
}

enum polygon_how polygon_triangulate(const float *pos, const uint32_t *idx, uint32_t n,
                                     uint32_t (*out)[3], uint32_t *scratch)
{
    if (n == 3) {
        fan(n, out);
        return POLYGON_FAN;
    }
    /* Newell normal: robust for any planar (or nearly planar) polygon */
    double nx = 0, ny = 0, nz = 0;
    for (uint32_t i = 0; i < n; i++) {
        uint32_t j = i + 1 == n ? 0 : i + 1; /* no division in these loops */
        const float *a = pos + 3 * (size_t)idx[i], *b = pos + 3 * (size_t)idx[j];
        nx += ((double)a[1] - b[1]) * ((double)a[2] + b[2]);
        ny += ((double)a[2] - b[2]) * ((double)a[0] + b[0]);
        nz += ((double)a[0] - b[0]) * ((double)a[1] + b[1]);
    }
    /* drop the axis the normal is most aligned with; keep orientation via the sign */
    int ax = fabs(nx) >= fabs(ny) && fabs(nx) >= fabs(nz) ? 0 : fabs(ny) >= fabs(nz) ? 1 : 2;
    double sign = (ax == 0 ? nx : ax == 1 ? ny : nz) < 0 ? -1 : 1;
    int u = (ax + 1) % 3, v = (ax + 2) % 3;
    if (!(fabs(nx) + fabs(ny) + fabs(nz) > 0) || !isfinite(nx + ny + nz)) {
        fan(n, out); /* no area at all: nothing to decide */
        return POLYGON_FAN;
    }
#define PT(k) ((struct p2){pos[3 * (size_t)idx[k] + u], pos[3 * (size_t)idx[k] + v]})
    /* convex: no turn against the polygon's orientation */
    bool convex = true;
    struct p2 p0 = PT(n - 2), p1 = PT(n - 1);
    for (uint32_t i = 0; i < n && convex; i++) { /* each corner's turn, walking round */
        struct p2 p2 = PT(i);
        convex = sign * cross3(p0, p1, p2) >= 0;
        p0 = p1, p1 = p2;
    }
    if (convex) {
        fan(n, out);
        return POLYGON_FAN;
    }
    if (n > POLYGON_MAX_EAR) {
        fan(n, out);
        return POLYGON_FAN_TOO_BIG;
    }
    uint32_t *prev = scratch, *next = scratch + n;
    for (uint32_t i = 0; i < n; i++) {
        prev[i] = (i + n - 1) % n;
        next[i] = (i + 1) % n;
    }
    uint32_t count = n, i = 0, misses = 0, k = 0;
    while (count > 3) {
        uint32_t a = prev[i], c = next[i];
        struct p2 pa = PT(a), pb = PT(i), pc = PT(c);
        double turn = sign * cross3(pa, pb, pc);
        /* a corner in line with its neighbours covers nothing: clipping it is free */
        bool ear = turn >= 0;
        for (uint32_t j = next[c]; turn > 0 && ear && j != a; j = next[j]) {
            struct p2 pj = PT(j);
            if (!same(pj, pa) && !same(pj, pb) && !same(pj, pc) && inside(pj, pa, pb, pc, sign))
                ear = false;
        }
        if (ear || misses > count) { /* no ear anywhere: clip this corner regardless */
            out[k][0] = a;
            out[k][1] = i;
            out[k][2] = c;
            k++;
            next[a] = c;
            prev[c] = a;
            count--;
            misses = 0;
            i = a; /* the neighbours may have become ears */
        } else {
            i = c;
            misses++;
        }
    }
    out[k][0] = prev[i];
    out[k][1] = i;
    out[k][2] = next[i];
#undef PT
    return POLYGON_EARS;
}
