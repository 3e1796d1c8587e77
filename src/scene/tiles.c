/* tiles.c: atlas tiles — faces that each map one whole tile of a texture atlas, welded per
 * tile for the simplifiers (see tiles.h). */
#include "tiles.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "order.h"

/* a tile class: a material, the tile its faces map (none: a material without a texture,
 * whose uvs nothing reads) and how, in tile units: t = g pos + c (c modulo 1) */
struct tile_key { /* (compared as bytes: no padding; sorted, a tile's classes together) */
    uint32_t mat;
    float rect[4];    /* u0, v0, du, dv of the tile; du = 0: no texture */
    int32_t cq[2];    /* c, in 1/1024 of the tile */
    uint32_t zero;
    double g[2][3];   /* g, rounded to 10 significant bits (0: under 1e-4 of the largest) */
};
_Static_assert(sizeof(struct tile_key) == 6 * 8 + 8 * 4, "struct tile_key has no padding");
struct tile_class {
    struct tile_key k;
    double c[2];      /* its first face's */
    uint32_t derived; /* its material in the hierarchy's mesh */
};

#define TILE_CQ 1024

/* x rounded to 10 significant bits, 0 when not above tiny */
static double snap(double x, double tiny)
{
    if (!(fabs(x) > tiny))
        return 0;
    int ex;
    double fr = frexp(x, &ex);
    return ldexp(round(ldexp(fr, 10)), ex - 10);
}

/* Can material mt's faces be tile classes: its textures all read uv set 0, untransformed,
 * repeated? *textured: it has one. */
static bool tile_material(const struct material *mt, bool *textured)
{
    const struct tex_slot *sl[] = {&mt->base, &mt->alpha_map, &mt->emissive_map,
                                   &mt->normal_map, &mt->occlusion_map, &mt->spec_map};
    *textured = mt->texture >= 0;
    for (size_t k = 0; k < sizeof sl / sizeof *sl; k++) {
        if (sl[k]->tex < 0)
            continue;
        if (sl[k]->uv != 0 || sl[k]->xform || sl[k]->tile || sl[k]->wrap[0] != TEX_WRAP_REPEAT ||
            sl[k]->wrap[1] != TEX_WRAP_REPEAT)
            return false;
        *textured = true;
    }
    return true;
}

/* triangle t's class (the key fields and the mapping) when it has one: its uvs on the
 * corners of their box (a tile, or half of it cut corner to corner), a plane */
static bool tri_class(const struct mesh *m, uint32_t t, bool textured, struct tile_class *o)
{
    memset(o, 0, sizeof *o);
    o->k.mat = m->tri_material[t];
    if (!textured)
        return true;
    const struct mesh_vertex *v[3] = {&m->verts[m->tris[t][0]], &m->verts[m->tris[t][1]],
                                      &m->verts[m->tris[t][2]]};
    float lo[2], hi[2];
    for (int k = 0; k < 2; k++) {
        lo[k] = fminf(fminf(v[0]->uv[k], v[1]->uv[k]), v[2]->uv[k]);
        hi[k] = fmaxf(fmaxf(v[0]->uv[k], v[1]->uv[k]), v[2]->uv[k]);
        if (!(hi[k] > lo[k]) || !isfinite(lo[k]) || !isfinite(hi[k]))
            return false;
        for (int j = 0; j < 3; j++)
            if (v[j]->uv[k] != lo[k] && v[j]->uv[k] != hi[k])
                return false;
        o->k.rect[k] = lo[k], o->k.rect[2 + k] = hi[k] - lo[k];
    }
    double e1[3], e2[3], n[3], a[3], b[3], nn = 0, len = 0;
    for (int k = 0; k < 3; k++) {
        e1[k] = (double)v[1]->pos[k] - v[0]->pos[k];
        e2[k] = (double)v[2]->pos[k] - v[0]->pos[k];
    }
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    a[0] = e2[1] * n[2] - e2[2] * n[1]; /* e2 x n */
    a[1] = e2[2] * n[0] - e2[0] * n[2];
    a[2] = e2[0] * n[1] - e2[1] * n[0];
    b[0] = n[1] * e1[2] - n[2] * e1[1]; /* n x e1 */
    b[1] = n[2] * e1[0] - n[0] * e1[2];
    b[2] = n[0] * e1[1] - n[1] * e1[0];
    for (int k = 0; k < 3; k++)
        nn += n[k] * n[k], len = fmax(len, fmax(fabs(e1[k]), fabs(e2[k])));
    if (!(nn > 1e-12 * len * len * len * len) || !isfinite(nn))
        return false;
    for (int k = 0; k < 2; k++) {
        const double s = o->k.rect[2 + k], d1 = (v[1]->uv[k] - v[0]->uv[k]) / s,
                     d2 = (v[2]->uv[k] - v[0]->uv[k]) / s;
        double gr[3], big = 0;
        for (int q = 0; q < 3; q++)
            gr[q] = (d1 * a[q] + d2 * b[q]) / nn, big = fmax(big, fabs(gr[q]));
        double c = (v[0]->uv[k] - o->k.rect[k]) / s;
        for (int q = 0; q < 3; q++) {
            o->k.g[k][q] = snap(gr[q], 1e-4 * big);
            c -= o->k.g[k][q] * v[0]->pos[q];
        }
        if (!isfinite(c)) /* (a tile too small for its face, or far out) */
            return false;
        c -= floor(c);
        o->c[k] = c;
        o->k.cq[k] = (int32_t)lround(c * TILE_CQ) % TILE_CQ;
    }
    return true;
}

/* a vertex's weld key: position, normal, colour and class */
struct weld_key {
    float pos[3], nrm[3];
    uint8_t col[4];
    int32_t cls;
};

int tiles_build(const struct mesh *m, struct mesh_tiles *B)
{
    memset(B, 0, sizeof *B);
    const uint32_t nt = m->n_tris, nv = m->n_verts;
    int rc = -1;
    uint8_t *mat_ok = calloc(m->n_materials, 2);
    struct tile_key *key = calloc(nt ? nt : 1, sizeof *key);
    struct tile_class *tc = NULL, one;
    int32_t *tcls = malloc((size_t)nt * sizeof *tcls);
    uint32_t *order = malloc((size_t)(nt > nv ? nt : nv) * sizeof *order);
    struct weld_key *wk = NULL;
    B->vcls = malloc((size_t)nv * sizeof *B->vcls);
    if (!mat_ok || !key || !tcls || !order || !B->vcls)
        goto out;
    for (uint32_t k = 0; k < m->n_materials; k++) {
        bool tex;
        mat_ok[2 * k] = tile_material(&m->materials[k], &tex);
        mat_ok[2 * k + 1] = tex;
    }
    for (uint32_t t = 0; t < nt; t++) { /* a material tiles when all its faces do */
        const uint32_t k = m->tri_material[t];
        if (!mat_ok[2 * k])
            continue;
        if (tri_class(m, t, mat_ok[2 * k + 1], &one))
            key[t] = one.k;
        else
            mat_ok[2 * k] = 0;
    }
    uint32_t n = 0;
    for (uint32_t t = 0; t < nt; t++)
        if (mat_ok[2 * m->tri_material[t]])
            order[n++] = t;
    order_by_record(order, n, key, sizeof *key);
    for (uint32_t t = 0; t < nt; t++)
        tcls[t] = -1;
    B->n_cls = 0;
    for (uint32_t i = 0; i < n; i++)
        B->n_cls += i == 0 || memcmp(&key[order[i]], &key[order[i - 1]], sizeof *key);
    if (!(tc = malloc((B->n_cls ? B->n_cls : 1) * sizeof *tc)))
        goto out;
    B->n_cls = 0;
    for (uint32_t i = 0; i < n; i++) {
        if (i == 0 || memcmp(&key[order[i]], &key[order[i - 1]], sizeof *key))
            tri_class(m, order[i], mat_ok[2 * key[order[i]].mat + 1], &tc[B->n_cls++]);
        tcls[order[i]] = (int32_t)B->n_cls - 1;
    }
    /* a vertex's class: its triangles' one; demoted until every triangle's corners agree */
    for (uint32_t v = 0; v < nv; v++)
        B->vcls[v] = -1;
    for (bool changed = true; changed;) {
        changed = false;
        for (uint32_t t = 0; t < nt; t++)
            for (int j = 0; j < 3; j++) {
                int32_t *x = &B->vcls[m->tris[t][j]];
                if (*x == -1 && tcls[t] >= 0)
                    *x = tcls[t];
                else if (*x != -2 && (*x != tcls[t] || tcls[t] < 0))
                    *x = -2, changed = true;
            }
        for (uint32_t t = 0; t < nt; t++)
            if (tcls[t] >= 0 && (B->vcls[m->tris[t][0]] != tcls[t] ||
                                 B->vcls[m->tris[t][1]] != tcls[t] ||
                                 B->vcls[m->tris[t][2]] != tcls[t]))
                tcls[t] = -1, changed = true;
    }
    uint32_t n_tiled = 0;
    for (uint32_t v = 0; v < nv; v++)
        n_tiled += B->vcls[v] >= 0;
    if (!n_tiled) { /* (nothing to weld: the seams stay) */
        rc = 0;
        goto none;
    }
    /* derived materials: one per textured (material, tile) */
    uint32_t n_der = 0;
    for (uint32_t i = 0; i < B->n_cls; i++) {
        struct tile_class *c = &tc[i];
        c->derived = c->k.mat;
        if (c->k.rect[2] == 0)
            continue;
        if (i > 0 && tc[i - 1].k.mat == c->k.mat &&
            !memcmp(tc[i - 1].k.rect, c->k.rect, sizeof c->k.rect))
            c->derived = tc[i - 1].derived; /* (sorted: a tile's classes are together) */
        else
            c->derived = m->n_materials + n_der++;
    }
    if ((size_t)m->n_materials + n_der > UINT16_MAX) { /* (tri_material is 16 bits) */
        rc = 0;
        goto none;
    }
    B->n_mats = m->n_materials + n_der;
    B->mats = malloc((size_t)B->n_mats * sizeof *B->mats);
    wk = malloc((size_t)nv * sizeof *wk);
    B->weld = malloc((size_t)nv * sizeof *B->weld);
    if (!B->mats || !wk || !B->weld)
        goto out;
    memcpy(B->mats, m->materials, (size_t)m->n_materials * sizeof *B->mats);
    for (uint32_t i = 0; i < B->n_cls; i++) {
        const struct tile_class *c = &tc[i];
        if (c->derived < m->n_materials)
            continue;
        struct material *d = &B->mats[c->derived];
        *d = m->materials[c->k.mat];
        d->features = true;
        struct tex_slot *sl[] = {&d->base, &d->alpha_map, &d->emissive_map,
                                 &d->normal_map, &d->occlusion_map, &d->spec_map};
        for (size_t k = 0; k < sizeof sl / sizeof *sl; k++)
            if (sl[k]->tex >= 0 || (k == 0 && d->texture >= 0)) {
                sl[k]->tile = true;
                memcpy(sl[k]->rect, c->k.rect, sizeof c->k.rect);
            }
    }
    /* welds: tiled vertices of one key are one */
    n = 0;
    for (uint32_t v = 0; v < nv; v++) {
        B->weld[v] = v;
        if (B->vcls[v] < 0)
            continue;
        memset(&wk[v], 0, sizeof wk[v]);
        memcpy(wk[v].pos, m->verts[v].pos, sizeof wk[v].pos);
        memcpy(wk[v].nrm, m->verts[v].nrm, sizeof wk[v].nrm);
        if (m->colors)
            memcpy(wk[v].col, m->colors[v], sizeof wk[v].col);
        wk[v].cls = B->vcls[v];
        order[n++] = v;
    }
    order_by_record(order, n, wk, sizeof *wk);
    for (uint32_t i = 1; i < n; i++)
        if (!memcmp(&wk[order[i]], &wk[order[i - 1]], sizeof *wk))
            B->weld[order[i]] = B->weld[order[i - 1]];
    B->cls = tc;
    tc = NULL;
    rc = 0;
    goto out;
none:
    free(B->vcls), B->vcls = NULL;
out:
    if (rc)
        tiles_free(B);
    free(mat_ok);
    free(key);
    free(tc);
    free(tcls);
    free(order);
    free(wk);
    return rc;
}


void tiles_vertex(const struct mesh_tiles *T, const struct mesh *m, uint32_t v,
                  struct mesh_vertex *out, uint16_t *material)
{
    const int32_t k = T->vcls ? T->vcls[v] : -1;
    if (k < 0 || !(T->cls[k].k.rect[2] > 0))
        return;
    const struct tile_class *tc = &T->cls[k];
    const float *p = m->verts[v].pos;
    for (int a = 0; a < 2; a++)
        out->uv[a] = (float)(tc->k.g[a][0] * p[0] + tc->k.g[a][1] * p[1] + tc->k.g[a][2] * p[2] +
                             tc->c[a]);
    *material = (uint16_t)tc->derived;
}

void tiles_welded_corners(const struct mesh_tiles *T, const struct mesh *m, uint32_t *out)
{
    const uint32_t *c = &m->tris[0][0];
    for (size_t i = 0; i < (size_t)m->n_tris * 3; i++)
        out[i] = T->weld[c[i]];
}

void tiles_free(struct mesh_tiles *T)
{
    free(T->weld);
    free(T->vcls);
    free(T->cls);
    free(T->mats);
    memset(T, 0, sizeof *T);
}
