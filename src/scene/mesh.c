/* mesh.c: building the unique-vertex mesh from corner-indexed data, and freeing it
 * (see mesh.h). */
#include "mesh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>


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

/* Area-weighted normal sums per position over every triangle (file winding). */
static double *position_normals(const struct mesh_source *s)
{
    double *acc = calloc(s->n_pos, 3 * sizeof *acc);
    if (!acc)
        return NULL;
    for (uint32_t t = 0; t < s->n_tris; t++) {
        const struct mesh_corner *c = &s->corners[(size_t)t * 3];
        const float *p0 = &s->pos[(size_t)c[0].pos * 3];
        const float *p1 = &s->pos[(size_t)c[1].pos * 3];
        const float *p2 = &s->pos[(size_t)c[2].pos * 3];
        double a[3] = {(double)p1[0] - p0[0], (double)p1[1] - p0[1], (double)p1[2] - p0[2]};
        double b[3] = {(double)p2[0] - p0[0], (double)p2[1] - p0[1], (double)p2[2] - p0[2]};
        double n[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                       a[0] * b[1] - a[1] * b[0]};
        for (int k = 0; k < 3; k++) {
            double *d = &acc[(size_t)c[k].pos * 3];
            d[0] += n[0];
            d[1] += n[1];
            d[2] += n[2];
        }
    }
    return acc;
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
    m->colors = NULL;
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
    out->n_verts = out->n_tris = 0;
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

    /* Corners that share a position are chained from it (head[pos] -> next[...]): a new
     * corner only compares with the few vertices made from its own position, and the
     * arrays are walked in the file's order, which keeps them in cache (a hash table
     * probed at random cost twice as much on the 300k-triangle sports car). */
    size_t cap_v = s->n_pos < n_corners ? s->n_pos : n_corners;
    cap_v = cap_v < 16 ? 16 : cap_v;
    struct vkey *keys = malloc(cap_v * sizeof *keys);
    uint32_t *next = malloc(cap_v * sizeof *next);
    uint32_t *head = calloc(s->n_pos ? s->n_pos : 1, sizeof *head); /* vertex + 1, 0 none */
    out->tris = malloc((size_t)s->n_tris * sizeof *out->tris);
    out->tri_material = malloc((size_t)s->n_tris * sizeof *out->tri_material);
    if (!keys || !next || !head || !out->tris || !out->tri_material)
        goto oom;

    uint32_t n = 0;
    for (uint32_t t = 0; t < s->n_tris; t++) {
        uint16_t mat = s->tri_material ? s->tri_material[t] : 0;
        out->tri_material[t] = mat;
        for (int k = 0; k < 3; k++) {
            const struct mesh_corner *c = &s->corners[(size_t)t * 3 + (size_t)k];
            uint32_t v = head[c->pos];
            for (int walk = 0; v && !(keys[v - 1].uv == c->uv && keys[v - 1].nrm == c->nrm &&
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
                keys[n] = (struct vkey){c->pos, c->uv, c->nrm, mat};
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

    out->n_tris = s->n_tris;
    out->n_verts = n;
    out->verts = malloc((size_t)n * sizeof *out->verts);
    out->vert_material = malloc((size_t)n * sizeof *out->vert_material);
    if (s->rgb && !(out->colors = malloc((size_t)n * sizeof *out->colors)))
        goto oom;
    double *acc = NULL;
    if (!out->verts || !out->vert_material || (need_generated && !(acc = position_normals(s))))
        goto oom;
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
        if (k->nrm != MESH_NONE) {
            const float *f = &s->nrm[(size_t)k->nrm * 3];
            double d[3] = {f[0], f[1], f[2]};
            normalise_or_z(d, v->nrm);
        } else {
            normalise_or_z(&acc[(size_t)k->pos * 3], v->nrm);
        }
        out->vert_material[i] = (uint16_t)k->material;
        if (out->colors)
            memcpy(out->colors[i], &s->rgb[(size_t)k->pos * 3], 3);
    }
    free(acc);
    free(keys);
    set_bounds(out);
    return 0;

oom:
    free(keys);
    free(next);
    free(head);
    drop_geometry(out);
    return err_set(e, "out of memory building a mesh of %u triangles", (unsigned)s->n_tris);
}

void mesh_free(struct mesh *m)
{
    drop_geometry(m);
    free(m->materials);
    for (uint32_t i = 0; i < m->n_textures; i++)
        texture_free(&m->textures[i]);
    free(m->textures);
    memset(m, 0, sizeof *m);
}
