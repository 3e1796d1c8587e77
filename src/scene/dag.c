/* dag.c: the cluster hierarchy of a mesh (see dag.h). */
#include "dag.h"

#include <math.h>
#include <meshoptimizer.h>
#include <stdlib.h>
#include <string.h>

#include "cluster.h"
#include "order.h"
#include "tiles.h"
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
    struct mesh_tiles T; /* atlas tiles (tiles.h): the source's vertices welded */
};

/* the vertex v is to the simplifier */
static inline uint32_t welded(const struct build *B, uint32_t v)
{
    return B->T.weld ? B->T.weld[v] : v;
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

/* level 0: the source's triangles in meshlets, found again by their corners; the clusters'
 * own spheres; what no meshlet took (degenerate triangles, if the meshlets drop any) in
 * runs of the file's order */
static int level0(struct build *B)
{
    const struct mesh *m = B->m;
    const uint32_t n = m->n_tris;
    uint32_t(*wt)[3] = m->tris; /* the triangles as the simplifier sees them */
    if (B->T.weld) {
        if (!(wt = malloc((size_t)n * sizeof *wt)))
            return -1;
        tiles_welded_corners(&B->T, m, &wt[0][0]);
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
    order_by_record(order, nv, g->pos, 3 * sizeof *g->pos);
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

/* the first level whose clusters draw copies of their vertices: DAG_COPY_LEVEL, or for a
 * tiled mesh every coarser level (its copies carry their tile uvs) */
static uint32_t copy_level(const struct build *B)
{
    return B->T.vcls ? 1 : DAG_COPY_LEVEL;
}

/* the hierarchy's own vertex array: the source's, then for each cluster of level
 * DAG_COPY_LEVEL or coarser (their triangles are consecutive, in the order the clusters were
 * made) a copy of each vertex it uses, its corners renumbered to them; the finer ones keep
 * the source's */
static int own_vertices(struct build *B, struct mesh_dag *d)
{
    const struct mesh *m = B->m;
    struct mesh *hm = &d->mesh;
    const uint32_t from = copy_level(B);
    size_t extra = 0;
    for (size_t i = 0; i < B->n; i++)
        if (B->c[i].level >= from)
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
        if (c->level < from)
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
                    tiles_vertex(&B->T, m, v, &hm->verts[nv], &hm->vert_material[nv]);
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
    if (!B.stamp || !B.local || (m->features && tiles_build(m, &B.T)))
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
    if (!hm->tri_material)
        goto fail;
    if (B.T.mats) { /* (the source's, and its tiles') */
        hm->materials = B.T.mats, hm->n_materials = B.T.n_mats;
        B.T.mats = NULL;
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
    /* per cluster: its culling box and triangle span; a coarser cluster's triangles are
     * consecutive, and a copying one's vertices too (own_vertices): it keeps its first of
     * each (dag.h), and only level 0's keep a list of triangles (its clusters come first) */
    size_t ntl = 0;
    B.owner++;
    for (size_t i = 0; i < B.n; i++, B.owner++) {
        struct dag_cluster *c = &B.c[i];
        const uint32_t *t = B.tris.a + c->tri_first;
        const bool coarse = c->level > 0, copies = c->level >= copy_level(&B);
        if (!coarse && (i != d->n_level0 || c->tri_first != ntl))
            goto fail; /* (cannot happen: level0 makes them first) */
        cluster_bounds(hm, t, c->n_tris, &c->box);
        c->tri_lo = UINT32_MAX, c->tri_hi = 0;
        c->vert_first = c->n_verts = 0;
        bool consecutive = true;
        for (uint32_t k = 0; k < c->n_tris; k++) {
            c->tri_lo = t[k] < c->tri_lo ? t[k] : c->tri_lo;
            c->tri_hi = t[k] > c->tri_hi ? t[k] : c->tri_hi;
            consecutive &= !coarse || t[k] == t[0] + k;
            for (int j = 0; j < 3 && copies; j++) {
                uint32_t v = hm->tris[t[k]][j];
                if (B.stamp[v] != B.owner) { /* (a copy: each the one after the last) */
                    B.stamp[v] = B.owner;
                    consecutive &= !c->n_verts || v == c->vert_first + c->n_verts;
                    c->vert_first = c->n_verts++ ? c->vert_first : v;
                }
            }
        }
        if (!consecutive)
            goto fail; /* (cannot happen: simplify_group, own_vertices) */
        if (coarse) {
            c->tri_first = t[0];
        } else {
            d->n_level0++;
            ntl += c->n_tris;
        }
    }
    uint32_t *st = realloc(B.tris.a, (ntl ? ntl : 1) * sizeof *st);
    d->tris = st ? st : B.tris.a;
    B.tris.a = NULL;
    d->c = B.c;
    d->n = (uint32_t)B.n;
    B.c = NULL;
    d->levels = levels;
    d->build_ms = timing_now_ms() - t0;
    d->bytes = sizeof *d + mesh_geometry_bytes(hm) + cluster_bytes(hm) +
               (hm->materials != m->materials ? hm->n_materials * sizeof *hm->materials : 0) +
               d->n * sizeof *d->c + ntl * sizeof *d->tris;
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
    free(d);
out:
    free(B.stamp);
    free(B.local);
    free(B.tri3.a);
    free(B.tris.a);
    free(B.c);
    tiles_free(&B.T);
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

/* does the array a of n bytes start with m's b (n_b bytes)? */
static bool starts_with(const void *a, size_t n, const void *b, size_t n_b)
{
    return a && b && n >= n_b && memcmp(a, b, n_b) == 0;
}

void dag_settle(struct mesh *m)
{
    struct mesh_dag *d = m->dag;
    if (!d || dag_is_cut_mesh(m) || (d->shared & DAG_SETTLED))
        return;
    d->shared |= DAG_SETTLED;
    struct mesh *hm = &d->mesh;
    const size_t nv = m->n_verts, hv = hm->n_verts, nt = m->n_tris, ht = hm->n_tris;
    size_t saved = 0;
    if (starts_with(hm->verts, hv * sizeof *hm->verts, m->verts, nv * sizeof *m->verts) &&
        starts_with(hm->vert_material, hv * sizeof *hm->vert_material, m->vert_material,
                    nv * sizeof *m->vert_material)) {
        free(m->verts), free(m->vert_material);
        m->verts = hm->verts, m->vert_material = hm->vert_material;
        d->shared |= DAG_SHARES_VERTS;
        saved += nv * (sizeof *m->verts + sizeof *m->vert_material);
    }
    if (starts_with(hm->tris, ht * sizeof *hm->tris, m->tris, nt * sizeof *m->tris) &&
        starts_with(hm->tri_material, ht * sizeof *hm->tri_material, m->tri_material,
                    nt * sizeof *m->tri_material)) {
        free(m->tris), free(m->tri_material);
        m->tris = hm->tris, m->tri_material = hm->tri_material;
        d->shared |= DAG_SHARES_TRIS;
        saved += nt * (sizeof *m->tris + sizeof *m->tri_material);
    }
    if (starts_with(hm->colors, hv * sizeof *hm->colors, m->colors, nv * sizeof *m->colors)) {
        free(m->colors);
        m->colors = hm->colors;
        d->shared |= DAG_SHARES_COLORS;
        saved += nv * sizeof *m->colors;
    }
    /* the copies' positions are their sources': the same positions, numbered alike */
    if (hm->n_pos == m->n_pos &&
        starts_with(hm->pos_id, hv * sizeof *hm->pos_id, m->pos_id, nv * sizeof *m->pos_id) &&
        starts_with(hm->pos_xyz, hm->n_pos * sizeof *hm->pos_xyz, m->pos_xyz,
                    m->n_pos * sizeof *m->pos_xyz)) {
        free(m->pos_id), free(m->pos_xyz);
        m->pos_id = hm->pos_id, m->pos_xyz = hm->pos_xyz;
        d->shared |= DAG_SHARES_POSITIONS;
        saved += nv * sizeof *m->pos_id + m->n_pos * sizeof *m->pos_xyz;
    }
    d->bytes -= saved < d->bytes ? saved : 0;
}

void dag_free(struct mesh *m)
{
    struct mesh_dag *d = m->dag;
    if (!d || dag_is_cut_mesh(m))
        return;
    mesh_free_clusters(&d->mesh);
    if (d->mesh.materials != m->materials)
        free(d->mesh.materials);
    if (!(d->shared & DAG_SHARES_TRIS)) /* (else m's own now) */
        free(d->mesh.tris), free(d->mesh.tri_material);
    if (!(d->shared & DAG_SHARES_VERTS))
        free(d->mesh.verts), free(d->mesh.vert_material);
    if (!(d->shared & DAG_SHARES_COLORS))
        free(d->mesh.colors);
    if (!(d->shared & DAG_SHARES_POSITIONS))
        free(d->mesh.pos_id), free(d->mesh.pos_xyz);
    free(d->c);
    free(d->tris);
    free(d);
    m->dag = NULL;
}
