/* mesh.c: building the unique-vertex mesh from corner-indexed data, and freeing it
 * (see mesh.h). */
#include "mesh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mem.h"

/* How many vertices of one position a corner compares with before making its own: keeps a
 * file that gives one position thousands of different uvs linear, at the price of a few
 * duplicate vertices. */
#define MESH_CHAIN_MAX 32

/* A vertex is one distinct corner: these four values. */
struct vkey {
    uint32_t pos, uv, nrm;
    uint32_t material;
};

static void normalise_or_z(const double v[3], float out[3])
{
    double len = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (len > 0 && isfinite(len)) {
        out[0] = (float)(v[0] / len);
        out[1] = (float)(v[1] / len);
        out[2] = (float)(v[2] / len);
    } else {
        out[0] = 0;
        out[1] = 0;
        out[2] = 1;
    }
}

static int check_corners(const struct mesh_source *s, struct err *e)
{
    for (size_t i = 0; i < (size_t)s->n_tris * 3; i++) {
        const struct mesh_corner *c = &s->corners[i];
        if (c->pos >= s->n_pos || (c->uv != MESH_NONE && c->uv >= s->n_uv) ||
            (c->nrm != MESH_NONE && c->nrm >= s->n_nrm))
            return err_set(e, "mesh corner %zu of triangle %zu indexes past its arrays", i % 3,
                           i / 3);
    }
    return 0;
}

/* The face normal of triangle t: cross(p1 - p0, p2 - p0), unnormalised (its length is twice
 * the area: the sums below are area-weighted). */
static void face_normal(const struct mesh_source *s, uint32_t t, double n[3])
{
    const struct mesh_corner *c = &s->corners[(size_t)t * 3];
    const float *p0 = &s->pos[(size_t)c[0].pos * 3];
    const float *p1 = &s->pos[(size_t)c[1].pos * 3];
    const float *p2 = &s->pos[(size_t)c[2].pos * 3];
    double a[3] = {(double)p1[0] - p0[0], (double)p1[1] - p0[1], (double)p1[2] - p0[2]};
    double b[3] = {(double)p2[0] - p0[0], (double)p2[1] - p0[1], (double)p2[2] - p0[2]};
    n[0] = a[1] * b[2] - a[2] * b[1];
    n[1] = a[2] * b[0] - a[0] * b[2];
    n[2] = a[0] * b[1] - a[1] * b[0];
}

/* Generated normals (mesh.h): per corner the index of its fan's normal in *sums_out (n
 * fans, 3 doubles each, unnormalised), in *fan_out (3 per triangle). Fans are numbered
 * position by position; a position without creases is one fan whose sum adds the same
 * face normals in the same order as one smooth sum per position would (the same bits).
 * -1 when out of memory. */
struct fan_edge {
    uint32_t q, j; /* the edge's other position, the incidence (index into the position's) */
};

static int fan_edge_cmp(const void *a, const void *b)
{
    const struct fan_edge *x = a, *y = b;
    return x->q != y->q ? (x->q < y->q ? -1 : 1) : (x->j < y->j ? -1 : x->j > y->j);
}

/* Sort by (q, j). Equal keys are equal edges, so any sort gives the same list; most
 * positions have a dozen edges, where insertion beats qsort's calls (5% of the 1M
 * sphere's load). */
static void sort_edges(struct fan_edge *e, size_t n)
{
    if (n > 32) {
        qsort(e, n, sizeof *e, fan_edge_cmp);
        return;
    }
    for (size_t i = 1; i < n; i++) {
        struct fan_edge x = e[i];
        size_t k = i;
        for (; k > 0 && fan_edge_cmp(&x, &e[k - 1]) < 0; k--)
            e[k] = e[k - 1];
        e[k] = x;
    }
}

static uint32_t uf_find(uint32_t *up, uint32_t i)
{
    while (up[i] != i)
        i = up[i] = up[up[i]];
    return i;
}

static int crease_fans(const struct mesh_source *s, double cos_crease, bool smooth,
                       uint32_t **fan_out, double **sums_out, uint32_t *n_out)
{
    const uint32_t nt = s->n_tris;
    const size_t nc = (size_t)nt * 3;
    double *fn = malloc((size_t)nt * 3 * sizeof *fn);
    uint32_t *off = calloc((size_t)s->n_pos + 1, sizeof *off);
    uint32_t *inc = malloc(nc * sizeof *inc); /* incidences: corner index t * 3 + k */
    uint32_t *fan = malloc(nc * sizeof *fan);
    struct fan_edge *edges = NULL;
    uint32_t *up = NULL, *local = NULL;
    size_t cap = 0;
    double *sums = NULL;
    int rc = -1;
    if (!fn || !off || !inc || !fan)
        goto done;
    mem_big(fn, (size_t)nt * 3 * sizeof *fn);
    mem_big(inc, nc * sizeof *inc);
    mem_big(fan, nc * sizeof *fan);
    for (uint32_t t = 0; t < nt; t++)
        face_normal(s, t, &fn[(size_t)t * 3]);
    for (size_t i = 0; i < nc; i++)
        off[s->corners[i].pos + 1]++;
    for (uint32_t p = 0; p < s->n_pos; p++)
        off[p + 1] += off[p];
    for (size_t i = 0; i < nc; i++) /* in corner order: each position's list is too */
        inc[off[s->corners[i].pos]++] = (uint32_t)i;
    for (uint32_t p = s->n_pos; p > 0; p--) /* (the fill moved each start to the next's) */
        off[p] = off[p - 1];
    off[0] = 0;
    uint32_t n_fans = 0;
    for (uint32_t p = 0; p < s->n_pos; p++) {
        const uint32_t a = off[p], deg = off[p + 1] - a;
        if (deg == 0)
            continue;
        if (smooth || deg == 1) {
            for (uint32_t j = 0; j < deg; j++)
                fan[inc[a + j]] = n_fans;
            n_fans++;
            continue;
        }
        if (2 * (size_t)deg > cap) {
            cap = 4 * (size_t)deg;
            struct fan_edge *ne = realloc(edges, cap * sizeof *ne);
            uint32_t *nu = ne ? realloc(up, cap * sizeof *nu) : NULL;
            uint32_t *nl = nu ? realloc(local, cap * sizeof *nl) : NULL;
            if (ne)
                edges = ne;
            if (nu)
                up = nu;
            if (!nl)
                goto done;
            local = nl;
        }
        /* the two edges at p of each incidence, sorted by their other end: triangles that
         * share an edge through p are neighbours in the list */
        for (uint32_t j = 0; j < deg; j++) {
            uint32_t ci = inc[a + j], t = ci / 3, k = ci % 3;
            edges[2 * j] = (struct fan_edge){s->corners[(size_t)t * 3 + (k + 1) % 3].pos, j};
            edges[2 * j + 1] = (struct fan_edge){s->corners[(size_t)t * 3 + (k + 2) % 3].pos, j};
            up[j] = j;
        }
        sort_edges(edges, 2 * (size_t)deg);
        bool crease = false;
        for (size_t e = 1; e < 2 * (size_t)deg; e++) {
            if (edges[e].q != edges[e - 1].q || edges[e].q == p)
                continue;
            uint32_t ja = edges[e - 1].j, jb = edges[e].j;
            uint32_t ta = inc[a + ja] / 3, tb = inc[a + jb] / 3;
            const double *na = &fn[(size_t)ta * 3], *nb = &fn[(size_t)tb * 3];
            double la = sqrt(na[0] * na[0] + na[1] * na[1] + na[2] * na[2]);
            double lb = sqrt(nb[0] * nb[0] + nb[1] * nb[1] + nb[2] * nb[2]);
            double d = na[0] * nb[0] + na[1] * nb[1] + na[2] * nb[2];
            if (ta != tb && la > 0 && lb > 0 && d < cos_crease * la * lb) {
                crease = true; /* a degenerate face creases nothing */
                continue;
            }
            up[uf_find(up, ja)] = uf_find(up, jb);
        }
        if (!crease) {
            for (uint32_t j = 0; j < deg; j++)
                fan[inc[a + j]] = n_fans;
            n_fans++;
            continue;
        }
        for (uint32_t j = 0; j < deg; j++) /* a triangle's two corners at p: one fan */
            for (uint32_t i = j + 1; i < deg && inc[a + i] / 3 == inc[a + j] / 3; i++)
                up[uf_find(up, i)] = uf_find(up, j);
        for (uint32_t j = 0; j < deg; j++)
            local[j] = UINT32_MAX;
        for (uint32_t j = 0; j < deg; j++) { /* fans numbered in order of first corner */
            uint32_t r = uf_find(up, j);
            if (local[r] == UINT32_MAX)
                local[r] = n_fans++;
            fan[inc[a + j]] = local[r];
        }
    }
    sums = calloc(n_fans ? n_fans : 1, 3 * sizeof *sums);
    mem_big(sums, (size_t)n_fans * 3 * sizeof *sums);
    if (!sums)
        goto done;
    for (size_t i = 0; i < nc; i++) { /* triangle by triangle: the order of the smooth sum */
        double *d = &sums[(size_t)fan[i] * 3];
        const double *n = &fn[(i / 3) * 3];
        d[0] += n[0];
        d[1] += n[1];
        d[2] += n[2];
    }
    *fan_out = fan;
    *sums_out = sums;
    *n_out = n_fans;
    fan = NULL;
    sums = NULL;
    rc = 0;
done:
    free(fn);
    free(off);
    free(inc);
    free(fan);
    free(edges);
    free(up);
    free(local);
    free(sums);
    return rc;
}

static void set_bounds(struct mesh *m)
{
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (uint32_t i = 0; i < m->n_verts; i++)
        for (int k = 0; k < 3; k++) {
            lo[k] = fminf(lo[k], m->verts[i].pos[k]);
            hi[k] = fmaxf(hi[k], m->verts[i].pos[k]);
        }
    double c[3], r2 = 0;
    for (int k = 0; k < 3; k++) {
        m->bbox_min[k] = lo[k];
        m->bbox_max[k] = hi[k];
        c[k] = 0.5 * ((double)lo[k] + hi[k]);
        m->center[k] = (float)c[k];
    }
    /* distances from the float centre the renderer will use, so the sphere really holds
     * every vertex; rounded up when converting the radius to float */
    for (uint32_t i = 0; i < m->n_verts; i++) {
        double d2 = 0;
        for (int k = 0; k < 3; k++) {
            double d = (double)m->verts[i].pos[k] - m->center[k];
            d2 += d * d;
        }
        r2 = d2 > r2 ? d2 : r2;
    }
    double r = sqrt(r2);
    m->radius = (float)r;
    if ((double)m->radius < r)
        m->radius = nextafterf(m->radius, INFINITY);
}

static void drop_geometry(struct mesh *m)
{
    free(m->verts);
    free(m->tris);
    free(m->tri_material);
    free(m->vert_material);
    free(m->colors);
    free(m->uv1);
    free(m->tangents);
    free(m->pos_id);
    free(m->pos_xyz);
    m->pos_id = NULL;
    m->pos_xyz = NULL;
    m->n_pos = 0;
    m->colors = NULL;
    m->uv1 = NULL;
    m->tangents = NULL;
    m->verts = NULL;
    m->tris = NULL;
    m->tri_material = NULL;
    m->vert_material = NULL;
    m->n_verts = m->n_tris = 0;
}

int mesh_build(const struct mesh_source *s, struct mesh *out, struct err *e)
{
    out->verts = NULL;
    out->tris = NULL;
    out->tri_material = NULL;
    out->vert_material = NULL;
    out->colors = NULL;
    out->uv1 = NULL;
    out->tangents = NULL;
    out->pos_id = NULL;
    out->pos_xyz = NULL;
    out->n_pos = 0;
    out->n_verts = out->n_tris = out->n_opaque = 0;
    out->has_uvs = out->has_normals = false;
    if (s->n_tris == 0)
        return err_set(e, "mesh has no triangles");
    /* every corner may be a new vertex: keep 3 * n_tris within uint32 */
    if (s->n_tris > UINT32_MAX / 3)
        return err_set(e, "mesh has %u triangles (limit %u)", (unsigned)s->n_tris,
                       (unsigned)(UINT32_MAX / 3));
    if (check_corners(s, e))
        return -1;

    size_t n_corners = (size_t)s->n_tris * 3;
    bool need_generated = false;
    for (size_t i = 0; i < n_corners; i++) {
        out->has_uvs |= s->corners[i].uv != MESH_NONE;
        out->has_normals |= s->corners[i].nrm != MESH_NONE;
        need_generated |= s->corners[i].nrm == MESH_NONE;
    }
    /* generated normals: corner i's fan is fan[i], its normal key s->n_nrm + fan[i] (keys
     * of given normals stay below) */
    uint32_t *fan = NULL, n_fans = 0;
    double *acc = NULL;
    if (need_generated) {
        if ((uint64_t)s->n_nrm + n_corners >= MESH_NONE)
            return err_set(e, "mesh has too many normals (%u) for its %u triangles",
                           (unsigned)s->n_nrm, (unsigned)s->n_tris);
        double deg = s->crease_set ? s->crease_deg : MESH_CREASE_DEFAULT;
        bool smooth = !(deg < 180);
        double cos_crease = smooth ? -1 : cos((deg > 0 ? deg : 0) * (M_PI / 180.0));
        if (crease_fans(s, cos_crease, smooth, &fan, &acc, &n_fans))
            return err_set(e, "out of memory building a mesh of %u triangles",
                           (unsigned)s->n_tris);
    }

    /* Corners that share a position are chained from it (head[pos] -> next[...]): a new
     * corner only compares with the few vertices made from its own position, and the
     * arrays are walked in the file's order, which keeps them in cache (a hash table
     * probed at random cost twice as much on the 300k-triangle sports car). */
    size_t cap_v = s->n_pos < n_corners ? s->n_pos : n_corners;
    if (need_generated && cap_v < n_fans) /* each fan is a vertex at least: no realloc (it */
        cap_v = n_fans;                   /* copied the arrays of the 1M sphere) */
    cap_v = cap_v < 16 ? 16 : cap_v;
    struct vkey *keys = malloc(cap_v * sizeof *keys);
    uint32_t *next = malloc(cap_v * sizeof *next);
    uint32_t *head = calloc(s->n_pos ? s->n_pos : 1, sizeof *head); /* vertex + 1, 0 none */
    out->tris = malloc((size_t)s->n_tris * sizeof *out->tris);
    out->tri_material = malloc((size_t)s->n_tris * sizeof *out->tri_material);
    if (!keys || !next || !head || !out->tris || !out->tri_material)
        goto oom;
    mem_big(keys, cap_v * sizeof *keys);
    mem_big(next, cap_v * sizeof *next);
    mem_big(head, (size_t)s->n_pos * sizeof *head);
    mem_big(out->tris, (size_t)s->n_tris * sizeof *out->tris);

    uint32_t n = 0;
    for (uint32_t t = 0; t < s->n_tris; t++) {
        uint16_t mat = s->tri_material ? s->tri_material[t] : 0;
        out->tri_material[t] = mat;
        for (int k = 0; k < 3; k++) {
            const struct mesh_corner *c = &s->corners[(size_t)t * 3 + (size_t)k];
            const uint32_t nrm = c->nrm != MESH_NONE ? c->nrm
                                                     : s->n_nrm + fan[(size_t)t * 3 + (size_t)k];
            uint32_t v = head[c->pos];
            for (int walk = 0; v && !(keys[v - 1].uv == c->uv && keys[v - 1].nrm == nrm &&
                                      keys[v - 1].material == mat);
                 walk++) /* past MESH_CHAIN_MAX a duplicate vertex is made: harmless */
                v = walk < MESH_CHAIN_MAX ? next[v - 1] : 0;
            if (v == 0) {
                if (n == cap_v) {
                    size_t cap = cap_v * 2 < n_corners ? cap_v * 2 : n_corners;
                    struct vkey *nk = realloc(keys, cap * sizeof *keys);
                    if (nk)
                        keys = nk;
                    uint32_t *nn = nk ? realloc(next, cap * sizeof *next) : NULL;
                    if (!nn)
                        goto oom;
                    next = nn;
                    cap_v = cap;
                }
                keys[n] = (struct vkey){c->pos, c->uv, nrm, mat};
                next[n] = head[c->pos];
                head[c->pos] = ++n;
                v = n;
            }
            out->tris[t][k] = v - 1;
        }
    }
    free(head);
    free(next);
    head = next = NULL;

    out->n_tris = out->n_opaque = s->n_tris;
    out->n_verts = n;
    out->verts = malloc((size_t)n * sizeof *out->verts);
    out->vert_material = malloc((size_t)n * sizeof *out->vert_material);
    if ((s->rgb || s->rgba) && !(out->colors = malloc((size_t)n * sizeof *out->colors)))
        goto oom;
    if (s->uv1 && !(out->uv1 = malloc((size_t)n * sizeof *out->uv1)))
        goto oom;
    if (s->tangent && !(out->tangents = malloc((size_t)n * sizeof *out->tangents)))
        goto oom;
    if (!out->verts || !out->vert_material)
        goto oom;
    mem_big(out->verts, (size_t)n * sizeof *out->verts);
    for (uint32_t i = 0; i < n; i++) {
        const struct vkey *k = &keys[i];
        struct mesh_vertex *v = &out->verts[i];
        memcpy(v->pos, &s->pos[(size_t)k->pos * 3], sizeof v->pos);
        if (k->uv != MESH_NONE) {
            v->uv[0] = s->uv[(size_t)k->uv * 2];
            v->uv[1] = s->uv[(size_t)k->uv * 2 + 1];
        } else {
            v->uv[0] = v->uv[1] = 0;
        }
        if (k->nrm < s->n_nrm) {
            const float *f = &s->nrm[(size_t)k->nrm * 3];
            double d[3] = {f[0], f[1], f[2]};
            normalise_or_z(d, v->nrm);
        } else {
            normalise_or_z(&acc[(size_t)(k->nrm - s->n_nrm) * 3], v->nrm);
        }
        out->vert_material[i] = (uint16_t)k->material;
        if (s->rgba) {
            memcpy(out->colors[i], &s->rgba[(size_t)k->pos * 4], 4);
        } else if (s->rgb) {
            memcpy(out->colors[i], &s->rgb[(size_t)k->pos * 3], 3);
            out->colors[i][3] = 255;
        }
        if (s->uv1)
            memcpy(out->uv1[i], &s->uv1[(size_t)k->pos * 2], sizeof out->uv1[i]);
        if (s->tangent)
            memcpy(out->tangents[i], &s->tangent[(size_t)k->pos * 4], sizeof out->tangents[i]);
    }
    free(acc);
    free(fan);
    free(keys);
    set_bounds(out);
    if (mesh_share_positions(out))
        goto oom;
    return 0;

oom:
    free(acc);
    free(fan);
    free(keys);
    free(next);
    free(head);
    drop_geometry(out);
    return err_set(e, "out of memory building a mesh of %u triangles", (unsigned)s->n_tris);
}

int mesh_share_positions(struct mesh *m)
{
    free(m->pos_id);
    free(m->pos_xyz);
    m->pos_id = NULL;
    m->pos_xyz = NULL;
    m->n_pos = 0;
    const uint32_t n = m->n_verts;
    if (n == 0)
        return 0;
    size_t cap = 16;
    while (cap < 2 * (size_t)n)
        cap *= 2;
    uint32_t *id = malloc((size_t)n * sizeof *id), *first = malloc((size_t)n * sizeof *first);
    uint32_t *slot = calloc(cap, sizeof *slot); /* position + 1, 0 empty */
    if (!id || !first || !slot) {
        free(id);
        free(first);
        free(slot);
        return -1;
    }
    uint32_t np = 0;
    for (uint32_t i = 0; i < n; i++) {
        uint32_t b[3];
        memcpy(b, m->verts[i].pos, sizeof b);
        uint64_t h = ((uint64_t)b[0] * 0x9E3779B97F4A7C15ull) ^
                     ((uint64_t)b[1] * 0xC2B2AE3D27D4EB4Full) ^
                     ((uint64_t)b[2] * 0x165667B19E3779F9ull);
        for (size_t k = (size_t)(h ^ (h >> 29)) & (cap - 1);; k = (k + 1) & (cap - 1)) {
            if (!slot[k]) {
                first[np] = i;
                id[i] = np++;
                slot[k] = np;
                break;
            }
            if (!memcmp(m->verts[first[slot[k] - 1]].pos, b, sizeof b)) {
                id[i] = slot[k] - 1;
                break;
            }
        }
    }
    free(slot);
    if (2 * (uint64_t)np > n) { /* (walking by position would not pay: none kept) */
        free(id);
        free(first);
        return 0;
    }
    float(*xyz)[3] = malloc((size_t)np * sizeof *xyz);
    if (!xyz) {
        free(id);
        free(first);
        return -1;
    }
    for (uint32_t p = 0; p < np; p++)
        memcpy(xyz[p], m->verts[first[p]].pos, sizeof xyz[p]);
    free(first);
    m->pos_id = id;
    m->pos_xyz = xyz;
    m->n_pos = np;
    return 0;
}

/* v with axis `axis` turned to +Y (mesh_turn_up) */
static void turn3(float *v, char axis)
{
    float x = v[0], y = v[1], z = v[2];
    if (axis == 'z')
        v[0] = x, v[1] = z, v[2] = -y;
    else if (axis == 'x')
        v[0] = -y, v[1] = x, v[2] = z;
}

void mesh_turn_up(struct mesh *m, char axis)
{
    if (axis != 'x' && axis != 'z')
        return;
    for (uint32_t i = 0; i < m->n_verts; i++) {
        turn3(m->verts[i].pos, axis);
        turn3(m->verts[i].nrm, axis);
        if (m->tangents)
            turn3(m->tangents[i], axis);
    }
    for (uint32_t i = 0; i < m->n_cameras; i++) {
        turn3(m->cameras[i].eye, axis);
        turn3(m->cameras[i].forward, axis);
        turn3(m->cameras[i].up, axis);
    }
    if (m->n_verts)
        set_bounds(m);
}

/* ---- tangents ---- */

static double dot3(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* the angle at corner a of the triangle a b c */
static double corner_angle(const float *a, const float *b, const float *c)
{
    double u[3], v[3];
    for (int k = 0; k < 3; k++)
        u[k] = (double)b[k] - a[k], v[k] = (double)c[k] - a[k];
    double lu = sqrt(dot3(u, u)), lv = sqrt(dot3(v, v));
    if (!(lu > 0 && lv > 0))
        return 0;
    double x = dot3(u, v) / (lu * lv);
    return acos(x < -1 ? -1 : x > 1 ? 1 : x);
}

int mesh_tangents(struct mesh *m, bool second)
{
    const uint32_t nv = m->n_verts;
    /* per vertex: sums of the two handednesses, 4 doubles each (xyz, weight) */
    double *acc = calloc((size_t)nv * 8, sizeof *acc);
    int8_t *tri_sign = malloc((size_t)m->n_tris + 1);
    if (!acc || !tri_sign) {
        free(acc);
        free(tri_sign);
        return -1;
    }
    for (uint32_t t = 0; t < m->n_tris; t++) {
        const uint32_t *c = m->tris[t];
        const float *p[3], *w[3];
        for (int k = 0; k < 3; k++) {
            p[k] = m->verts[c[k]].pos;
            w[k] = second ? m->uv1[c[k]] : m->verts[c[k]].uv;
        }
        double e1[3], e2[3];
        for (int k = 0; k < 3; k++)
            e1[k] = (double)p[1][k] - p[0][k], e2[k] = (double)p[2][k] - p[0][k];
        double du1 = (double)w[1][0] - w[0][0], dv1 = (double)w[1][1] - w[0][1];
        double du2 = (double)w[2][0] - w[0][0], dv2 = (double)w[2][1] - w[0][1];
        double r = du1 * dv2 - du2 * dv1;
        tri_sign[t] = 0;
        if (!(fabs(r) > 1e-20) || !isfinite(r))
            continue; /* no uv area: no direction */
        double sd[3], td[3]; /* dP/du, dP/dv */
        for (int k = 0; k < 3; k++) {
            sd[k] = (e1[k] * dv2 - e2[k] * dv1) / r;
            td[k] = (e2[k] * du1 - e1[k] * du2) / r;
        }
        double fn[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                        e1[0] * e2[1] - e1[1] * e2[0]};
        double cr[3] = {fn[1] * sd[2] - fn[2] * sd[1], fn[2] * sd[0] - fn[0] * sd[2],
                        fn[0] * sd[1] - fn[1] * sd[0]};
        int sign = dot3(cr, td) < 0 ? -1 : 1;
        tri_sign[t] = (int8_t)sign;
        for (int k = 0; k < 3; k++) {
            const float *nf = m->verts[c[k]].nrm;
            double n[3] = {nf[0], nf[1], nf[2]}, d = dot3(n, sd), tk[3];
            for (int j = 0; j < 3; j++)
                tk[j] = sd[j] - n[j] * d;
            double l = sqrt(dot3(tk, tk));
            double a = corner_angle(p[k], p[(k + 1) % 3], p[(k + 2) % 3]);
            if (!(l > 0) || !isfinite(l))
                continue;
            double *s = &acc[(size_t)c[k] * 8 + (sign < 0 ? 4 : 0)];
            for (int j = 0; j < 3; j++)
                s[j] += tk[j] / l * a;
            s[3] += a > 0 ? a : 1e-12;
        }
    }
    /* vertices both handednesses use: a copy for the negative one */
    uint32_t extra = 0;
    for (uint32_t v = 0; v < nv; v++)
        extra += acc[(size_t)v * 8 + 3] > 0 && acc[(size_t)v * 8 + 7] > 0;
    uint32_t *twin = NULL;
    if (extra) {
        twin = malloc((size_t)nv * sizeof *twin);
        struct mesh_vertex *nvx = realloc(m->verts, (size_t)(nv + extra) * sizeof *nvx);
        if (nvx)
            m->verts = nvx;
        uint16_t *nvm = nvx ? realloc(m->vert_material, (size_t)(nv + extra) * sizeof *nvm) : NULL;
        if (nvm)
            m->vert_material = nvm;
        bool ok = twin && nvx && nvm;
        if (ok && m->colors) {
            uint8_t(*nc)[4] = realloc(m->colors, (size_t)(nv + extra) * sizeof *nc);
            ok = nc != NULL;
            if (nc)
                m->colors = nc;
        }
        if (ok && m->uv1) {
            float(*nu)[2] = realloc(m->uv1, (size_t)(nv + extra) * sizeof *nu);
            ok = nu != NULL;
            if (nu)
                m->uv1 = nu;
        }
        if (!ok) {
            free(twin);
            free(acc);
            free(tri_sign);
            return -1;
        }
        uint32_t k = nv;
        for (uint32_t v = 0; v < nv; v++) {
            twin[v] = UINT32_MAX;
            if (!(acc[(size_t)v * 8 + 3] > 0 && acc[(size_t)v * 8 + 7] > 0))
                continue;
            twin[v] = k;
            m->verts[k] = m->verts[v];
            m->vert_material[k] = m->vert_material[v];
            if (m->colors)
                memcpy(m->colors[k], m->colors[v], sizeof m->colors[k]);
            if (m->uv1)
                memcpy(m->uv1[k], m->uv1[v], sizeof m->uv1[k]);
            k++;
        }
        for (uint32_t t = 0; t < m->n_tris; t++)
            if (tri_sign[t] < 0)
                for (int c = 0; c < 3; c++)
                    if (twin[m->tris[t][c]] != UINT32_MAX)
                        m->tris[t][c] = twin[m->tris[t][c]];
    }
    m->tangents = malloc((size_t)(nv + extra) * sizeof *m->tangents);
    if (!m->tangents) {
        free(twin);
        free(acc);
        free(tri_sign);
        return -1;
    }
    for (uint32_t v = 0; v < nv; v++) {
        const double *pos = &acc[(size_t)v * 8], *neg = pos + 4;
        /* a vertex of one handedness; its twin (if any) the negative one */
        const double *own = pos[3] > 0 ? pos : neg;
        float w = pos[3] > 0 || !(neg[3] > 0) ? 1.0f : -1.0f;
        uint32_t dst[2] = {v, twin && twin[v] != UINT32_MAX ? twin[v] : UINT32_MAX};
        const double *src[2] = {own, neg};
        float sg[2] = {w, -1};
        for (int i = 0; i < 2; i++) {
            if (dst[i] == UINT32_MAX)
                continue;
            const float *nf = m->verts[v].nrm;
            double n[3] = {nf[0], nf[1], nf[2]}, t[3] = {src[i][0], src[i][1], src[i][2]};
            double d = dot3(n, t);
            for (int j = 0; j < 3; j++)
                t[j] -= n[j] * d;
            double l = sqrt(dot3(t, t));
            if (!(l > 1e-12) || !isfinite(l)) { /* any direction in the normal's plane */
                double a[3] = {fabs(n[0]) < 0.9 ? 1 : 0, fabs(n[0]) < 0.9 ? 0 : 1, 0};
                d = dot3(n, a);
                for (int j = 0; j < 3; j++)
                    t[j] = a[j] - n[j] * d;
                l = sqrt(dot3(t, t));
            }
            for (int j = 0; j < 3; j++)
                m->tangents[dst[i]][j] = (float)(t[j] / l);
            m->tangents[dst[i]][3] = sg[i];
        }
    }
    m->n_verts = nv + extra;
    if (extra) /* (the clusters' vertex reach is stale: built again by whoever wants them) */
        mesh_free_clusters(m);
    if (extra && mesh_share_positions(m)) { /* (the twins share their vertex's position) */
        free(twin);
        free(acc);
        free(tri_sign);
        return -1;
    }
    free(twin);
    free(acc);
    free(tri_sign);
    return 0;
}

void mesh_free_clusters(struct mesh *m)
{
    if (!m->clusters)
        return;
    free(m->clusters->c);
    free(m->clusters);
    m->clusters = NULL;
}

bool mesh_positions_finite(const struct mesh *m)
{
    for (uint32_t v = 0; v < m->n_verts; v++)
        for (int k = 0; k < 3; k++)
            if (!isfinite(m->verts[v].pos[k]))
                return false;
    return true;
}

void mesh_free(struct mesh *m)
{
    mesh_free_clusters(m);
    drop_geometry(m);
    free(m->materials);
    free(m->cameras);
    for (uint32_t i = 0; i < m->n_textures; i++)
        texture_free(&m->textures[i]);
    free(m->textures);
    memset(m, 0, sizeof *m);
}

size_t mesh_geometry_bytes(const struct mesh *m)
{
    const size_t nv = m->n_verts, nt = m->n_tris;
    return nv * sizeof *m->verts + nt * (sizeof *m->tris + sizeof *m->tri_material) +
           (m->vert_material ? nv * sizeof *m->vert_material : 0) +
           (m->pos_id ? nv * sizeof *m->pos_id + m->n_pos * sizeof *m->pos_xyz : 0) +
           (m->colors ? nv * sizeof *m->colors : 0) + (m->uv1 ? nv * sizeof *m->uv1 : 0) +
           (m->tangents ? nv * sizeof *m->tangents : 0);
}
