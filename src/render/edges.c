/* edges.c: a mesh's edges and their triangles (edges.h). */
#include "edges.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

struct at { /* a vertex by its position */
    float p[3];
    uint32_t i;
};

static int by_position(const void *pa, const void *pb)
{
    const struct at *a = pa, *b = pb;
    for (int k = 0; k < 3; k++)
        if (a->p[k] != b->p[k])
            return a->p[k] < b->p[k] ? -1 : 1;
    return 0;
}

struct half {
    uint64_t key; /* welded (low, high) vertex */
    uint32_t tri;
    uint8_t corner;
};

static int by_key(const void *pa, const void *pb)
{
    const struct half *a = pa, *b = pb;
    if (a->key != b->key)
        return a->key < b->key ? -1 : 1;
    return a->tri < b->tri ? -1 : a->tri > b->tri;
}

/* The unit normal of triangle t; false when it has no area. */
static bool face_normal(const struct mesh *m, uint32_t t, double n[3])
{
    const float *a = m->verts[m->tris[t][0]].pos, *b = m->verts[m->tris[t][1]].pos,
                *c = m->verts[m->tris[t][2]].pos;
    double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    n[0] = u[1] * v[2] - u[2] * v[1];
    n[1] = u[2] * v[0] - u[0] * v[2];
    n[2] = u[0] * v[1] - u[1] * v[0];
    double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; k++)
        n[k] = l > 0 ? n[k] / l : 0;
    return l > 0;
}

int edge_table_build(struct edge_table *et, const struct mesh *m, struct err *e)
{
    edge_table_free(et);
    struct at *order = malloc((size_t)m->n_verts * sizeof *order);
    uint32_t *weld = malloc((size_t)m->n_verts * sizeof *weld);
    struct half *h = malloc((size_t)m->n_tris * 3 * sizeof *h);
    et->e = malloc((size_t)m->n_tris * 3 * sizeof *et->e);
    if (!order || !weld || !h || !et->e) {
        free(order), free(weld), free(h);
        edge_table_free(et);
        return err_set(e, "out of memory for the edges of %u triangles", m->n_tris);
    }
    for (uint32_t i = 0; i < m->n_verts; i++) {
        memcpy(order[i].p, m->verts[i].pos, sizeof order[i].p);
        order[i].i = i;
    }
    qsort(order, m->n_verts, sizeof *order, by_position);
    for (uint32_t i = 0; i < m->n_verts; i++) /* each vertex -> the first at its position */
        weld[order[i].i] = i > 0 && by_position(&order[i - 1], &order[i]) == 0
                               ? weld[order[i - 1].i]
                               : order[i].i;
    size_t n = 0;
    for (uint32_t t = 0; t < m->n_tris; t++)
        for (int k = 0; k < 3; k++) {
            uint32_t a = weld[m->tris[t][k]], b = weld[m->tris[t][(k + 1) % 3]];
            if (a == b)
                continue; /* a degenerate corner pair draws nothing */
            uint64_t lo = a < b ? a : b, hi = a < b ? b : a;
            h[n++] = (struct half){lo << 32 | hi, t, (uint8_t)k};
        }
    qsort(h, n, sizeof *h, by_key);
    et->n = 0;
    for (size_t i = 0; i < n;) {
        size_t j = i + 1;
        while (j < n && h[j].key == h[i].key)
            j++;
        for (size_t k = i; k < j; k++) {
            if (j - i == 2 && k == i + 1)
                break; /* the pair's second triangle: recorded with the first */
            uint32_t t = h[k].tri;
            struct edge *ed = &et->e[et->n++];
            ed->v0 = m->tris[t][h[k].corner];
            ed->v1 = m->tris[t][(h[k].corner + 1) % 3];
            ed->t0 = t;
            ed->t1 = j - i == 2 ? h[i + 1].tri : EDGE_NONE;
            ed->crease = false;
            if (ed->t1 != EDGE_NONE) {
                double a[3], b[3];
                ed->crease = face_normal(m, t, a) && face_normal(m, ed->t1, b) &&
                             a[0] * b[0] + a[1] * b[1] + a[2] * b[2] <
                                 cos(EDGE_CREASE_DEG * 3.14159265358979323846 / 180);
            }
        }
        i = j;
    }
    free(order);
    free(weld);
    free(h);
    et->mesh = m;
    et->n_tris = m->n_tris;
    return 0;
}

void edge_table_free(struct edge_table *et)
{
    free(et->e);
    *et = (struct edge_table){0};
}
