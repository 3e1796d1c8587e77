/* lod.c: the chain of simplified meshes (meshoptimizer) and the level a frame draws
 * (see lod.h). */
#include "lod.h"

#include <math.h>
#include <pthread.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include <meshoptimizer.h>

#include "cluster.h"
#include "dag.h"
#include "lod_cache.h"
#include "tiles.h"

struct mesh_lod {
    atomic_int n_ready;                 /* levels[0 .. n_ready) are complete */
    struct mesh levels[LOD_MAX_LEVELS]; /* levels[k] is level k + 1 */
    double error[LOD_MAX_LEVELS];       /* levels[k]'s error, object-space units */
    double shade[LOD_MAX_LEVELS];       /* levels[k]'s shading error, radians (lod_shade_error) */
    double area;                        /* the source's surface area, object units squared */
    uint32_t *root[LOD_MAX_LEVELS];     /* levels[k]'s vertices as the source's (while the
                                           chain is built, for the cache) */
    int cache;                          /* enum lod_cache_use */
    struct material *mats;              /* a tiled chain's materials (tiles.h), every
                                           level's; NULL: the source's */
};

struct lod_job {
    pthread_t thread;
    struct mesh *meshes;
    int n;
    atomic_bool cancel, done;
    bool clusters; /* the cluster hierarchies first */
};

_Static_assert(sizeof(unsigned int) == sizeof(uint32_t), "meshoptimizer indices are ours");
_Static_assert(LOD_CACHE_LEVELS == LOD_MAX_LEVELS, "a cache file holds a whole chain");

/* a level's own arrays (its materials and textures are the source's) */
static void level_free(struct mesh *l)
{
    free(l->verts);
    free(l->tris);
    free(l->tri_material);
    free(l->vert_material);
    free(l->colors);
    free(l->pos_id);
    free(l->pos_xyz);
    mesh_free_clusters(l);
    memset(l, 0, sizeof *l);
}

/* A level's geometry: the triangles idx[0 .. n_idx) of src, with only the vertices they use,
 * in order of first use; textures and bounds are the source mesh's (borrowed), materials
 * src's (the source's, or a tiled chain's). tiles: src is the root, and its tiled vertices
 * get their tile uvs and derived materials (tiles.h), tiles->mats the level's. */
static int make_level(const struct mesh *root, const struct mesh *src, const uint32_t *idx,
                      size_t n_idx, struct mesh *out, const uint32_t *src_root,
                      uint32_t **root_out, const struct mesh_tiles *tiles)
{
    memset(out, 0, sizeof *out);
    uint32_t *remap = malloc((size_t)src->n_verts * sizeof *remap);
    if (!remap)
        return -1;
    size_t nv = meshopt_optimizeVertexFetchRemap(remap, idx, n_idx, src->n_verts);
    /* (root_out: each new vertex as the root's, through src's own map; NULL: src is root) */
    uint32_t *to_root = root_out ? malloc((nv ? nv : 1) * sizeof *to_root) : NULL;
    if (root_out && !to_root) {
        free(remap);
        return -1;
    }
    uint32_t nt = (uint32_t)(n_idx / 3);
    out->verts = malloc(nv * sizeof *out->verts);
    out->vert_material = malloc(nv * sizeof *out->vert_material);
    out->tris = malloc((size_t)nt * sizeof *out->tris);
    out->tri_material = malloc((size_t)nt * sizeof *out->tri_material);
    if (src->colors)
        out->colors = malloc(nv * sizeof *out->colors);
    if (!out->verts || !out->vert_material || !out->tris || !out->tri_material ||
        (src->colors && !out->colors)) {
        free(remap);
        free(to_root);
        level_free(out);
        return -1;
    }
    for (uint32_t v = 0; v < src->n_verts; v++) {
        uint32_t d = remap[v];
        if (d == UINT32_MAX)
            continue;
        out->verts[d] = src->verts[v];
        out->vert_material[d] = src->vert_material[v];
        if (tiles) /* (src is the root: its tiled vertices get their tile uvs) */
            tiles_vertex(tiles, root, v, &out->verts[d], &out->vert_material[d]);
        if (to_root)
            to_root[d] = src_root ? src_root[v] : v;
        if (out->colors)
            memcpy(out->colors[d], src->colors[v], sizeof out->colors[d]);
    }
    for (uint32_t t = 0; t < nt; t++) {
        for (int k = 0; k < 3; k++)
            out->tris[t][k] = remap[idx[3 * (size_t)t + (size_t)k]];
        /* a triangle's corners share its material: seams are never crossed (lod.h) */
        out->tri_material[t] = out->vert_material[out->tris[t][0]];
    }
    free(remap);
    if (root_out)
        *root_out = to_root;
    out->n_verts = (uint32_t)nv;
    out->n_tris = out->n_opaque = nt;
    out->materials = tiles ? tiles->mats : src->materials; /* (a tiled chain's, or the root's) */
    out->n_materials = tiles ? tiles->n_mats : src->n_materials;
    out->features = root->features;
    out->one_sided = root->one_sided;
    out->textures = root->textures;
    out->n_textures = root->n_textures;
    out->has_uvs = root->has_uvs;
    out->has_normals = root->has_normals;
    memcpy(out->bbox_min, root->bbox_min, sizeof out->bbox_min);
    memcpy(out->bbox_max, root->bbox_max, sizeof out->bbox_max);
    memcpy(out->center, root->center, sizeof out->center);
    out->radius = root->radius;
    mesh_share_positions(out); /* (out of memory: NULL, each vertex positioned alone) */
    cluster_build(out);        /* (out of memory: none, drawn triangle by triangle) */
    return 0;
}

/* the sum of the triangles' areas */
static double mesh_area(const struct mesh *m)
{
    double sum = 0;
    for (uint32_t t = 0; t < m->n_tris; t++) {
        vec3 p[3];
        for (int k = 0; k < 3; k++) {
            const float *q = m->verts[m->tris[t][k]].pos;
            p[k] = v3(q[0], q[1], q[2]);
        }
        sum += 0.5 * v3_len(v3_cross(v3_sub(p[1], p[0]), v3_sub(p[2], p[0])));
    }
    return sum;
}

static float extent(const struct mesh *m)
{
    return meshopt_simplifyScale(m->verts[0].pos, m->n_verts, sizeof *m->verts);
}

/* Can m have a chain? (Not with second uvs or tangents, which its levels would need, nor
 * with blended triangles, which stay apart; a mesh drawn by the features path only of atlas
 * tiles, which build_chain finds.) */
static bool chain_fits(const struct mesh *m)
{
    return m->n_tris >= 2 * LOD_MIN_TRIS && m->vert_material && !m->uv1 && !m->tangents &&
           m->n_opaque == m->n_tris;
}

static bool eligible(const struct mesh *m)
{
    return !m->lod && chain_fits(m);
}

uint64_t lod_chain_key(const struct mesh *m)
{
    /* (and the shading error's weighting by material, lod_shade_weight: 2) */
    const double rules[] = {LOD_MAX_LEVELS, LOD_MIN_TRIS, LOD_MAX_ERROR, LOD_CALM,
                            LOD_CALM_SHARE, LOD_CALM_KEEP, 2};
    return lod_cache_key(m, rules, (int)(sizeof rules / sizeof *rules));
}

/* The chain from the cache's file, made as the simplifier's output made it: 0, or -1 (no
 * usable file, or out of memory: m has no levels then) */
static int chain_from_cache(struct mesh *m, struct mesh_lod *l, uint64_t key)
{
    struct lod_cached c;
    if (lod_cache_read(m, key, &c))
        return -1;
    int k = 0;
    for (; k < c.n_levels; k++) {
        if (make_level(m, m, c.idx[k], (size_t)c.n_tris[k] * 3, &l->levels[k], NULL, NULL, NULL))
            break;
        l->error[k] = c.error[k];
        l->shade[k] = c.shade[k];
    }
    lod_cached_free(&c);
    if (k < c.n_levels) {
        while (k > 0)
            level_free(&l->levels[--k]);
        return -1;
    }
    l->cache = LOD_CACHE_READ;
    atomic_store_explicit(&l->n_ready, k, memory_order_release);
    return 0;
}

/* The finished chain into the cache: each level's triangles as the source's vertices */
static void chain_to_cache(struct mesh *m, struct mesh_lod *l, uint64_t key, int n)
{
    struct lod_cached c = {.n_levels = n};
    for (int k = 0; k < n; k++) {
        const struct mesh *lv = &l->levels[k];
        c.idx[k] = malloc((size_t)lv->n_tris * 3 * sizeof *c.idx[k]);
        if (!c.idx[k] || !l->root[k]) {
            lod_cached_free(&c);
            return;
        }
        for (size_t i = 0; i < (size_t)lv->n_tris * 3; i++)
            c.idx[k][i] = l->root[k][lv->tris[i / 3][i % 3]];
        c.n_tris[k] = lv->n_tris;
        c.error[k] = l->error[k];
        c.shade[k] = l->shade[k];
    }
    if (lod_cache_write(m, key, &c) == 0)
        l->cache = LOD_CACHE_WRITTEN;
    lod_cached_free(&c);
}

/* w's triangles merged where that costs no error (LOD_TILE_ERROR), LOD_TILE_CHUNK of them
 * at a time in the file's order (which decides ties of depth, and keeps a voxel exporter's
 * neighbouring blocks together), each chunk's border locked: no merged face spans more
 * than its chunk (a face long across the model draws the ties of its edges apart from the
 * short ones it replaced: on the test's block world, merged whole, 36 dB where chunks keep
 * 42). The result into out[0 .. *n), *rel the largest error; 0, or -1 out of memory. */
static int merge_chunks(const struct mesh *w, uint32_t *out, size_t *n, float *rel)
{
    const uint32_t nt = w->n_tris;
    uint32_t *loc = malloc((size_t)w->n_verts * sizeof *loc);
    uint32_t *back = malloc((size_t)LOD_TILE_CHUNK * 3 * sizeof *back);
    uint32_t *in = malloc((size_t)LOD_TILE_CHUNK * 3 * sizeof *in);
    uint32_t *dst = malloc((size_t)LOD_TILE_CHUNK * 3 * sizeof *dst);
    float *pos = malloc((size_t)LOD_TILE_CHUNK * 9 * sizeof *pos);
    int rc = -1;
    if (!loc || !back || !in || !dst || !pos)
        goto out;
    for (uint32_t v = 0; v < w->n_verts; v++)
        loc[v] = UINT32_MAX;
    *n = 0, *rel = 0;
    for (uint32_t c0 = 0; c0 < nt; c0 += LOD_TILE_CHUNK) {
        const uint32_t c1 = nt - c0 > LOD_TILE_CHUNK ? c0 + LOD_TILE_CHUNK : nt;
        uint32_t nv = 0;
        for (uint32_t t = c0; t < c1; t++)
            for (int k = 0; k < 3; k++) {
                const uint32_t v = w->tris[t][k];
                if (loc[v] == UINT32_MAX) {
                    loc[v] = nv, back[nv] = v;
                    memcpy(&pos[3 * (size_t)nv], w->verts[v].pos, 3 * sizeof *pos);
                    nv++;
                }
                in[3 * (size_t)(t - c0) + (size_t)k] = loc[v];
            }
        float r = 0;
        const size_t got = meshopt_simplify(dst, in, (size_t)(c1 - c0) * 3, pos, nv,
                                            3 * sizeof *pos, 0, LOD_TILE_ERROR,
                                            meshopt_SimplifyLockBorder, &r);
        *rel = r > *rel ? r : *rel; /* (of the chunk's extent: as of the mesh's, larger) */
        for (size_t i = 0; i < got; i++)
            out[(*n)++] = back[dst[i]];
        for (uint32_t i = 0; i < nv; i++)
            loc[back[i]] = UINT32_MAX;
    }
    rc = 0;
out:
    free(loc);
    free(back);
    free(in);
    free(dst);
    free(pos);
    return rc;
}

/* A tiled chain's first level: the source over its welded vertices (tiles.h: their tile
 * uvs, the derived materials, which l keeps for every level), merged where that costs no
 * error (merge_chunks: coplanar faces of a tile). *k0: 1 when it
 * made the level, 0 when it merges under a tenth (the chain stops: the seams stay). 0, or
 * -1 out of memory. idx: room for the source's corners. */
static int tiled_level(struct mesh *m, struct mesh_lod *l, struct mesh_tiles *tiles,
                       uint32_t *idx, float scale0, double *error, int *k0)
{
    *k0 = 0;
    const size_t n3 = (size_t)m->n_tris * 3;
    tiles_welded_corners(tiles, m, idx);
    struct mesh w; /* (only the welded vertices: the simplifier sees no wedge unused) */
    if (make_level(m, m, idx, n3, &w, NULL, NULL, tiles))
        return -1;
    float rel = 0;
    size_t n = 0;
    int rc = merge_chunks(&w, idx, &n, &rel);
    if (rc == 0 && n / 3 <= (size_t)m->n_tris * 9 / 10 && n / 3 >= LOD_MIN_TRIS) {
        if (make_level(m, &w, idx, n, &l->levels[0], NULL, NULL, NULL)) {
            rc = -1;
        } else {
            double shade = lod_shade_error(m, &l->levels[0]);
            if (shade < 0) {
                level_free(&l->levels[0]);
                rc = -1;
            } else {
                *error = (double)rel * scale0;
                l->error[0] = *error;
                l->shade[0] = shade;
                l->mats = tiles->mats; /* (the levels' materials: l's from now on) */
                tiles->mats = NULL;
                atomic_store_explicit(&l->n_ready, 1, memory_order_release);
                *k0 = 1;
            }
        }
    }
    level_free(&w);
    return rc;
}

/* The calm level (lod.h): m's calm triangles (those whose material's lod_shade_weight is
 * under LOD_CALM) simplified to LOD_CALM_KEEP of their number into idx, their border with
 * the others locked (there they meet other materials: a seam, which the simplifier would
 * slide along), then every other triangle as it is; *rel the simplifier's error. The
 * indices written, or 0: no calm level (calm triangles under LOD_CALM_SHARE of m's, none
 * other, or they cannot lose a quarter). scratch: room for m's corners. */
static size_t calm_level(const struct mesh *m, uint32_t *idx, uint32_t *scratch, float budget,
                         float *rel)
{
    uint8_t *calm = malloc(m->n_materials ? m->n_materials : 1);
    if (!calm)
        return 0; /* (out of memory: no calm level, the chain goes on without it) */
    for (uint32_t q = 0; q < m->n_materials; q++)
        calm[q] = lod_shade_weight(m, q) < LOD_CALM;
    size_t nc = 0;
    for (uint32_t t = 0; t < m->n_tris; t++)
        nc += calm[m->tri_material[t]];
    size_t got = 0;
    if (nc >= m->n_tris * LOD_CALM_SHARE && nc < m->n_tris) {
        /* the calm ones first in scratch, the others after them, each in their order */
        uint32_t *rest = scratch + 3 * nc;
        size_t c = 0, r = 0;
        for (uint32_t t = 0; t < m->n_tris; t++)
            memcpy(calm[m->tri_material[t]] ? scratch + 3 * c++ : rest + 3 * r++, m->tris[t],
                   3 * sizeof *scratch);
        got = meshopt_simplify(idx, scratch, nc * 3, m->verts[0].pos, m->n_verts,
                               sizeof *m->verts, (size_t)(nc * LOD_CALM_KEEP) * 3, budget,
                               meshopt_SimplifyLockBorder, rel);
        if (got / 3 > nc * 3 / 4)
            got = 0;
        else {
            memcpy(idx + got, rest, r * 3 * sizeof *idx);
            got += r * 3;
        }
    }
    free(calm);
    return got;
}

/* Level after level, each from the one before, until a stop rule of lod.h says no (or, for
 * a large mesh, from the cache: lod_cache.h). */
static int build_chain(struct mesh *m, struct mesh_lod *l, const atomic_bool *cancel)
{
    if (!mesh_positions_finite(m)) /* the simplifier's quadrics cannot hold them: no levels */
        return 0;
    float scale0 = extent(m);
    if (!(scale0 > 0) || !isfinite(scale0)) /* all at one point, or too far apart */
        return 0;
    l->area = mesh_area(m);
    /* a mesh on the features path: a chain only of atlas tiles (tiles.h), from a first level
     * of their welded faces merged where it costs no error */
    struct mesh_tiles tiles = {0};
    if (m->features && tiles_build(m, &tiles))
        return -1;
    if (m->features && !tiles.weld)
        return 0;
    const bool cached = !m->features && m->n_tris >= LOD_CACHE_MIN_TRIS && lod_cache_enabled();
    const uint64_t key = cached ? lod_chain_key(m) : 0;
    if (cached && chain_from_cache(m, l, key) == 0)
        return 0;
    uint32_t *idx = malloc((size_t)m->n_tris * 3 * sizeof *idx);
    if (!idx) {
        tiles_free(&tiles);
        return -1;
    }
    const struct mesh *src = m;
    double error = 0;
    int rc = 0, k0 = 0;
    if (tiles.weld)
        rc = tiled_level(m, l, &tiles, idx, scale0, &error, &k0);
    if (k0 > 0)
        src = &l->levels[0];
    for (int k = k0; rc == 0 && k < LOD_MAX_LEVELS && !(cancel && atomic_load(cancel)) &&
                     !(tiles.weld && !k0); k++) {
        size_t target = src->n_tris / 2;
        float scale = k == 0 ? scale0 : extent(src);
        double budget = (LOD_MAX_ERROR * scale0 - error) / scale; /* relative, what is left */
        if (target < LOD_MIN_TRIS || !(budget > 0))
            break;
        float rel = 0;
        size_t n = 0, most = (size_t)src->n_tris * 3 / 4; /* (triangles a level may keep) */
        if (k == 0 && !m->features) { /* (a tiled chain's materials are all its own) */
            uint32_t *scratch = malloc((size_t)m->n_tris * 3 * sizeof *scratch);
            n = scratch ? calm_level(m, idx, scratch, (float)budget, &rel) : 0;
            free(scratch);
            most = n ? (size_t)m->n_tris * 7 / 8 : most;
        }
        if (!n)
            n = meshopt_simplify(idx, &src->tris[0][0], (size_t)src->n_tris * 3,
                                 src->verts[0].pos, src->n_verts, sizeof *src->verts,
                                 target * 3, (float)budget, 0, &rel);
        if (n / 3 > most || n / 3 < LOD_MIN_TRIS)
            break; /* stalled: seams and borders everywhere, or the error budget is spent */
        if (make_level(m, src, idx, n, &l->levels[k], k ? l->root[k - 1] : NULL,
                       cached ? &l->root[k] : NULL, NULL)) {
            rc = -1;
            break;
        }
        double shade = lod_shade_error(m, &l->levels[k]);
        if (shade < 0) {
            level_free(&l->levels[k]);
            rc = -1;
            break;
        }
        error += (double)rel * scale;
        l->error[k] = error;
        l->shade[k] = shade;
        atomic_store_explicit(&l->n_ready, k + 1, memory_order_release);
        src = &l->levels[k];
    }
    free(idx);
    tiles_free(&tiles);
    int n = atomic_load_explicit(&l->n_ready, memory_order_relaxed);
    if (cached && rc == 0 && n > 0 && !(cancel && atomic_load(cancel)))
        chain_to_cache(m, l, key, n); /* (a chain cut short by a cancel is not the chain) */
    for (int k = 0; k < LOD_MAX_LEVELS; k++) {
        free(l->root[k]);
        l->root[k] = NULL;
    }
    return rc;
}

static int attach(struct mesh *m)
{
    m->lod = calloc(1, sizeof *m->lod);
    if (!m->lod)
        return -1;
    atomic_init(&m->lod->n_ready, 0);
    return 0;
}

int lod_build(struct mesh *m, struct err *e)
{
    if (!eligible(m))
        return 0;
    if (attach(m) || build_chain(m, m->lod, NULL))
        return err_set(e, "out of memory for the levels of detail of %u triangles",
                       (unsigned)m->n_tris);
    return 0;
}

static void *job_main(void *arg)
{
    struct lod_job *j = arg;
    for (int i = 0; i < j->n && !atomic_load(&j->cancel); i++)
        if (j->meshes[i].lod) { /* the hierarchy, else the chain (out of memory: none, or
                                   fewer levels, still fine) */
            if (j->clusters)
                dag_build(&j->meshes[i], &j->cancel);
            if (!dag_of(&j->meshes[i]) && chain_fits(&j->meshes[i]))
                build_chain(&j->meshes[i], j->meshes[i].lod, &j->cancel);
        }
    atomic_store(&j->done, true);
    return NULL;
}

int lod_start(struct mesh *meshes, int n, bool clusters, struct lod_job **out, struct err *e)
{
    *out = NULL;
    int want = 0;
    for (int i = 0; i < n; i++)
        if (eligible(&meshes[i]) || (clusters && !meshes[i].lod && dag_eligible(&meshes[i]))) {
            if (attach(&meshes[i]))
                return err_set(e, "out of memory");
            want++;
        }
    if (!want)
        return 0;
    struct lod_job *j = calloc(1, sizeof *j);
    if (!j)
        return err_set(e, "out of memory");
    j->meshes = meshes;
    j->n = n;
    j->clusters = clusters;
    atomic_init(&j->cancel, false);
    atomic_init(&j->done, false);
    /* the builder takes no signals: the terminal's handlers belong to the main thread */
    sigset_t all, old;
    sigfillset(&all);
    pthread_sigmask(SIG_SETMASK, &all, &old);
    int rc = pthread_create(&j->thread, NULL, job_main, j);
    pthread_sigmask(SIG_SETMASK, &old, NULL);
    if (rc) { /* no thread: build here */
        job_main(j);
        free(j);
        return 0;
    }
    *out = j;
    return 0;
}

bool lod_done(const struct lod_job *j)
{
    return !j || atomic_load(&j->done);
}

void lod_finish(struct lod_job *j, bool cancel)
{
    if (!j)
        return;
    if (cancel)
        atomic_store(&j->cancel, true);
    pthread_join(j->thread, NULL);
    free(j);
}

void lod_free(struct mesh *m)
{
    dag_free(m);
    if (!m->lod)
        return;
    int n = atomic_load(&m->lod->n_ready);
    for (int k = 0; k < n; k++)
        level_free(&m->lod->levels[k]);
    free(m->lod->mats);
    free(m->lod);
    m->lod = NULL;
}

size_t lod_bytes(const struct mesh *m)
{
    size_t b = 0;
    for (int k = 1; k < lod_level_count(m); k++)
        b += mesh_geometry_bytes(lod_level(m, k)) + cluster_bytes(lod_level(m, k));
    if (m->lod)
        b += sizeof *m->lod;
    return b;
}

int lod_level_count(const struct mesh *m)
{
    return m->lod ? 1 + atomic_load_explicit(&m->lod->n_ready, memory_order_acquire) : 1;
}

const struct mesh *lod_level(const struct mesh *m, int k)
{
    return k == 0 ? m : &m->lod->levels[k - 1];
}

double lod_level_error(const struct mesh *m, int k)
{
    return k == 0 ? 0 : m->lod->error[k - 1];
}

int lod_cache_use(const struct mesh *m)
{
    return m->lod ? m->lod->cache : LOD_CACHE_NONE;
}

double lod_level_shade_error(const struct mesh *m, int k)
{
    return k == 0 ? 0 : m->lod->shade[k - 1];
}

double lod_pixels_per_unit(const struct camera *cam, int fb_h, vec3 center, double radius)
{
    if (cam->ortho_height > 0)
        return fb_h / cam->ortho_height;
    vec3 fwd = v3_norm(v3_sub(cam->target, cam->eye));
    double z = v3_dot(v3_sub(center, cam->eye), fwd) - radius; /* the nearest view depth */
    z = z > cam->near ? z : cam->near;
    return fb_h / (2 * z * tan(cam->fov_deg * (M_PI / 360.0)));
}

double lod_share(const struct mesh *m, double px_per_unit, int fb_w, int fb_h)
{
    double r = m->radius * px_per_unit, disc = M_PI * r * r;
    double shadow = m->lod ? m->lod->area / 4 * px_per_unit * px_per_unit : disc;
    double s = (disc < shadow ? disc : shadow) / ((double)fb_w * fb_h);
    return s < 1 ? s : 1;
}

int lod_choose(const struct mesh *m, enum lod_mode mode, float ratio, float max_px,
               double px_per_unit, double share)
{
    int n = lod_level_count(m);
    if (mode == LOD_OFF || n == 1)
        return 0;
    if (mode == LOD_RATIO) { /* nearest by ratio: |log(kept / wanted)| smallest */
        double want = (double)ratio * m->n_tris;
        int best = 0;
        double best_d = INFINITY;
        for (int k = 0; k < n; k++) {
            double d = fabs(log(lod_level(m, k)->n_tris / want));
            if (d < best_d)
                best = k, best_d = d;
        }
        return best;
    }
    /* the shading bound scales with the pixel bound (auto:PX) */
    double shade_max = LOD_SHADE_BOUND * max_px / LOD_DEFAULT_PX / sqrt(share > 1e-9 ? share : 1e-9);
    int k = 0;
    while (k + 1 < n && lod_level_error(m, k + 1) * px_per_unit < max_px &&
           lod_level_shade_error(m, k + 1) < shade_max)
        k++;
    return k;
}
