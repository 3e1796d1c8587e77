/* plan_blend.c: the blended pass (see plan_blend.h). */
#include "plan_blend.h"

#include <stdlib.h>
#include <string.h>

#include "frame.h"

struct blended {
    double key; /* view depth: larger is farther */
    int item;
    uint32_t tri;
};

static int farthest_first(const void *a, const void *b)
{
    const struct blended *x = a, *y = b;
    if (x->key != y->key)
        return x->key > y->key ? -1 : 1;
    if (x->item != y->item)
        return x->item < y->item ? -1 : 1;
    return x->tri < y->tri ? -1 : x->tri > y->tri;
}

int plan_blend_draw(struct frontend *fe, struct span_ctx *ctx, const struct kernel_set *ks,
                    const struct draw_item *items, int n_items, const struct camera *cam,
                    const struct render_opts *o, struct fb *fb, mat4 pv,
                    struct frame_stats *stats, struct err *e)
{
    size_t n = 0;
    for (int it = 0; it < n_items; it++)
        n += items[it].mesh->n_tris - items[it].mesh->n_opaque;
    if (n == 0 || o->shade == SHADE_WIRE)
        return 0;
    struct blended *b = malloc(n * sizeof *b);
    uint32_t(*tris)[3] = malloc(n * sizeof *tris);
    uint16_t *mats = malloc(n * sizeof *mats);
    if (!b || !tris || !mats) {
        free(b);
        free(tris);
        free(mats);
        return err_set(e, "out of memory for %zu blended triangles", n);
    }
    const bool ortho = cam->ortho_height > 0;
    size_t k = 0;
    for (int it = 0; it < n_items; it++) {
        const struct mesh *m = items[it].mesh;
        mat4 mvp = m4_mul(pv, items[it].model);
        for (uint32_t t = m->n_opaque; t < m->n_tris; t++) {
            double c[3] = {0, 0, 0};
            for (int v = 0; v < 3; v++)
                for (int a = 0; a < 3; a++)
                    c[a] += m->verts[m->tris[t][v]].pos[a] / 3.0;
            int row = ortho ? 2 : 3;
            double d = mvp.m[row][0] * c[0] + mvp.m[row][1] * c[1] + mvp.m[row][2] * c[2] +
                       mvp.m[row][3];
            b[k++] = (struct blended){d, it, t};
        }
    }
    qsort(b, n, sizeof *b, farthest_first);
    struct frame *f = malloc(sizeof *f); /* ~11 KB: off the stack, as plan_tiles' */
    if (!f) {
        free(b);
        free(tris);
        free(mats);
        return err_set(e, "out of memory for a frame");
    }
    frame_init(f, cam, o, ks, fb, stats);
    frontend_begin(fe, f, NULL, ctx, 1);
    int rc = 0;
    /* each item's vertices once, then its triangles run by run in the sorted order */
    struct vertex_out *vo[SCENE_MAX_ITEMS] = {NULL};
    for (int it = 0; it < n_items && rc == 0; it++) {
        const struct mesh *m = items[it].mesh;
        if (m->n_opaque == m->n_tris)
            continue;
        if (!(vo[it] = frontend_item_verts(fe, it, m->n_verts, e))) {
            rc = -1;
            break;
        }
        frame_item(f, &items[it], pv);
        f->k->vertex_run(m, &f->u, vo[it], 0, m->n_verts);
    }
    for (size_t i = 0; i < n && rc == 0;) {
        const int it = b[i].item;
        const struct mesh *m = items[it].mesh;
        size_t j = i;
        for (; j < n && b[j].item == it; j++) {
            memcpy(tris[j - i], m->tris[b[j].tri], sizeof tris[0]);
            mats[j - i] = m->tri_material[b[j].tri];
        }
        struct mesh run = *m; /* the item's mesh with these triangles alone */
        run.tris = tris;
        run.tri_material = mats;
        run.n_tris = run.n_opaque = (uint32_t)(j - i);
        run.clusters = NULL; /* (the mesh's are of its own order) */
        frame_item(f, &items[it], pv);
        rc = frontend_triangles(fe, f, &items[it], &run, vo[it], false, 0, run.n_tris,
                                m->n_verts, e);
        i = j;
    }
    if (rc == 0)
        rc = frontend_finish(fe, f, e);
    else
        frontend_abandon(fe, f);
    free(f);
    stats->pixels_tested += ctx->tested;
    stats->pixels_shaded += ctx->shaded;
    free(b);
    free(tris);
    free(mats);
    return rc;
}
