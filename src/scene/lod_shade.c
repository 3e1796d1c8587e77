/* lod_shade.c: a level's shading error (lod.h's lod_shade_error) — how far the normals a
 * level interpolates turn from the source's, measured at a sample of the source's vertices
 * on the level's surface, each weighted by how far it moves its material's colour
 * (lod_shade_weight). */
#include "lod.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vecmath.h"

/* the source's vertices sampled (at most; every vertex of a smaller mesh) */
#define SHADE_SAMPLES 2048

static vec3 at(const float *p)
{
    return v3(p[0], p[1], p[2]);
}

/* the point of triangle abc closest to p, as barycentrics bc; its squared distance (the
 * Voronoi-region walk of Ericson's Real-Time Collision Detection, 5.1.5) */
static double closest(vec3 p, vec3 a, vec3 b, vec3 c, double bc[3])
{
    vec3 ab = v3_sub(b, a), ac = v3_sub(c, a), ap = v3_sub(p, a), bp = v3_sub(p, b),
         cp = v3_sub(p, c);
    double d1 = v3_dot(ab, ap), d2 = v3_dot(ac, ap), d3 = v3_dot(ab, bp), d4 = v3_dot(ac, bp);
    double d5 = v3_dot(ab, cp), d6 = v3_dot(ac, cp);
    double va = d3 * d6 - d5 * d4, vb = d5 * d2 - d1 * d6, vc = d1 * d4 - d3 * d2;
    if (d1 <= 0 && d2 <= 0)
        bc[0] = 1, bc[1] = 0, bc[2] = 0;
    else if (d3 >= 0 && d4 <= d3)
        bc[0] = 0, bc[1] = 1, bc[2] = 0;
    else if (d6 >= 0 && d5 <= d6)
        bc[0] = 0, bc[1] = 0, bc[2] = 1;
    else if (vc <= 0 && d1 >= 0 && d3 <= 0)
        bc[1] = d1 / (d1 - d3), bc[0] = 1 - bc[1], bc[2] = 0;
    else if (vb <= 0 && d2 >= 0 && d6 <= 0)
        bc[2] = d2 / (d2 - d6), bc[0] = 1 - bc[2], bc[1] = 0;
    else if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0)
        bc[2] = (d4 - d3) / ((d4 - d3) + (d5 - d6)), bc[1] = 1 - bc[2], bc[0] = 0;
    else {
        double s = va + vb + vc;
        bc[1] = s > 0 ? vb / s : 1.0 / 3, bc[2] = s > 0 ? vc / s : 1.0 / 3;
        bc[0] = 1 - bc[1] - bc[2];
    }
    vec3 q = v3_sub(v3_add(v3_add(v3_scale(a, bc[0]), v3_scale(b, bc[1])), v3_scale(c, bc[2])), p);
    return v3_dot(q, q);
}

/* a uniform grid over the source's box, each cell listing the level's triangles whose box
 * meets it */
struct grid {
    double lo[3], cell;
    int n[3];
    uint32_t *start; /* cells + 1 */
    uint32_t *list;
};

static int cell_of(const struct grid *g, double v, int axis)
{
    double c = floor((v - g->lo[axis]) / g->cell);
    return c < 0 ? 0 : c >= g->n[axis] ? g->n[axis] - 1 : (int)c;
}

static size_t cell_index(const struct grid *g, int x, int y, int z)
{
    return ((size_t)z * (size_t)g->n[1] + (size_t)y) * (size_t)g->n[0] + (size_t)x;
}

/* the cells triangle t's box meets: lo[3], hi[3] */
static void tri_cells(const struct grid *g, const struct mesh *l, uint32_t t, int lo[3], int hi[3])
{
    for (int i = 0; i < 3; i++) {
        float mn = l->verts[l->tris[t][0]].pos[i], mx = mn;
        for (int k = 1; k < 3; k++) {
            float v = l->verts[l->tris[t][k]].pos[i];
            mn = v < mn ? v : mn, mx = v > mx ? v : mx;
        }
        lo[i] = cell_of(g, mn, i), hi[i] = cell_of(g, mx, i);
    }
}

/* -1: out of memory; 1: too many entries for this resolution (a coarser one is tried) */
static int grid_build(struct grid *g, const struct mesh *src, const struct mesh *l, int res)
{
    double ext = 0;
    for (int i = 0; i < 3; i++) {
        g->lo[i] = src->bbox_min[i];
        ext = fmax(ext, (double)src->bbox_max[i] - src->bbox_min[i]);
    }
    g->cell = ext > 0 ? ext / res * (1 + 1e-6) : 1;
    for (int i = 0; i < 3; i++) {
        double n = ceil(((double)src->bbox_max[i] - src->bbox_min[i]) / g->cell);
        g->n[i] = n < 1 ? 1 : n > res ? res : (int)n;
    }
    size_t cells = (size_t)g->n[0] * (size_t)g->n[1] * (size_t)g->n[2];
    g->start = calloc(cells + 1, sizeof *g->start);
    if (!g->start)
        return -1;
    size_t total = 0, cap = 16 * (size_t)l->n_tris + (1u << 20);
    for (uint32_t t = 0; t < l->n_tris; t++) {
        int lo[3], hi[3];
        tri_cells(g, l, t, lo, hi);
        total += (size_t)(hi[0] - lo[0] + 1) * (size_t)(hi[1] - lo[1] + 1) * (size_t)(hi[2] - lo[2] + 1);
        if (total > cap || total >= UINT32_MAX) {
            free(g->start);
            return 1;
        }
        for (int z = lo[2]; z <= hi[2]; z++)
            for (int y = lo[1]; y <= hi[1]; y++)
                for (int x = lo[0]; x <= hi[0]; x++)
                    g->start[cell_index(g, x, y, z) + 1]++;
    }
    for (size_t c = 0; c < cells; c++)
        g->start[c + 1] += g->start[c];
    g->list = malloc((total ? total : 1) * sizeof *g->list);
    uint32_t *fill = malloc(cells * sizeof *fill);
    if (!g->list || !fill) {
        free(g->start);
        free(g->list);
        free(fill);
        return -1;
    }
    memcpy(fill, g->start, cells * sizeof *fill);
    for (uint32_t t = 0; t < l->n_tris; t++) {
        int lo[3], hi[3];
        tri_cells(g, l, t, lo, hi);
        for (int z = lo[2]; z <= hi[2]; z++)
            for (int y = lo[1]; y <= hi[1]; y++)
                for (int x = lo[0]; x <= hi[0]; x++)
                    g->list[fill[cell_index(g, x, y, z)]++] = t;
    }
    free(fill);
    return 0;
}

/* the cosine between n (unit) and the level's normal at the point of its surface nearest p
 * (cells up to two rings around p's; where several triangles are as near — an edge, a
 * crease — the normal nearest n: the side p belongs to); -2 when no triangle is that near */
static double nearest_cos(const struct grid *g, const struct mesh *l, const float *p, const float *n)
{
    int c[3] = {cell_of(g, p[0], 0), cell_of(g, p[1], 1), cell_of(g, p[2], 2)};
    /* how far p lies inside its cell: ring r's cells are at least margin + (r - 1) cells away */
    double margin = INFINITY;
    for (int i = 0; i < 3; i++) {
        double lo = g->lo[i] + c[i] * g->cell, in = fmin(p[i] - lo, lo + g->cell - p[i]);
        margin = fmin(margin, fmax(in, 0));
    }
    double best = INFINITY, best_cos = -2;
    const double tol = 1e-12 * g->cell * g->cell;
    for (int r = 0; r <= 2; r++) {
        /* ring r is only worth it if its cells can hold something nearer than the best */
        double reach = r == 0 ? 0 : margin + (r - 1) * g->cell;
        if (r > 0 && best <= reach * reach)
            break;
        for (int z = c[2] - r; z <= c[2] + r; z++)
            for (int y = c[1] - r; y <= c[1] + r; y++)
                for (int x = c[0] - r; x <= c[0] + r; x++) {
                    if (x < 0 || y < 0 || z < 0 || x >= g->n[0] || y >= g->n[1] || z >= g->n[2])
                        continue;
                    if (abs(x - c[0]) != r && abs(y - c[1]) != r && abs(z - c[2]) != r)
                        continue; /* (an inner ring's) */
                    size_t ci = cell_index(g, x, y, z);
                    for (uint32_t k = g->start[ci]; k < g->start[ci + 1]; k++) {
                        const uint32_t *tv = l->tris[g->list[k]];
                        double bc[3];
                        double d = closest(at(p), at(l->verts[tv[0]].pos), at(l->verts[tv[1]].pos),
                                           at(l->verts[tv[2]].pos), bc);
                        if (d > best + tol)
                            continue;
                        vec3 in = v3(0, 0, 0);
                        for (int j = 0; j < 3; j++)
                            in = v3_add(in, v3_scale(at(l->verts[tv[j]].nrm), bc[j]));
                        double len = v3_len(in);
                        double cs = len > 0 ? v3_dot(in, at(n)) / len : -1;
                        if (d < best - tol || cs > best_cos)
                            best_cos = cs;
                        best = d < best ? d : best;
                    }
                }
    }
    return best_cos;
}

/* light.h's LIGHT_DIFFUSE and LIGHT_DEFAULT_ALBEDO (the render layer's, which scene cannot
 * include: tests/unit/test_lod.c checks they agree) */
#define SHADE_DIFFUSE 0.9
#define SHADE_ALBEDO 0.8

/* Material mt's slope and range (lod_shade_weight): how far its lit colour moves per radian
 * a normal turns, as a root mean square over the directions the normal may face (the
 * diffuse term LIGHT_DIFFUSE kd sin: (LIGHT_DIFFUSE kd)^2 2/3; the highlight ks cos^ns: about
 * ks^2 / 2 at any ns, a steep slope over a small cap), and the most it can move at all,
 * LIGHT_DIFFUSE kd + ks (albedo and ks: their largest channel) */
static void shade_terms(const struct mesh *m, uint32_t mt, double *slope, double *range)
{
    const struct material *a = &m->materials[mt];
    double kd = 0, ks = 0;
    for (int c = 0; c < 3; c++) {
        kd = fmax(kd, a->implicit ? (a->texture >= 0 || m->colors ? 1 : SHADE_ALBEDO) : a->kd[c]);
        ks = fmax(ks, a->ks[c]);
    }
    *slope = sqrt(SHADE_DIFFUSE * kd * SHADE_DIFFUSE * kd * (2.0 / 3) + ks * ks / 2);
    *range = SHADE_DIFFUSE * kd + ks;
}

/* the slope of the material LOD_SHADE_BOUND was measured on (albedo 0.8, no highlight:
 * test_lod.c's bumpy sphere) */
static double ref_slope(void)
{
    return SHADE_DIFFUSE * SHADE_ALBEDO * sqrt(2.0 / 3);
}

double lod_shade_weight(const struct mesh *m, uint32_t mt)
{
    if (m->materials[mt].features)
        return 1;
    double slope, range;
    shade_terms(m, mt, &slope, &range);
    return fmin(1, slope / ref_slope());
}

/* An angle error a (radians) at a vertex of material mt, as the angle of the measured
 * material that moves its colour as far: a itself for a material as lively as that one or
 * more (counted as the bound was measured), else a x lod_shade_weight, but no more than the
 * angle that moves that material's colour by all the duller one's can move (its range): the
 * car's brake discs (weight 0.088) count 0.088 a up to 0.14 rad. */
static double weighted_angle(const struct mesh *m, uint32_t mt, double a)
{
    if (m->materials[mt].features)
        return a;
    double slope, range;
    shade_terms(m, mt, &slope, &range);
    const double w = slope / ref_slope(); /* (lod_shade_weight's, before its cap at 1) */
    return w >= 1 ? a : fmin(a * w, range / ref_slope());
}

double lod_shade_error(const struct mesh *src, const struct mesh *lvl)
{
    if (!src->n_verts || !lvl->n_tris)
        return 0;
    struct grid g;
    int res = 2 * (int)cbrt((double)lvl->n_tris) + 1, rc; /* (a few triangles a cell) */
    res = res > 128 ? 128 : res;
    while ((rc = grid_build(&g, src, lvl, res)) == 1 && res > 1)
        res /= 2;
    if (rc)
        return -1;
    double sum = 0;
    uint32_t n = src->n_verts < SHADE_SAMPLES ? src->n_verts : SHADE_SAMPLES, used = 0;
    for (uint32_t s = 0; s < n; s++) {
        /* one vertex from each of n equal strata of the vertex array, at a scrambled place
         * in it (not in step with a grid's rows) */
        uint64_t lo = (uint64_t)s * src->n_verts / n, hi = (uint64_t)(s + 1) * src->n_verts / n;
        uint32_t v = (uint32_t)(lo + (hi > lo ? (s * 2654435761u) % (hi - lo) : 0));
        double cs = nearest_cos(&g, lvl, src->verts[v].pos, src->verts[v].nrm);
        if (cs < -1.5)
            continue;
        /* (the angle weighted by how far it moves this vertex's colour) */
        double a = weighted_angle(src, src->vert_material[v], acos(cs > 1 ? 1 : cs < -1 ? -1 : cs));
        sum += a * a;
        used++;
    }
    free(g.start);
    free(g.list);
    return used ? sqrt(sum / used) : 0;
}
