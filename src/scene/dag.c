/* dag.c: the cluster hierarchy of a mesh (see dag.h). */
#include "dag.h"

#include <math.h>
#include <meshoptimizer.h>
#include <stdlib.h>
#include <string.h>

#include "cluster.h"
#include "timing.h"

/* growable arrays of uint32_t */
struct u32s {
    uint32_t *a;
    size_t n, cap;
};

static int push(struct u32s *v, uint32_t x)
{
    if (v->n == v->cap) {
        size_t nc = v->cap ? 2 * v->cap : 1024;
        uint32_t *g = realloc(v->a, nc * sizeof *g);
        if (!g)
            return -1;
        v->a = g, v->cap = nc;
    }
    v->a[v->n++] = x;
    return 0;
}

/* what the build grows */
struct build {
    const struct mesh *m;
    struct u32s tri3;    /* triangles of the hierarchy's mesh, 3 corners each */
    struct u32s tris;    /* clusters' triangle lists */
    struct dag_cluster *c;
    size_t n, cap;
    uint32_t *stamp;     /* per source vertex: a local number's owner (the group or cluster) */
    uint32_t *local;     /* per source vertex: its local number */
    uint32_t owner;
    /* atlas tiles (tiles()): per source vertex the vertex it is one with to the simplifier
     * (itself but where tile classes weld seams), and its tile class or -1 */
    uint32_t *weld;
    int32_t *vcls;
    struct tile_class *cls;
    uint32_t n_cls;
    struct material *mats; /* the source's materials, then one per (material, tile) */
    uint32_t n_mats;
};

/* the vertex v is to the simplifier */
static inline uint32_t welded(const struct build *B, uint32_t v)
{
    return B->weld ? B->weld[v] : v;
}

/* order[0 .. n) (numbers of records of `size` bytes at base) sorted by their records'
 * bytes, then by number: equal records come together, the lowest number first */
static const unsigned char *sort_base; /* qsort's context */
static size_t sort_size;

static int by_record(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    int c = memcmp(sort_base + x * sort_size, sort_base + y * sort_size, sort_size);
    return c ? c : (x > y) - (x < y);
}

static void sort_by_record(uint32_t *order, size_t n, const void *base, size_t size)
{
    sort_base = base, sort_size = size;
    qsort(order, n, sizeof *order, by_record);
}

static struct dag_cluster *new_cluster(struct build *B)
{
    if (B->n == B->cap) {
        size_t nc = B->cap ? 2 * B->cap : 1024;
        struct dag_cluster *g = realloc(B->c, nc * sizeof *g);
        if (!g)
            return NULL;
        B->c = g, B->cap = nc;
    }
    struct dag_cluster *c = &B->c[B->n++];
    memset(c, 0, sizeof *c);
    c->p_error = -1;
    return c;
}

/* the sphere around the corners of B->tris.a[first .. first + n) */
static void tri_sphere(const struct build *B, size_t first, uint32_t n, float center[3],
                       float *radius)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (uint32_t i = 0; i < n; i++)
        for (int j = 0; j < 3; j++) {
            const float *p = B->m->verts[B->tri3.a[3 * (size_t)B->tris.a[first + i] + j]].pos;
            for (int a = 0; a < 3; a++)
                lo[a] = fmin(lo[a], p[a]), hi[a] = fmax(hi[a], p[a]);
        }
    double c[3], r = 0;
    for (int a = 0; a < 3; a++)
        c[a] = 0.5 * (lo[a] + hi[a]);
    for (uint32_t i = 0; i < n; i++)
        for (int j = 0; j < 3; j++) {
            const float *p = B->m->verts[B->tri3.a[3 * (size_t)B->tris.a[first + i] + j]].pos;
            double d = 0;
            for (int a = 0; a < 3; a++)
                d += (p[a] - c[a]) * (p[a] - c[a]);
            r = fmax(r, sqrt(d));
        }
    for (int a = 0; a < 3; a++)
        center[a] = (float)c[a];
    *radius = (float)(r * (1 + 1e-6) + 1e-30) + fabsf(center[0]) * 1e-7f +
              fabsf(center[1]) * 1e-7f + fabsf(center[2]) * 1e-7f; /* (float rounding) */
}

/* the sphere that holds spheres (c, r) and (d, s), into (c, r) */
static void merge_sphere(float c[3], float *r, const float d[3], float s)
{
    double v[3] = {d[0] - c[0], d[1] - c[1], d[2] - c[2]};
    double len = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (len + s <= *r)
        return;
    if (len + *r <= s) {
        memcpy(c, d, 3 * sizeof *c);
        *r = s;
        return;
    }
    double nr = 0.5 * (len + *r + s), t = (nr - *r) / len;
    for (int a = 0; a < 3; a++)
        c[a] = (float)(c[a] + t * v[a]);
    *r = (float)(nr * (1 + 1e-6)) + fabsf(c[0]) * 1e-7f + fabsf(c[1]) * 1e-7f +
         fabsf(c[2]) * 1e-7f;
}

/* meshlets of the index buffer idx[0 .. 3 nt) over positions pos (nv, stride bytes):
 * meshlets, their vertices and triangles, NULL-free on success (the caller frees) */
struct meshlets {
    struct meshopt_Meshlet *ml;
    unsigned *mv;
    unsigned char *mt;
    size_t n;
};

static int make_meshlets(struct meshlets *o, const uint32_t *idx, size_t nt, const float *pos,
                         size_t nv, size_t stride)
{
    const size_t maxm = meshopt_buildMeshletsBound(3 * nt, DAG_CLUSTER_VERTS, DAG_CLUSTER_TRIS);
    o->ml = malloc(maxm * sizeof *o->ml);
    o->mv = malloc(maxm * DAG_CLUSTER_VERTS * sizeof *o->mv);
    o->mt = malloc(maxm * DAG_CLUSTER_TRIS * 3 + 4);
    if (!o->ml || !o->mv || !o->mt) {
        free(o->ml), free(o->mv), free(o->mt);
        return -1;
    }
    o->n = meshopt_buildMeshlets(o->ml, o->mv, o->mt, idx, 3 * nt, pos, nv, stride,
                                 DAG_CLUSTER_VERTS, DAG_CLUSTER_TRIS, 0.0f);
    return 0;
}

static void free_meshlets(struct meshlets *o)
{
    free(o->ml), free(o->mv), free(o->mt);
}

static int ascending(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return x < y ? -1 : x > y;
}

/* the triangles B->tris.a[from ..] as a level 0 cluster (ascending; none: nothing) */
static int close_cluster(struct build *B, size_t from)
{
    const uint32_t cnt = (uint32_t)(B->tris.n - from);
    if (!cnt)
        return 0;
    qsort(B->tris.a + from, cnt, sizeof *B->tris.a, ascending);
    struct dag_cluster *c = new_cluster(B);
    if (!c)
        return -1;
    c->tri_first = (uint32_t)from;
    c->n_tris = cnt;
    tri_sphere(B, from, cnt, c->center, &c->radius);
    return 0;
}

/* ---- atlas tiles (dag.h): faces of one material that each map one tile of the texture
 * the same way are one surface to the simplifier ---- */

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

/* Tile classes for a mesh on the features path (the hierarchy's derived materials are
 * drawn there; a mesh on the default path keeps its seams): each triangle of a material
 * whose faces all map tiles (tri_class) gets its class, a vertex the class of all its
 * triangles (a vertex of two classes, or of a triangle without one, and then that
 * triangle's other corners, has none); vertices of one class at one position, with one
 * normal and colour, are welded; a derived material per textured (material, tile), its
 * slots wrapping inside the tile. 0, also with nothing to weld; -1 out of memory. */
static int tiles(struct build *B)
{
    const struct mesh *m = B->m;
    if (!m->features)
        return 0;
    const uint32_t nt = m->n_tris, nv = m->n_verts;
    int rc = -1;
    uint8_t *mat_ok = calloc(m->n_materials, 2);
    struct tile_key *key = malloc((size_t)nt * sizeof *key);
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
    sort_by_record(order, n, key, sizeof *key);
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
    sort_by_record(order, n, wk, sizeof *wk);
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
    free(mat_ok);
    free(key);
    free(tc);
    free(tcls);
    free(order);
    free(wk);
    return rc;
}

/* level 0: the source's triangles in meshlets, found again by their corners; the clusters'
 * own spheres; what no meshlet took (degenerate triangles, if the meshlets drop any) in
 * runs of the file's order */
static int level0(struct build *B)
{
    const struct mesh *m = B->m;
    const uint32_t n = m->n_tris;
    uint32_t(*wt)[3] = m->tris; /* the triangles as the simplifier sees them */
    if (B->weld) {
        if (!(wt = malloc((size_t)n * sizeof *wt)))
            return -1;
        for (uint32_t t = 0; t < n; t++)
            for (int j = 0; j < 3; j++)
                wt[t][j] = B->weld[m->tris[t][j]];
    }
    struct meshlets ms;
    if (make_meshlets(&ms, &wt[0][0], n, m->verts[0].pos, m->n_verts, sizeof *m->verts)) {
        if (wt != m->tris)
            free(wt);
        return -1;
    }
    int rc = -1;
    uint32_t *start = calloc((size_t)m->n_verts + 1, sizeof *start);
    uint32_t *by_v = malloc((size_t)n * 3 * sizeof *by_v);
    uint8_t *used = calloc(n, 1);
    if (!start || !by_v || !used)
        goto out;
    for (uint32_t t = 0; t < n; t++)
        for (int j = 0; j < 3; j++)
            start[wt[t][j] + 1]++;
    for (uint32_t v = 0; v < m->n_verts; v++)
        start[v + 1] += start[v];
    for (uint32_t t = 0; t < n; t++)
        for (int j = 0; j < 3; j++)
            by_v[start[wt[t][j]]++] = t;
    for (uint32_t v = m->n_verts; v > 0; v--)
        start[v] = start[v - 1];
    start[0] = 0;
    for (size_t k = 0; k < ms.n; k++) {
        const size_t from = B->tris.n;
        for (unsigned i = 0; i < ms.ml[k].triangle_count; i++) {
            const unsigned char *l = ms.mt + ms.ml[k].triangle_offset + 3 * i;
            const unsigned *vv = ms.mv + ms.ml[k].vertex_offset;
            uint32_t a = vv[l[0]], b = vv[l[1]], c = vv[l[2]];
            for (uint32_t q = start[a]; q < start[a + 1]; q++) {
                uint32_t t = by_v[q];
                const uint32_t *x = wt[t];
                bool same = (x[0] == a && x[1] == b && x[2] == c) ||
                            (x[1] == a && x[2] == b && x[0] == c) ||
                            (x[2] == a && x[0] == b && x[1] == c);
                if (same && !used[t]) {
                    used[t] = 1;
                    if (push(&B->tris, t))
                        goto out;
                    break;
                }
            }
        }
        if (close_cluster(B, from))
            goto out;
    }
    for (uint32_t t = 0; t < n;) { /* what no meshlet took */
        const size_t from = B->tris.n;
        for (; t < n && B->tris.n - from < DAG_CLUSTER_TRIS; t++)
            if (!used[t] && push(&B->tris, t))
                goto out;
        if (close_cluster(B, from))
            goto out;
    }
    rc = 0;
out:
    free_meshlets(&ms);
    free(start);
    free(by_v);
    free(used);
    if (wt != m->tris)
        free(wt);
    return rc;
}

static int by_key(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

/* scratch for one group */
struct group {
    struct u32s idx;  /* local corners */
    struct u32s vert; /* local -> source vertex */
    float *pos;       /* local positions */
    size_t pos_cap;
    uint32_t *dst;
    size_t dst_cap;
    uint32_t *pid;    /* local -> position id (equal positions, equal id) */
    uint64_t *e, *bin, *bout; /* edges; the input's and the output's open ones */
    size_t e_cap;
};


/* the directed edges of idx[0 .. n) (by position id) whose reverse is not there, sorted,
 * into out; their number */
static size_t open_edges(const struct group *g, const uint32_t *idx, size_t n, uint64_t *out)
{
    for (size_t i = 0; i < n; i += 3)
        for (int k = 0; k < 3; k++)
            g->e[i + (size_t)k] = (uint64_t)g->pid[idx[i + (size_t)k]] << 32 |
                                  g->pid[idx[i + (size_t)(k + 1) % 3]];
    qsort(g->e, n, sizeof *g->e, by_key);
    size_t no = 0;
    for (size_t i = 0; i < n; i++) {
        uint64_t rev = g->e[i] << 32 | g->e[i] >> 32;
        if (!bsearch(&rev, g->e, n, sizeof *g->e, by_key))
            out[no++] = g->e[i];
    }
    return no;
}

/* Did the simplification keep the group's border (its open edges, by position) exactly?
 * meshopt_SimplifyLockBorder (0.18) locks the border vertices it classifies as such, but a
 * border vertex that is also on a uv or material seam is a seam to it, and may move along
 * the seam: then the neighbours would not meet it. 1 yes, 0 no, -1 out of memory. */
static int border_kept(struct group *g, size_t got)
{
    const size_t n = g->idx.n, nv = g->vert.n;
    if (n > g->e_cap) {
        free(g->e), free(g->bin), free(g->bout);
        g->e = malloc(n * sizeof *g->e);
        g->bin = malloc(n * sizeof *g->bin);
        g->bout = malloc(n * sizeof *g->bout);
        g->e_cap = g->e && g->bin && g->bout ? n : 0;
        if (!g->e_cap)
            return -1;
    }
    uint32_t *order = malloc(nv * sizeof *order);
    uint32_t *pid = realloc(g->pid, (nv ? nv : 1) * sizeof *pid);
    if (!order || !pid) {
        free(order);
        if (pid)
            g->pid = pid;
        return -1;
    }
    g->pid = pid;
    for (uint32_t v = 0; v < nv; v++)
        order[v] = v;
    sort_by_record(order, nv, g->pos, 3 * sizeof *g->pos);
    for (size_t i = 0; i < nv; i++)
        pid[order[i]] = i > 0 && memcmp(&g->pos[3 * (size_t)order[i]], &g->pos[3 * (size_t)order[i - 1]],
                                        3 * sizeof *g->pos) == 0
                            ? pid[order[i - 1]]
                            : (uint32_t)i;
    free(order);
    size_t a = open_edges(g, g->idx.a, n, g->bin);
    size_t b = open_edges(g, g->dst, got, g->bout);
    return a == b && memcmp(g->bin, g->bout, a * sizeof *g->bin) == 0;
}

/* the local number of source vertex v in the group being gathered */
static int local_of(struct build *B, struct group *g, uint32_t v, uint32_t *out)
{
    if (B->stamp[v] != B->owner) {
        B->stamp[v] = B->owner;
        B->local[v] = (uint32_t)g->vert.n;
        if (push(&g->vert, v))
            return -1;
    }
    *out = B->local[v];
    return 0;
}

/* group clusters cl[0 .. k): simplified together, their border locked, split again into new
 * clusters of level `level` (appended to B and their numbers to *next): 1; a group that
 * stalls gets none and its clusters go to *next as they are: 0; -1 out of memory. */
static int simplify_group(struct build *B, struct group *g, const uint32_t *cl, int k,
                          uint32_t level, double scale, struct u32s *next)
{
    g->idx.n = g->vert.n = 0;
    B->owner++;
    float gc[3], gr = 0, ge = 0;
    memcpy(gc, B->c[cl[0]].center, sizeof gc);
    gr = B->c[cl[0]].radius;
    for (int i = 0; i < k; i++) {
        const struct dag_cluster *c = &B->c[cl[i]];
        merge_sphere(gc, &gr, c->center, c->radius);
        ge = fmaxf(ge, c->error);
        for (uint32_t t = 0; t < c->n_tris; t++)
            for (int j = 0; j < 3; j++) {
                uint32_t lv;
                if (local_of(B, g, welded(B, B->tri3.a[3 * (size_t)B->tris.a[c->tri_first + t] + j]),
                             &lv) ||
                    push(&g->idx, lv))
                    return -1;
            }
    }
    if (g->vert.n * 3 > g->pos_cap) {
        float *p = realloc(g->pos, g->vert.n * 3 * sizeof *p);
        if (!p)
            return -1;
        g->pos = p, g->pos_cap = g->vert.n * 3;
    }
    for (size_t v = 0; v < g->vert.n; v++)
        memcpy(&g->pos[3 * v], B->m->verts[g->vert.a[v]].pos, 3 * sizeof *g->pos);
    if (g->idx.n > g->dst_cap) {
        uint32_t *d = realloc(g->dst, g->idx.n * sizeof *d);
        if (!d)
            return -1;
        g->dst = d, g->dst_cap = g->idx.n;
    }
    const size_t nt = g->idx.n / 3;
    float rel = 0;
    size_t got = meshopt_simplify(g->dst, g->idx.a, g->idx.n, g->pos, g->vert.n,
                                  3 * sizeof *g->pos, (nt / 2) * 3, 1.0f,
                                  meshopt_SimplifyLockBorder, &rel);
    int kept = got / 3 > nt * 5 / 6 || got == 0 ? 0 : border_kept(g, got);
    if (kept < 0)
        return -1;
    if (!kept) { /* stalled, or its border moved: its clusters go on to the next level's
                    grouping as they are */
        for (int i = 0; i < k; i++)
            if (push(next, cl[i]))
                return -1;
        return 0;
    }
    float err = (float)fmax(fmax((double)ge, (double)rel * scale), (double)ge + DAG_MIN_STEP * scale);
    if (!(err > ge))
        err = nextafterf(ge, INFINITY);
    for (int i = 0; i < k; i++) {
        struct dag_cluster *c = &B->c[cl[i]];
        memcpy(c->p_center, gc, sizeof gc);
        c->p_radius = gr;
        c->p_error = err;
    }
    struct meshlets ms;
    if (make_meshlets(&ms, g->dst, got / 3, g->pos, g->vert.n, 3 * sizeof *g->pos))
        return -1;
    for (size_t q = 0; q < ms.n; q++) {
        const size_t from = B->tris.n;
        for (unsigned i = 0; i < ms.ml[q].triangle_count; i++) {
            const unsigned char *l = ms.mt + ms.ml[q].triangle_offset + 3 * i;
            const unsigned *vv = ms.mv + ms.ml[q].vertex_offset;
            const uint32_t id = (uint32_t)(B->tri3.n / 3);
            if (push(&B->tris, id) || push(&B->tri3, g->vert.a[vv[l[0]]]) ||
                push(&B->tri3, g->vert.a[vv[l[1]]]) || push(&B->tri3, g->vert.a[vv[l[2]]])) {
                free_meshlets(&ms);
                return -1;
            }
        }
        struct dag_cluster *c = new_cluster(B);
        if (!c || push(next, (uint32_t)(B->n - 1))) {
            free_meshlets(&ms);
            return -1;
        }
        c->tri_first = (uint32_t)from;
        c->n_tris = (uint32_t)(B->tris.n - from);
        memcpy(c->center, gc, sizeof gc);
        c->radius = gr;
        c->error = err;
        c->level = level;
    }
    free_meshlets(&ms);
    return 1;
}

/* the clusters of a level by vertex, and the grouping's scratch (indices into cur) */
struct adj {
    uint32_t *start; /* per source vertex + 1 */
    uint32_t *cl;
    size_t cl_cap;
    uint8_t *grouped;
    uint32_t *cnt, *touched;
    size_t cap;
};

/* the source vertices cluster c uses, once each, into out (at most 3 n_tris) */
static uint32_t cluster_verts(struct build *B, const struct dag_cluster *c, uint32_t *out)
{
    uint32_t n = 0;
    B->owner++;
    for (uint32_t t = 0; t < c->n_tris; t++)
        for (int j = 0; j < 3; j++) {
            uint32_t v = welded(B, B->tri3.a[3 * (size_t)B->tris.a[c->tri_first + t] + j]);
            if (B->stamp[v] != B->owner)
                B->stamp[v] = B->owner, out[n++] = v;
        }
    return n;
}

static int adjacency(struct build *B, const struct u32s *cur, struct adj *A)
{
    const uint32_t nv = B->m->n_verts;
    uint32_t vl[3 * 512];
    if (!A->start && !(A->start = malloc(((size_t)nv + 1) * sizeof *A->start)))
        return -1;
    if (cur->n > A->cap) {
        free(A->grouped), free(A->cnt), free(A->touched);
        A->grouped = malloc(cur->n);
        A->cnt = calloc(cur->n, sizeof *A->cnt);
        A->touched = malloc(cur->n * sizeof *A->touched);
        if (!A->grouped || !A->cnt || !A->touched)
            return -1;
        A->cap = cur->n;
    }
    memset(A->grouped, 0, cur->n);
    memset(A->start, 0, ((size_t)nv + 1) * sizeof *A->start);
    size_t total = 0;
    for (size_t i = 0; i < cur->n; i++) {
        uint32_t n = cluster_verts(B, &B->c[cur->a[i]], vl);
        for (uint32_t q = 0; q < n; q++)
            A->start[vl[q] + 1]++;
        total += n;
    }
    if (total > A->cl_cap) {
        uint32_t *g2 = realloc(A->cl, total * sizeof *g2);
        if (!g2)
            return -1;
        A->cl = g2, A->cl_cap = total;
    }
    for (uint32_t v = 0; v < nv; v++)
        A->start[v + 1] += A->start[v];
    for (size_t i = 0; i < cur->n; i++) {
        uint32_t n = cluster_verts(B, &B->c[cur->a[i]], vl);
        for (uint32_t q = 0; q < n; q++)
            A->cl[A->start[vl[q]]++] = (uint32_t)i;
    }
    for (uint32_t v = nv; v > 0; v--)
        A->start[v] = A->start[v - 1];
    A->start[0] = 0;
    return 0;
}

/* a group from cur index first (if not grouped yet): up to DAG_GROUP clusters, each next
 * one the ungrouped cluster sharing the most vertices with it so far; its size (0: first
 * was grouped already) */
static int grow_group(struct build *B, const struct u32s *cur, struct adj *A, uint32_t first,
                      uint32_t gi[DAG_GROUP])
{
    if (A->grouped[first])
        return 0;
    uint32_t vl[3 * 512];
    int k = 0;
    gi[k++] = first;
    A->grouped[first] = 1;
    while (k < DAG_GROUP) {
        size_t nt = 0;
        for (int q = 0; q < k; q++) {
            uint32_t n = cluster_verts(B, &B->c[cur->a[gi[q]]], vl);
            for (uint32_t x = 0; x < n; x++)
                for (uint32_t y = A->start[vl[x]]; y < A->start[vl[x] + 1]; y++) {
                    uint32_t j = A->cl[y];
                    if (A->grouped[j])
                        continue;
                    if (!A->cnt[j])
                        A->touched[nt++] = j;
                    A->cnt[j]++;
                }
        }
        uint32_t best = UINT32_MAX, most = 0;
        for (size_t x = 0; x < nt; x++) {
            uint32_t j = A->touched[x];
            if (A->cnt[j] > most || (A->cnt[j] == most && j < best))
                best = j, most = A->cnt[j];
            A->cnt[j] = 0;
        }
        if (best == UINT32_MAX)
            break;
        gi[k++] = best;
        A->grouped[best] = 1;
    }
    return k;
}

/* the levels above level 0, until one cluster is left, nothing simplifies or
 * DAG_MAX_LEVELS; the number of levels */
static int coarser(struct build *B, const atomic_bool *cancel, int *levels)
{
    const struct mesh *m = B->m;
    double scale = meshopt_simplifyScale(m->verts[0].pos, m->n_verts, sizeof *m->verts);
    struct u32s cur = {0}, next = {0};
    struct group g = {0};
    struct adj A = {0};
    uint64_t *keys = NULL;
    int rc = -1;
    for (size_t i = 0; i < B->n; i++)
        if (push(&cur, (uint32_t)i))
            goto out;
    *levels = 1;
    for (uint32_t level = 1; level < DAG_MAX_LEVELS && cur.n > 1; level++) {
        if (cancel && atomic_load(cancel))
            break;
        uint64_t *k2 = realloc(keys, cur.n * sizeof *k2);
        if (!k2)
            goto out;
        keys = k2;
        for (size_t i = 0; i < cur.n; i++) {
            const float *p = B->c[cur.a[i]].center;
            uint32_t q[3];
            for (int a = 0; a < 3; a++) {
                double size = (double)m->bbox_max[a] - m->bbox_min[a];
                double u = size > 0 ? (p[a] - m->bbox_min[a]) / size * 1023.0 : 0;
                q[a] = u >= 0 && u <= 1023.0 ? (uint32_t)u : u > 1023.0 ? 1023 : 0;
            }
            keys[i] = (uint64_t)cluster_morton3(q) << 32 | i;
        }
        qsort(keys, cur.n, sizeof *keys, by_key);
        next.n = 0;
        /* which clusters use each vertex */
        if (adjacency(B, &cur, &A))
            goto out;
        int progress = 0;
        for (size_t oi = 0; oi < cur.n; oi++) {
            uint32_t gi[DAG_GROUP], cl[DAG_GROUP];
            int k = grow_group(B, &cur, &A, (uint32_t)keys[oi], gi);
            for (int q = 0; q < k; q++)
                cl[q] = cur.a[gi[q]];
            int r = k > 1 ? simplify_group(B, &g, cl, k, level, scale, &next)
                  : k == 1 ? push(&next, cl[0])
                           : 0;
            if (r < 0)
                goto out;
            progress += r;
        }
        if (!progress)
            break;
        *levels = (int)level + 1;
        struct u32s t = cur;
        cur = next;
        next = t;
    }
    rc = 0;
out:
    free(cur.a);
    free(next.a);
    free(g.idx.a);
    free(g.vert.a);
    free(g.pos);
    free(g.dst);
    free(g.pid);
    free(g.e);
    free(g.bin);
    free(g.bout);
    free(keys);
    free(A.start);
    free(A.cl);
    free(A.grouped);
    free(A.cnt);
    free(A.touched);
    return rc;
}

bool dag_eligible(const struct mesh *m)
{
    if (m->n_tris < DAG_MIN_TRIS || m->n_opaque != m->n_tris || !m->vert_material ||
        m->uv1 || m->tangents)
        return false;
    return mesh_positions_finite(m);
}

/* the hierarchy's own vertex array: the source's, then for each coarser cluster (their
 * triangles are consecutive, in the order the clusters were made) a copy of each vertex it
 * uses, its corners renumbered to them */
static int own_vertices(struct build *B, struct mesh_dag *d)
{
    const struct mesh *m = B->m;
    struct mesh *hm = &d->mesh;
    size_t extra = 0;
    for (size_t i = 0; i < B->n; i++)
        if (B->c[i].level > 0)
            extra += 3 * (size_t)B->c[i].n_tris;
    const size_t cap = (size_t)m->n_verts + extra;
    hm->verts = malloc(cap * sizeof *hm->verts);
    hm->vert_material = malloc(cap * sizeof *hm->vert_material);
    hm->colors = m->colors ? malloc(cap * sizeof *hm->colors) : NULL;
    if (!hm->verts || !hm->vert_material || (m->colors && !hm->colors))
        return -1;
    memcpy(hm->verts, m->verts, (size_t)m->n_verts * sizeof *hm->verts);
    memcpy(hm->vert_material, m->vert_material, (size_t)m->n_verts * sizeof *hm->vert_material);
    if (m->colors)
        memcpy(hm->colors, m->colors, (size_t)m->n_verts * sizeof *hm->colors);
    uint32_t nv = m->n_verts;
    for (size_t i = 0; i < B->n; i++) {
        const struct dag_cluster *c = &B->c[i];
        if (c->level == 0)
            continue;
        B->owner++;
        for (uint32_t t = 0; t < c->n_tris; t++) {
            uint32_t *x = hm->tris[B->tris.a[c->tri_first + t]];
            for (int j = 0; j < 3; j++) {
                uint32_t v = x[j];
                if (B->stamp[v] != B->owner) {
                    B->stamp[v] = B->owner;
                    B->local[v] = nv;
                    hm->verts[nv] = m->verts[v];
                    hm->vert_material[nv] = m->vert_material[v];
                    const int32_t k = B->vcls ? B->vcls[v] : -1;
                    if (k >= 0 && B->cls[k].k.rect[2] > 0) { /* its tile's own uvs */
                        const struct tile_class *tc = &B->cls[k];
                        for (int a = 0; a < 2; a++)
                            hm->verts[nv].uv[a] =
                                (float)(tc->k.g[a][0] * m->verts[v].pos[0] +
                                        tc->k.g[a][1] * m->verts[v].pos[1] +
                                        tc->k.g[a][2] * m->verts[v].pos[2] + tc->c[a]);
                        hm->vert_material[nv] = (uint16_t)tc->derived;
                    }
                    if (hm->colors)
                        memcpy(hm->colors[nv], m->colors[v], sizeof hm->colors[nv]);
                    nv++;
                }
                x[j] = B->local[v];
            }
        }
    }
    hm->n_verts = nv;
    struct mesh_vertex *g = realloc(hm->verts, (size_t)nv * sizeof *g);
    hm->verts = g ? g : hm->verts;
    mesh_share_positions(hm); /* (out of memory: NULL, each vertex positioned alone) */
    return 0;
}

int dag_build(struct mesh *m, const atomic_bool *cancel)
{
    if (m->dag || !dag_eligible(m))
        return 0;
    const double t0 = timing_now_ms();
    struct build B = {.m = m};
    struct mesh_dag *d = NULL;
    int levels = 0, rc = -1;
    B.stamp = malloc((size_t)m->n_verts * sizeof *B.stamp);
    B.local = malloc((size_t)m->n_verts * sizeof *B.local);
    if (!B.stamp || !B.local || tiles(&B))
        goto out;
    memset(B.stamp, 0, (size_t)m->n_verts * sizeof *B.stamp);
    for (uint32_t t = 0; t < m->n_tris; t++)
        for (int j = 0; j < 3; j++)
            if (push(&B.tri3, m->tris[t][j]))
                goto out;
    if (level0(&B) || coarser(&B, cancel, &levels))
        goto out;
    rc = 0;
    if (levels < 2 || (cancel && atomic_load(cancel)))
        goto out; /* nothing coarser: the per-mesh chain (lod.h) may still do something */
    rc = -1;
    d = calloc(1, sizeof *d);
    if (!d)
        goto out;
    /* the hierarchy's mesh: the source's, with every level's triangles */
    struct mesh *hm = &d->mesh;
    *hm = *m;
    hm->pos_id = NULL, hm->pos_xyz = NULL; /* (own_vertices makes its own) */
    hm->n_pos = 0;
    hm->lod = NULL;
    hm->clusters = NULL;
    hm->dag = d;
    hm->n_tris = hm->n_opaque = (uint32_t)(B.tri3.n / 3);
    hm->tris = (uint32_t(*)[3])B.tri3.a;
    B.tri3.a = NULL;
    hm->tri_material = malloc((size_t)hm->n_tris * sizeof *hm->tri_material);
    d->verts = malloc(B.tris.n * 3 * sizeof *d->verts);
    if (!hm->tri_material || !d->verts)
        goto fail;
    if (B.mats) { /* (the source's, and its tiles') */
        hm->materials = B.mats, hm->n_materials = B.n_mats;
        B.mats = NULL;
    }
    memcpy(hm->tri_material, m->tri_material, (size_t)m->n_tris * sizeof *hm->tri_material);
    /* the coarser clusters' vertices copied after the source's, cluster by cluster: walked
     * in the mesh's order, every level reads its vertices forward, as the source does */
    if (own_vertices(&B, d))
        goto fail;
    for (uint32_t t = m->n_tris; t < hm->n_tris; t++) /* (corners share a material: seams) */
        hm->tri_material[t] = hm->vert_material[hm->tris[t][0]];
    cluster_build(hm); /* the runs the cut is walked by (out of memory: none, walked without) */
    uint32_t *st2 = realloc(B.stamp, (size_t)hm->n_verts * sizeof *st2);
    if (!st2)
        goto fail;
    B.stamp = st2;
    memset(B.stamp + m->n_verts, 0, (size_t)(hm->n_verts - m->n_verts) * sizeof *B.stamp);
    /* per cluster: its culling box, triangle span and vertices */
    size_t nvl = 0;
    B.owner++;
    for (size_t i = 0; i < B.n; i++, B.owner++) {
        struct dag_cluster *c = &B.c[i];
        const uint32_t *t = B.tris.a + c->tri_first;
        cluster_bounds(hm, t, c->n_tris, &c->box);
        c->tri_lo = UINT32_MAX, c->tri_hi = 0;
        c->vert_first = (uint32_t)nvl;
        for (uint32_t k = 0; k < c->n_tris; k++) {
            c->tri_lo = t[k] < c->tri_lo ? t[k] : c->tri_lo;
            c->tri_hi = t[k] > c->tri_hi ? t[k] : c->tri_hi;
            for (int j = 0; j < 3; j++) {
                uint32_t v = hm->tris[t[k]][j];
                if (B.stamp[v] != B.owner)
                    B.stamp[v] = B.owner, d->verts[nvl++] = v;
            }
        }
        c->n_verts = (uint32_t)(nvl - c->vert_first);
        d->n_level0 += c->level == 0;
    }
    uint32_t *sv = realloc(d->verts, (nvl ? nvl : 1) * sizeof *sv);
    d->verts = sv ? sv : d->verts;
    d->c = B.c;
    d->n = (uint32_t)B.n;
    B.c = NULL;
    d->tris = B.tris.a;
    B.tris.a = NULL;
    d->levels = levels;
    d->build_ms = timing_now_ms() - t0;
    d->bytes = sizeof *d + mesh_geometry_bytes(hm) + cluster_bytes(hm) +
               (hm->materials != m->materials ? hm->n_materials * sizeof *hm->materials : 0) +
               d->n * sizeof *d->c + B.tris.n * sizeof *d->tris + nvl * sizeof *d->verts;
    __atomic_store_n(&m->dag, d, __ATOMIC_RELEASE);
    d = NULL;
    rc = 0;
    goto out;
fail:
    if (d->mesh.materials != m->materials)
        free(d->mesh.materials);
    mesh_free_clusters(&d->mesh);
    free(d->mesh.tris);
    free(d->mesh.tri_material);
    if (d->mesh.verts != m->verts) {
        free(d->mesh.verts);
        free(d->mesh.vert_material);
        free(d->mesh.colors);
    }
    free(d->mesh.pos_id);
    free(d->mesh.pos_xyz);
    free(d->verts);
    free(d);
out:
    free(B.stamp);
    free(B.local);
    free(B.tri3.a);
    free(B.tris.a);
    free(B.c);
    free(B.weld);
    free(B.vcls);
    free(B.cls);
    free(B.mats);
    return rc;
}

const struct mesh_dag *dag_of(const struct mesh *m)
{
    return __atomic_load_n(&m->dag, __ATOMIC_ACQUIRE);
}

bool dag_is_cut_mesh(const struct mesh *m)
{
    return m->dag && m == &m->dag->mesh;
}

void dag_free(struct mesh *m)
{
    struct mesh_dag *d = m->dag;
    if (!d || dag_is_cut_mesh(m))
        return;
    mesh_free_clusters(&d->mesh);
    if (d->mesh.materials != m->materials)
        free(d->mesh.materials);
    free(d->mesh.tris);
    free(d->mesh.tri_material);
    free(d->mesh.verts);
    free(d->mesh.vert_material);
    free(d->mesh.colors);
    free(d->mesh.pos_id);
    free(d->mesh.pos_xyz);
    free(d->c);
    free(d->tris);
    free(d->verts);
    free(d);
    m->dag = NULL;
}
