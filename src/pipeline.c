/* pipeline.c: one frame over a list of draw items (see pipeline.h). */
#include "pipeline.h"

#include <assert.h>
#include <stdlib.h>
#include <string.h>

#include "batch.h"
#include "clip.h"
#include "line.h"
#include "lod.h"
#include "raster.h"
#include "setup.h"
#include "shade.h"
#include "span.h"
#include "timing.h"
#include "vertex.h"
#include "workers.h"

#define PIPELINE_FLUSH_ONE_THREAD 1024
#define PIPELINE_FLUSH_THREADS 512
/* The front end runs the vertex stage in chunks of at least this many vertices just before
 * the first triangle that uses them: it then reads vertex records still in the caches (a
 * mesh whose triangles come in the order of their vertices, as exporters write them; any
 * other order makes the chunks larger, up to the whole mesh at once). With threads too:
 * run on every thread first, the dense models' records (57 MB for lost_empire) were out
 * of the caches again when the front end read them (car 2 threads 7.9 -> 7.2 ms). */
#define PIPELINE_VERTEX_CHUNK 512
/* SPLIT_AUTO takes slices when the frame's meshes have a triangle for every
 * PIPELINE_SLICE_PIXELS pixels, or for every PIPELINE_SLICE_PIXELS_SMALL in a frame of up
 * to PIPELINE_SLICE_SMALL pixels (320x200). Two threads, fastest of each pair (ms): the
 * head 160x96 0.110 against tiles' 0.185, 320x200 0.223 against 0.276, 400x300 0.35
 * against 0.37, 480x360 even, 640x480 0.62 against 0.58; the demo 320x192 1.15 against
 * 1.24, 640x480 5.8 against 3.7 (its floor and teapot are a few large triangles: one
 * slice gets most of the pixels); lost_empire 640x480 12.4 against 14.9, the bunny even,
 * diablo3 (5k triangles) 2.1 against 1.5. */
#define PIPELINE_SLICE_PIXELS 8
#define PIPELINE_SLICE_PIXELS_SMALL 64
#define PIPELINE_SLICE_SMALL 64000

struct item_verts {
    struct vertex_out *v;
    uint32_t cap;
    const struct mesh *level; /* the level of detail this frame draws (chosen once a frame) */
};

struct pipeline {
    struct item_verts *items; /* vertex-stage output per draw item, reused across frames */
    int n_items;
    /* set-up triangles: front end -> back end. With threads, the pool draws one batch
     * while the front end fills the other: batch[cur] is being filled, batch[!cur] is
     * being drawn when in_flight */
    struct batch batch[2];
    int cur;
    bool in_flight;
    int n_threads;            /* the back end's threads, the caller's included */
    struct workers *workers;  /* n_threads - 1 of them */
    struct span_ctx *ctx;     /* one per thread */
    uint32_t flush_at;        /* set-up triangles that make the back end run (see use_threads) */
    /* vertices of set-up triangles waiting for vertex_shade_many (vertex_shade_batched):
     * shaded together before the back end reads them; at most three per set-up triangle */
    uint32_t *vq_idx;
    struct vertex_out **vq_out;
    uint32_t vq_n, vq_cap;
    const struct mesh *vq_mesh;
    /* SPLIT_SLICES (render.h): one single-thread pipeline per thread, each with its own
     * batches and vertex records; slice k > 0 draws into slice_fb[k], slice 0 into the
     * frame's framebuffer. The meshes the frame draws (NULL: skipped), chosen once. */
    struct pipeline **slice;
    struct fb *slice_fb;
    int n_slices;
    const struct mesh **slice_mesh;
    int slice_mesh_cap;
    struct slice_out { /* a slice's results, each on cache lines of its own: a slice counts
                        * as it goes, and two threads writing one line slow both */
        _Alignas(64) struct frame_stats st;
        struct err err;
        int rc;
        double ms; /* how long it took */
    } *slice_out;
    /* where the slices end, as fractions of the frame's triangles (slice k: cut[k] ..
     * cut[k+1]), moved after each frame toward equal times (slice_balance) */
    double slice_cut[WORKERS_MAX + 2];
    double slice_step[WORKERS_MAX + 2]; /* how far cut k may move next (slice_balance) */
    int slice_dir[WORKERS_MAX + 2];     /* which way it moved last: -1, 0, 1 */
    uint64_t slice_tris; /* the triangle count the cuts were made for */
};

/* What one frame's front end and back end share. */
struct frame {
    const struct render_opts *o;
    struct vertex_uniforms u;
    struct shade_ctx sc;
    struct span_ctx span; /* the template every thread's context starts from */
    struct fb *fb;
    struct frame_stats *stats;
};

static void slices_free(struct pipeline *p); /* (SPLIT_SLICES, below) */

struct pipeline *pipeline_new_batch(uint32_t batch_capacity)
{
    /* on cache lines of its own, as the threads' span contexts: a slice's pipeline is
     * written by its thread only, and must share no line with another's */
    size_t sz = (sizeof(struct pipeline) + 63) / 64 * 64;
    struct pipeline *p = aligned_alloc(64, sz);
    if (!p)
        return NULL;
    memset(p, 0, sz);
    if (batch_init(&p->batch[0], batch_capacity, NULL) ||
        batch_init(&p->batch[1], batch_capacity, NULL) ||
        !(p->vq_idx = malloc(3 * (size_t)p->batch[0].cap * sizeof *p->vq_idx)) ||
        !(p->vq_out = malloc(3 * (size_t)p->batch[0].cap * sizeof *p->vq_out))) {
        pipeline_destroy(p);
        return NULL;
    }
    p->vq_cap = 3 * p->batch[0].cap;
    return p;
}

struct pipeline *pipeline_new(void)
{
    return pipeline_new_batch(BATCH_DEFAULT_CAPACITY);
}

void pipeline_destroy(struct pipeline *p)
{
    if (!p)
        return;
    for (int i = 0; i < p->n_items; i++)
        free(p->items[i].v);
    free(p->items);
    batch_free(&p->batch[0]);
    batch_free(&p->batch[1]);
    workers_destroy(p->workers);
    free(p->ctx);
    free(p->vq_idx);
    free(p->vq_out);
    slices_free(p);
    free(p->slice_mesh);
    free(p);
}

/* n threads for the back end (and the vertex stage), kept until another count is asked */
static int use_threads(struct pipeline *p, int n, struct err *e)
{
    if (n == p->n_threads)
        return 0;
    workers_destroy(p->workers);
    free(p->ctx);
    p->n_threads = 0;
    p->workers = NULL;
    p->ctx = aligned_alloc(64, (size_t)n * sizeof *p->ctx); /* (whole lines each) */
    if (p->ctx)
        memset(p->ctx, 0, (size_t)n * sizeof *p->ctx);
    if (!p->ctx)
        return err_set(e, "out of memory for %d threads", n);
    if (!(p->workers = workers_new(n - 1, e)))
        return -1;
    p->n_threads = n;
    /* One thread draws a batch right after setting it up: a smaller batch finds the vertex
     * records its interpolation setup reads still in the caches (lost_empire at 160x96: a
     * drawn triangle for every 16 set up, 8192 drawn ones span ~16 MB of vertex records;
     * 16.8 -> 13.8 ms with 1024). Several threads draw one batch while the front end sets
     * up the next: batches small enough that the first is handed over early. */
    p->flush_at = n == 1 ? PIPELINE_FLUSH_ONE_THREAD : PIPELINE_FLUSH_THREADS;
    return 0;
}

/* Is the bounding sphere (object space) entirely outside one frustum plane? Planes come from
 * the rows of the object-to-clip matrix (Gribb & Hartmann), so this works for perspective and
 * orthographic cameras alike. */
static int sphere_outside(const struct mesh *m, mat4 mvp, double scale)
{
    vec3 c = v3(m->center[0], m->center[1], m->center[2]);
    double r = m->radius * scale;
    for (int i = 0; i < 6; i++) {
        int row = i / 2;
        double s = (i & 1) ? -1 : 1;
        double a = mvp.m[3][0] + s * mvp.m[row][0], b = mvp.m[3][1] + s * mvp.m[row][1];
        double cc = mvp.m[3][2] + s * mvp.m[row][2], d = mvp.m[3][3] + s * mvp.m[row][3];
        double len = sqrt(a * a + b * b + cc * cc);
        if (len > 0 && (a * c.x + b * c.y + cc * c.z + d) / len < -r)
            return 1;
    }
    return 0;
}

/* Largest factor by which the model matrix stretches any direction (bounded by column norms). */
static double max_scale(mat4 m)
{
    double best = 0;
    for (int j = 0; j < 3; j++) {
        double s = sqrt(m.m[0][j] * m.m[0][j] + m.m[1][j] * m.m[1][j] + m.m[2][j] * m.m[2][j]);
        best = s > best ? s : best;
    }
    return best;
}

/* flat shading: light.h's terms once per triangle, face normal from the file's winding, V
 * from the centroid */
static void flat_terms(const struct vertex_uniforms *u, const struct vertex_out *a,
                       const struct vertex_out *b, const struct vertex_out *c, float ns,
                       struct shade_tri *st)
{
    vec3 p0 = v3(a->wpos[0], a->wpos[1], a->wpos[2]);
    vec3 p1 = v3(b->wpos[0], b->wpos[1], b->wpos[2]);
    vec3 p2 = v3(c->wpos[0], c->wpos[1], c->wpos[2]);
    vec3 nd = v3_norm(v3_cross(v3_sub(p1, p0), v3_sub(p2, p0)));
    vec3 centroid = v3_scale(v3_add(v3_add(p0, p1), p2), 1.0 / 3.0);
    float n[3] = {(float)nd.x, (float)nd.y, (float)nd.z};
    float cw[3] = {(float)centroid.x, (float)centroid.y, (float)centroid.z};
    vertex_light(u, n, cw, ns, st->flat_d, st->flat_s);
}

/* the batch the pool is drawing, if any: join it, count its triangles, empty it */
static void drain(struct pipeline *p, struct frame *f)
{
    if (!p->in_flight)
        return;
    struct batch *b = &p->batch[!p->cur];
    f->stats->tris_empty += (uint64_t)batch_draw_finish(b, p->workers);
    batch_reset(b);
    p->in_flight = false;
}

/* the queued vertices shaded (the back end reads their varyings) */
static void shade_queued(struct pipeline *p, const struct frame *f)
{
    if (p->vq_n)
        vertex_shade_many(p->vq_mesh, &f->u, p->vq_idx, p->vq_out, p->vq_n);
    p->vq_n = 0;
}

/* the back end for what the front end has set up: one thread draws it now; with threads
 * the pool starts on it (after the batch before it) and the front end goes on with the
 * other batch */
static int flush(struct pipeline *p, struct frame *f, struct err *e)
{
    shade_queued(p, f); /* (while the pool still draws the batch before) */
    drain(p, f);
    struct batch *b = &p->batch[p->cur];
    if (batch_draw_start(b, raster_methods[f->o->raster], f->fb->w, f->fb->h, p->workers,
                         p->ctx, e))
        return -1;
    if (p->n_threads == 1) {
        f->stats->tris_empty += (uint64_t)batch_draw_finish(b, p->workers);
        batch_reset(b);
    } else {
        p->in_flight = true;
        p->cur = !p->cur;
    }
    return 0;
}

/* append one triangle (a source triangle or a piece of one) to the batch */
static void add_setup(struct pipeline *p, struct frame *f, const struct vertex_out *a,
                      const struct vertex_out *b, const struct vertex_out *c, uint32_t shade)
{
    struct batch *bt = &p->batch[p->cur];
    struct setup_tri *t = &bt->tris[bt->n_tris];
    if (setup_triangle(a, b, c, f->fb->w, f->fb->h, t) != SETUP_DRAW)
        return;
    t->shade = shade;
    bt->n_tris++;
    f->stats->tris_drawn++;
}

/* a triangle through a clipping plane: its pieces, set up and appended (rare: out of the
 * front end's loop, which keeps its registers for the common path) */
static __attribute__((noinline)) void clip_and_add(struct pipeline *p, struct frame *f,
                                                   struct vertex_out *v[3], uint32_t planes,
                                                   int n_var, uint32_t shade)
{
    struct batch *bt = &p->batch[p->cur];
    struct vertex_out *poly = &bt->verts[bt->n_verts];
    const struct vertex_out *cv[3] = {v[0], v[1], v[2]};
    int n = clip_triangle(cv, planes, n_var, f->u.guard_x, f->u.guard_y, poly);
    for (int k = 0; k < n; k++)
        if (!poly[k].projected) /* a vertex made by clipping */
            vertex_project(&poly[k], f->fb->w, f->fb->h);
    bt->n_verts += (uint32_t)n;
    for (int k = 1; k + 1 < n; k++)
        add_setup(p, f, &poly[0], &poly[k], &poly[k + 1], shade);
}

/* world position and varyings, once per vertex a drawn triangle uses: now, or queued for
 * vertex_shade_many (shaded = 2) when it does them faster together and `now` is false */
static void shade_vertices(struct pipeline *p, const struct mesh *m, const struct frame *f,
                           uint32_t i, struct vertex_out *v[3], bool now)
{
    const bool queue = !now && vertex_shade_batched(m, &f->u);
    for (int k = 0; k < 3; k++) {
        if (v[k]->shaded == 1)
            continue;
        f->stats->verts_lit += !v[k]->shaded;
        if (queue && !v[k]->shaded) {
            assert(p->vq_n < p->vq_cap); /* three per set-up triangle, emptied per batch */
            v[k]->shaded = 2;
            p->vq_mesh = m;
            p->vq_idx[p->vq_n] = m->tris[i][k];
            p->vq_out[p->vq_n++] = v[k];
        } else if (!queue) { /* (a queued vertex is shaded twice: the same floats) */
            vertex_shade(m, &f->u, m->tris[i][k], v[k]);
        }
    }
}

/* the shading record of the last material seen: triangles come in runs of one material */
struct shade_proto {
    int mat;
    struct shade_tri st;
};

/* append triangle i's shading record to the batch; its index */
static uint32_t add_shade(struct batch *bt, const struct frame *f, const struct draw_item *item,
                          const struct mesh *m, uint32_t i, struct vertex_out *v[3],
                          struct shade_proto *proto)
{
    uint16_t mi = m->tri_material[i];
    if (mi != proto->mat) {
        struct shade_tri *st = &proto->st;
        proto->mat = mi;
        st->mat = &m->materials[mi];
        st->tex = NULL;
        if (f->o->textures)
            st->tex = item->texture_override ? item->texture_override
                      : st->mat->texture >= 0 ? &m->textures[st->mat->texture]
                                              : NULL;
        st->vcolor = m->colors != NULL;
        light_base_color(st->mat, item->kd_override, st->tex || st->vcolor, st->base);
    }
    uint32_t shade = bt->n_shades++;
    struct shade_tri *st = &bt->shades[shade];
    *st = proto->st;
    if (f->span.mode == SHADE_FLAT)
        flat_terms(&f->u, v[0], v[1], v[2], st->mat->ns, st);
    return shade;
}

/* The front end for one item's filled triangles i0 .. i1-1 (m: the item's mesh at the level
 * of detail drawn; no triangle uses a vertex below verts_from); depth_only: the hidden-line
 * pre-pass (every face, whatever the culling; no shading records). */
static int front_end(struct pipeline *p, struct frame *f, const struct draw_item *item,
                     const struct mesh *m, struct vertex_out *vo, bool depth_only,
                     uint32_t i0, uint32_t i1, uint32_t verts_from, struct err *e)
{
    uint32_t verts_done = verts_from; /* (a slice: the lowest vertex its triangles use) */
    const struct render_opts *o = f->o;
    struct frame_stats *stats = f->stats;
    struct batch *bt = &p->batch[p->cur];
    int n_var = depth_only ? 0 : m->colors ? VARY_COLOR + 3 : vertex_varying_count(o->shade, o->view, f->u.lights.grey);
    struct shade_proto proto = {.mat = -1};
    /* counted in locals, added once: through the stats pointer every count would be a
     * memory update the compiler must keep in order with the batch's stores */
    uint64_t n_rejected = 0, n_culled = 0, n_no_centre = 0;
    const int fb_w = f->fb->w, fb_h = f->fb->h;
    for (uint32_t i = i0; i < i1; i++) {
        const uint32_t *c = m->tris[i];
        if (verts_done < m->n_verts) { /* the vertex stage just ahead of the triangles */
            uint32_t hi = c[0] > c[1] ? c[0] : c[1];
            hi = c[2] > hi ? c[2] : hi;
            if (hi >= verts_done) {
                uint32_t to = verts_done + PIPELINE_VERTEX_CHUNK;
                to = hi + 1 > to ? hi + 1 : to;
                to = to < m->n_verts ? to : m->n_verts;
                vertex_run(m, &f->u, vo, verts_done, to);
                verts_done = to;
            }
        }
        struct vertex_out *v[3] = {&vo[c[0]], &vo[c[1]], &vo[c[2]]};
        uint32_t all = v[0]->outcode & v[1]->outcode & v[2]->outcode;
        uint32_t any = v[0]->outcode | v[1]->outcode | v[2]->outcode;
        if ((all & VERTEX_OUT_FRUSTUM) || (any & VERTEX_INVALID)) {
            n_rejected++;
            continue;
        }
        /* an unclipped triangle whose box holds no pixel centre goes first: at terminal
         * sizes most triangles of a dense mesh do */
        int64_t box[4] = {0, 0, -1, -1};
        bool unclipped = !(any & VERTEX_NEEDS_CLIP);
        if (unclipped && !setup_box(v[0], v[1], v[2], fb_w, fb_h, box)) {
            n_no_centre++; /* whatever its facing: its determinant is never computed */
            continue;
        }
        /* culling: once per source triangle, never per clipped piece */
        if (!depth_only && o->cull != CULL_NONE &&
            setup_culled(o->cull, setup_front_facing(v[0], v[1], v[2]))) {
            n_culled++;
            continue;
        }
        if (!batch_has_room(bt) || bt->n_tris >= p->flush_at) {
            if (flush(p, f, e))
                return -1;
            bt = &p->batch[p->cur]; /* with threads, the other one */
        }
        if (unclipped) {
            /* set up first: most triangles of a dense mesh hold no pixel centre, and their
             * vertices need no lighting and the triangle no shading record */
            struct setup_tri *t = &bt->tris[bt->n_tris];
            if (setup_triangle_in_box(v[0], v[1], v[2], box, t) != SETUP_DRAW) {
                n_no_centre++;
                continue;
            }
            shade_vertices(p, m, f, i, v, false);
            t->shade = depth_only ? bt->n_shades : add_shade(bt, f, item, m, i, v, &proto);
            bt->n_tris++;
            stats->tris_drawn++;
            continue;
        }
        shade_vertices(p, m, f, i, v, true); /* clipping interpolates the varyings */
        uint32_t shade = depth_only ? bt->n_shades : add_shade(bt, f, item, m, i, v, &proto);
        stats->tris_clipped++;
        clip_and_add(p, f, v, any & VERTEX_NEEDS_CLIP, n_var, shade);
    }
    shade_queued(p, f);
    stats->tris_in += i1 - i0;
    stats->tris_rejected += n_rejected;
    stats->tris_culled += n_culled;
    stats->tris_no_centre += n_no_centre;
    return 0;
}

/* Triangle edges as lines. `overlay` edges decorate a shaded frame: they are not counted
 * as the frame's triangles. */
static void draw_edges(const struct mesh *m, const struct vertex_out *vo,
                       const struct render_opts *o, bool depth_test, bool overlay, struct fb *fb,
                       struct frame_stats *stats)
{
    for (uint32_t i = 0; i < m->n_tris; i++) {
        const struct vertex_out *v[3] = {&vo[m->tris[i][0]], &vo[m->tris[i][1]],
                                         &vo[m->tris[i][2]]};
        stats->tris_in += !overlay;
        if ((v[0]->outcode & v[1]->outcode & v[2]->outcode & VERTEX_OUT_FRUSTUM) ||
            ((v[0]->outcode | v[1]->outcode | v[2]->outcode) & VERTEX_INVALID)) {
            stats->tris_rejected += !overlay;
            continue;
        }
        if (o->cull != CULL_NONE && setup_culled(o->cull, setup_front_facing(v[0], v[1], v[2]))) {
            stats->tris_culled += !overlay;
            continue;
        }
        for (int k = 0; k < 3; k++)
            line_draw_clip(fb, v[k]->clip, v[(k + 1) % 3]->clip, o->wire_color, depth_test);
        stats->tris_drawn += !overlay;
    }
}

/* item it's vertex-stage output array, grown to n (kept across frames) */
static struct vertex_out *item_verts(struct pipeline *p, int it, uint32_t n, struct err *e)
{
    if (it >= p->n_items) {
        struct item_verts *ni = realloc(p->items, (size_t)(it + 1) * sizeof *ni);
        if (!ni)
            return err_set(e, "out of memory for %d draw items", it + 1), NULL;
        memset(ni + p->n_items, 0, (size_t)(it + 1 - p->n_items) * sizeof *ni);
        p->items = ni;
        p->n_items = it + 1;
    }
    struct item_verts *iv = &p->items[it];
    if (n > iv->cap) { /* 64-byte aligned: each half of a vertex is one cache line */
        void *nv = NULL;
        if (posix_memalign(&nv, 64, (size_t)n * sizeof *iv->v))
            return err_set(e, "out of memory for %u vertices", n), NULL;
        free(iv->v); /* the vertex stage rewrites every vertex each frame: nothing to keep */
        iv->v = nv;
        iv->cap = n;
    }
    return iv->v;
}

/* the frame's constants: camera, lights, methods */
static void frame_init(struct frame *f, const struct camera *cam, const struct render_opts *o,
                       struct fb *fb, struct frame_stats *stats)
{
    memset(f, 0, sizeof *f);
    f->o = o;
    f->fb = fb;
    f->stats = stats;
    struct vertex_uniforms *u = &f->u;
    u->eye = cam->eye;
    u->ortho = cam->ortho_height > 0;
    u->view_back = camera_back(cam);
    u->fb_w = fb->w;
    u->fb_h = fb->h;
    u->guard_x = 1.0 + 2.0 * VERTEX_GUARD_PX / fb->w;
    u->guard_y = 1.0 + 2.0 * VERTEX_GUARD_PX / fb->h;
    u->shade = o->shade;
    u->view = o->view;
    light_env_init(&u->lights, o);
    float eye[3] = {(float)cam->eye.x, (float)cam->eye.y, (float)cam->eye.z};
    float back[3] = {(float)u->view_back.x, (float)u->view_back.y, (float)u->view_back.z};
    shade_ctx_init(&f->sc, o, eye, u->ortho, back);
    f->span.fb = fb;
    f->span.shade = &f->sc;
    f->span.mode = o->view == VIEW_NORMALS ? SHADE_PHONG : o->shade;
    f->span.persp = o->persp;
    f->span.depth = o->depth;
}

/* the vertex stage on every thread, in chunks of vertices */
struct vertex_job {
    const struct mesh *m;
    const struct vertex_uniforms *u;
    struct vertex_out *out;
};

static void vertex_chunk(void *arg, size_t i0, size_t i1)
{
    const struct vertex_job *j = arg;
    vertex_run(j->m, j->u, j->out, (uint32_t)i0, (uint32_t)i1);
}

static void vertex_stage(struct pipeline *p, const struct mesh *m,
                         const struct vertex_uniforms *u, struct vertex_out *out)
{
    struct vertex_job j = {m, u, out};
    /* chunks of 4096 vertices, smaller for small meshes so that every thread gets some
     * (a chunk is at least 256 vertices: less is not worth a hand-over) */
    size_t per = (m->n_verts + 2 * (size_t)p->n_threads - 1) / (2 * (size_t)p->n_threads);
    size_t chunk = per < 256 ? 256 : per > 4096 ? 4096 : per;
    workers_for(p->workers, m->n_verts, chunk, vertex_chunk, &j);
}

/* the clear on every thread, in bands of 16 rows */
struct clear_job {
    struct fb *fb;
    const uint8_t *bg;
};

static void clear_band(void *arg, size_t y0, size_t y1)
{
    const struct clear_job *j = arg;
    fb_clear_rows(j->fb, j->bg, (int)y0, (int)y1);
}

/* the sky on every thread, in bands of 8 rows */
struct sky_job {
    const struct skybox *sky;
    const struct camera *cam;
    struct fb *fb;
};

static void sky_band(void *arg, size_t y0, size_t y1)
{
    const struct sky_job *j = arg;
    skybox_draw_rows(j->sky, j->cam, j->fb, (int)y0, (int)y1);
}

static void sky_stage(struct pipeline *p, const struct skybox *sky, const struct camera *cam,
                      struct fb *fb)
{
    struct sky_job j = {sky, cam, fb};
    workers_for(p->workers, (size_t)fb->h, 8, sky_band, &j);
}

/* Is the item's mesh wholly outside the view (its bounding sphere)? Then its triangles count
 * as culled. `counts`: the frame's statistics count this item here (its triangles toward
 * tris_full either way). */
static bool item_outside(const struct draw_item *item, mat4 mvp, double scale, bool counts,
                         struct frame_stats *stats)
{
    const struct mesh *m = item->mesh;
    if (counts)
        stats->tris_full += m->n_tris;
    if (!sphere_outside(m, mvp, scale))
        return false;
    if (counts) {
        stats->meshes_culled++;
        stats->tris_in += m->n_tris;
        stats->tris_culled += m->n_tris;
    }
    return true;
}

/* the vertex stage's matrices for one draw item */
static void item_uniforms(struct vertex_uniforms *u, const struct draw_item *item, mat4 pv)
{
    u->model = item->model;
    u->normal_matrix = m4_normal_matrix(item->model);
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 4; c++) {
            u->model_f[r][c] = (float)item->model.m[r][c];
            if (c < 3)
                u->normal_f[r][c] = (float)u->normal_matrix.m[r][c];
        }
    u->mvp = m4_mul(pv, item->model);
}

/* The item's mesh at the level of detail the frame draws (lod.h), noted in stats. */
static const struct mesh *lod_mesh(const struct draw_item *item, const struct camera *cam,
                                   int fb_h, const struct render_opts *o, double scale,
                                   struct frame_stats *stats)
{
    const struct mesh *m = item->mesh;
    int level = 0;
    if (o->lod != LOD_OFF) {
        vec3 c = m4_mul_point(item->model, v3(m->center[0], m->center[1], m->center[2]));
        double px = lod_pixels_per_unit(cam, fb_h, c, m->radius * scale) * scale;
        level = lod_choose(m, o, px);
    }
    stats->lod_min = stats->lod_min < 0 || level < stats->lod_min ? level : stats->lod_min;
    stats->lod_max = level > stats->lod_max ? level : stats->lod_max;
    return lod_level(m, level);
}

/* ---- SPLIT_SLICES (render.h): each thread the whole pipeline for a slice of the triangles */

static void slices_free(struct pipeline *p)
{
    for (int k = 0; k < p->n_slices; k++) {
        pipeline_destroy(p->slice[k]);
        fb_free(&p->slice_fb[k]);
    }
    free(p->slice);
    free(p->slice_fb);
    free(p->slice_out);
    p->slice = NULL, p->slice_fb = NULL, p->slice_out = NULL;
    p->n_slices = 0;
}

/* one slice pipeline per thread and a framebuffer for every slice but the first, of fb's
 * size */
static int slices_ready(struct pipeline *p, const struct fb *fb, int n_items, struct err *e)
{
    if (p->n_slices != p->n_threads) {
        slices_free(p);
        int n = p->n_threads;
        p->slice = calloc((size_t)n, sizeof *p->slice);
        p->slice_fb = calloc((size_t)n, sizeof *p->slice_fb);
        p->slice_out = aligned_alloc(64, (size_t)n * sizeof *p->slice_out);
        p->n_slices = n; /* (slices_free copes with the NULLs of a failure below) */
        if (!p->slice || !p->slice_fb || !p->slice_out) {
            p->n_slices = 0;
            slices_free(p);
            return err_set(e, "out of memory for %d slices", n);
        }
        for (int k = 0; k < n; k++)
            if (!(p->slice[k] = pipeline_new_batch(p->batch[0].cap)) ||
                use_threads(p->slice[k], 1, NULL)) {
                slices_free(p);
                return err_set(e, "out of memory for %d slices", n);
            }
        p->slice_tris = UINT64_MAX; /* the cuts are made again */
    }
    for (int k = 1; k < p->n_slices; k++)
        if (p->slice_fb[k].w != fb->w || p->slice_fb[k].h != fb->h) {
            fb_free(&p->slice_fb[k]);
            if (fb_init(&p->slice_fb[k], fb->w, fb->h, false, e))
                return -1;
        }
    if (n_items > p->slice_mesh_cap) {
        const struct mesh **nm = realloc(p->slice_mesh, (size_t)n_items * sizeof *nm);
        if (!nm)
            return err_set(e, "out of memory for %d draw items", n_items);
        p->slice_mesh = nm;
        p->slice_mesh_cap = n_items;
    }
    return 0;
}

/* the frame's index of the first triangle of slice k (k = n_slices: the end) */
static uint64_t slice_at(const struct pipeline *p, int k, uint64_t n_tris)
{
    return k >= p->n_slices ? n_tris : (uint64_t)(p->slice_cut[k] * (double)n_tris);
}

/* Move the cuts toward slices of equal time. A slice's time is taken as spread evenly over
 * its triangles and cut i heads for where the cumulative time reaches i/n of the whole,
 * but moves at most slice_step[i]: the step halves each time the cut turns back and grows
 * by half while it keeps its way, so a cut next to a few costly triangles (the demo's
 * floor at 640x480: moving the cut across it moved 3.6 ms) settles instead of jumping
 * over them every frame, and a new view still moves it quickly. Each slice keeps at least
 * a quarter of an even share. The cuts never change a picture, only which thread draws
 * what. */
static void slice_balance(struct pipeline *p)
{
    const int n = p->n_slices;
    double total = 0, most = 0, want[WORKERS_MAX + 2];
    for (int k = 0; k < n; k++) {
        total += p->slice_out[k].ms;
        most = p->slice_out[k].ms > most ? p->slice_out[k].ms : most;
    }
    /* within a tenth of even: left alone (each slice keeps its vertex records and batches
     * warm in its core's caches; moving on noise cost the demo 6%) */
    if (!(total > 0) || most * n < 1.1 * total)
        return;
    want[0] = 0, want[n] = 1;
    int k = 0; /* the slice in which the cumulative time reaches i/n */
    double acc = 0; /* time of slices before k */
    for (int i = 1; i < n; i++) {
        double target = total * i / n;
        while (k < n - 1 && acc + p->slice_out[k].ms < target)
            acc += p->slice_out[k++].ms;
        double t = p->slice_out[k].ms, w = p->slice_cut[k + 1] - p->slice_cut[k];
        want[i] = p->slice_cut[k] + (t > 0 ? (target - acc) / t : 0) * w;
    }
    const double least = 0.25 / n;
    for (int i = 1; i < n; i++) {
        double d = want[i] - p->slice_cut[i], step = p->slice_step[i];
        int dir = d > 0 ? 1 : d < 0 ? -1 : 0;
        step *= dir && p->slice_dir[i] && dir != p->slice_dir[i] ? 0.5 : 1.5;
        step = step < 1e-4 ? 1e-4 : step > 0.5 / n ? 0.5 / n : step;
        p->slice_step[i] = step, p->slice_dir[i] = dir;
        double c = p->slice_cut[i] + (d > step ? step : d < -step ? -step : d);
        double lo = p->slice_cut[i - 1] + least, hi = 1 - least * (n - i);
        p->slice_cut[i] = c < lo ? lo : c > hi ? hi : c;
    }
}

struct slice_job {
    struct pipeline *p;
    const struct draw_item *items;
    int n_items;
    const struct camera *cam;
    const struct render_opts *o;
    struct fb *fb;
    mat4 pv;
    uint64_t n_tris; /* the frame's triangles (slice k draws slice_at(k) .. slice_at(k+1)) */
    struct slice_out *out; /* p->slice_out */
};

/* slice k: its triangles through the front end and the back end, on one thread */
static void slice_main(void *arg, int k)
{
    struct slice_job *j = arg;
    struct pipeline *sp = j->p->slice[k];
    struct fb *fb = k ? &j->p->slice_fb[k] : j->fb;
    struct frame_stats *st = &j->out[k].st;
    struct err *e = &j->out[k].err;
    memset(st, 0, sizeof *st);
    j->out[k].rc = 0;
    if (k) { /* (slice 0's is the frame's: the others read it meanwhile) */
        fb->depth_mode = j->fb->depth_mode;
        fb->proj = j->fb->proj;
        fb->pixel_aspect = j->fb->pixel_aspect;
    }
    fb_clear(fb, j->o->background);
    struct frame f;
    frame_init(&f, j->cam, j->o, fb, st);
    batch_reset(&sp->batch[sp->cur]);
    sp->ctx[0] = f.span;
    const double t0 = timing_now_ms();
    const uint64_t lo = slice_at(j->p, k, j->n_tris), hi = slice_at(j->p, k + 1, j->n_tris);
    uint64_t base = 0; /* the frame's index of the item's first triangle */
    for (int it = 0; it < j->n_items && base < hi; it++) {
        const struct mesh *m = j->p->slice_mesh[it];
        if (!m)
            continue;
        uint64_t first = base;
        base += m->n_tris;
        if (base <= lo)
            continue;
        uint32_t i0 = (uint32_t)(lo > first ? lo - first : 0);
        uint32_t i1 = (uint32_t)(hi < base ? hi - first : m->n_tris);
        item_uniforms(&f.u, &j->items[it], j->pv);
        /* the vertex stage starts at the lowest vertex the slice's triangles use (one flat
         * loop over their indices: the compiler makes it a vector minimum) */
        uint32_t from = 0;
        if (i0) {
            const uint32_t *idx = m->tris[i0];
            from = m->n_verts;
            for (size_t i = 0; i < 3 * (size_t)(i1 - i0); i++)
                from = idx[i] < from ? idx[i] : from;
        }
        struct vertex_out *vo = item_verts(sp, it, m->n_verts, e);
        if (!vo || front_end(sp, &f, &j->items[it], m, vo, false, i0, i1, from, e)) {
            j->out[k].rc = -1;
            drain(sp, &f);
            return;
        }
    }
    j->out[k].rc = flush(sp, &f, e);
    drain(sp, &f);
    st->pixels_tested += sp->ctx[0].tested;
    st->pixels_shaded += sp->ctx[0].shaded;
    j->out[k].ms = timing_now_ms() - t0;
}

/* slices 1.. merged into slice 0 (the frame's framebuffer), rows y0 .. y1-1: the nearer
 * fragment wins, and on a tie the earlier slice (the depth test is strict) */
struct merge_job {
    struct fb *fb;
    const struct fb *slice_fb;
    int n_slices;
};

static void merge_rows(void *arg, size_t y0, size_t y1)
{
    const struct merge_job *j = arg;
    struct fb *fb = j->fb;
    const enum depth_mode mode = fb->depth_mode;
    const size_t i0 = y0 * (size_t)fb->w, i1 = y1 * (size_t)fb->w;
    for (int k = 1; k < j->n_slices; k++) {
        const struct fb *s = &j->slice_fb[k];
        for (size_t i = i0; i < i1; i++)
            if (fb_depth_passes(mode, s->depth[i], fb->depth[i])) {
                fb->depth[i] = s->depth[i];
                memcpy(fb->rgb + 3 * i, s->rgb + 3 * i, 3);
            }
    }
}

/* The surfaces of the frame by slices: the meshes and levels chosen once (as the tiles'
 * path does), the slices drawn on every thread, merged. */
static int draw_slices(struct pipeline *p, const struct draw_item *items, int n_items,
                       const struct camera *cam, const struct render_opts *o, struct fb *fb,
                       mat4 pv, struct frame_stats *stats, struct err *e)
{
    if (slices_ready(p, fb, n_items, e))
        return -1;
    struct slice_job job = {.p = p, .items = items, .n_items = n_items, .cam = cam, .o = o,
                            .fb = fb, .pv = pv, .out = p->slice_out},
                     *j = &job;
    for (int it = 0; it < n_items; it++) {
        const struct draw_item *item = &items[it];
        const struct mesh *m = item->mesh;
        p->slice_mesh[it] = NULL;
        if (m->n_tris == 0)
            continue;
        double scale = max_scale(item->model);
        if (item_outside(item, m4_mul(pv, item->model), scale, true, stats))
            continue;
        p->slice_mesh[it] = lod_mesh(item, cam, fb->h, o, scale, stats);
        j->n_tris += p->slice_mesh[it]->n_tris;
    }
    if (j->n_tris != p->slice_tris) { /* another scene: even slices to start from */
        for (int k = 0; k <= p->n_slices; k++) {
            p->slice_cut[k] = (double)k / p->n_slices;
            p->slice_step[k] = 0.25 / p->n_slices;
            p->slice_dir[k] = 0;
        }
        p->slice_tris = j->n_tris;
    }
    workers_run(p->workers, slice_main, j);
    int rc = 0;
    for (int k = 0; k < p->n_slices; k++) {
        const struct frame_stats *s = &j->out[k].st;
        if (j->out[k].rc && !rc) {
            rc = -1;
            if (e)
                *e = j->out[k].err;
        }
        stats->tris_in += s->tris_in;
        stats->tris_culled += s->tris_culled;
        stats->tris_rejected += s->tris_rejected;
        stats->tris_clipped += s->tris_clipped;
        stats->tris_drawn += s->tris_drawn;
        stats->tris_empty += s->tris_empty;
        stats->tris_no_centre += s->tris_no_centre;
        stats->verts_lit += s->verts_lit;
        stats->pixels_tested += s->pixels_tested;
        stats->pixels_shaded += s->pixels_shaded;
    }
    if (rc)
        return -1;
    slice_balance(p);
    struct merge_job mj = {fb, p->slice_fb, p->n_slices};
    workers_for(p->workers, (size_t)fb->h, 16, merge_rows, &mj);
    return 0;
}

/* tiles or slices for this frame (render.h, enum thread_split) */
static bool use_slices(const struct pipeline *p, const struct draw_item *items, int n_items,
                       const struct render_opts *o, const struct fb *fb, bool wire)
{
    if (p->n_threads < 2 || wire || o->view == VIEW_WIRE_OVERLAY || fb->overdraw ||
        o->split == SPLIT_TILES)
        return false;
    if (o->split == SPLIT_SLICES)
        return true;
    uint64_t n = 0, px = (uint64_t)fb->w * (uint64_t)fb->h;
    for (int it = 0; it < n_items; it++)
        n += items[it].mesh->n_tris;
    return n * PIPELINE_SLICE_PIXELS >= px ||
           (px <= PIPELINE_SLICE_SMALL && n * PIPELINE_SLICE_PIXELS_SMALL >= px);
}

int pipeline_draw(struct pipeline *p, const struct draw_item *items, int n_items,
                  const struct skybox *sky, const struct camera *cam,
                  const struct render_opts *o, struct fb *fb, struct frame_stats *stats,
                  struct err *e)
{
    double t0 = timing_now_ms();
    memset(stats, 0, sizeof *stats);
    stats->lod_min = stats->lod_max = -1;
    if (use_threads(p, o->threads > 0 ? o->threads : workers_cores(), e))
        return -1;
    stats->threads = p->n_threads;
    fb->depth_mode = o->depth;
    fb->proj = (struct fb_depth_proj){cam->ortho_height > 0, cam->near, cam->far};
    mat4 pv = m4_mul(camera_proj(cam, fb_aspect(fb)), camera_view(cam));
    bool show_sky = sky && (o->view == VIEW_COLOR || o->view == VIEW_WIRE_OVERLAY);
    bool wire = o->view != VIEW_NORMALS && o->shade == SHADE_WIRE; /* (frame_init's mode) */
    if (use_slices(p, items, n_items, o, fb, wire)) { /* each slice clears its own */
        stats->slices = true;
        if (draw_slices(p, items, n_items, cam, o, fb, pv, stats, e))
            return -1;
        if (show_sky) /* the sky goes where the surfaces left room */
            sky_stage(p, sky, cam, fb);
        if (o->view == VIEW_DEPTH)
            fb_show_depth(fb);
        stats->render_ms = timing_now_ms() - t0;
        return 0;
    }
    struct clear_job cj = {fb, o->background};
    workers_for(p->workers, (size_t)fb->h, 16, clear_band, &cj);
    struct frame f;
    frame_init(&f, cam, o, fb, stats);
    batch_reset(&p->batch[p->cur]);
    for (int k = 0; k < p->n_threads; k++)
        p->ctx[k] = f.span;
    assert(wire == (f.span.mode == SHADE_WIRE));

    /* wire frames have no surface colour: the sky goes everywhere, before anything else */
    if (show_sky && wire)
        sky_stage(p, sky, cam, fb);
    /* pass 1: surfaces (wire: depth only, for hidden lines), through the batch; pass 2:
     * edges, depth-tested against every item's surfaces when asked */
    bool pass1 = !wire || o->hidden_lines;
    bool pass2 = wire || o->view == VIEW_WIRE_OVERLAY;
    struct frame_stats pre = {0}; /* the hidden-line pre-pass: its counts are not the frame's */
    if (wire)
        f.stats = &pre;
    for (int pass = 1; pass <= 2; pass++) {
        if ((pass == 1 && !pass1) || (pass == 2 && !pass2))
            continue;
        /* a culled item is counted once: by the first pass that looks at it */
        bool counts = pass == 1 || !pass1;
        for (int it = 0; it < n_items; it++) {
            const struct draw_item *item = &items[it];
            const struct mesh *m = item->mesh;
            if (m->n_tris == 0)
                continue;
            item_uniforms(&f.u, item, pv);
            double scale = max_scale(item->model);
            if (item_outside(item, f.u.mvp, scale, counts, stats))
                continue;
            /* room for the mesh in full: changing levels never allocates (a batch the
             * pool is drawing points into earlier items' arrays only) */
            struct vertex_out *vo = item_verts(p, it, m->n_verts, e);
            if (!vo)
                goto fail;
            if (counts) /* once a frame: a background build may add levels meanwhile */
                p->items[it].level = lod_mesh(item, cam, fb->h, o, scale, stats);
            m = p->items[it].level;
            /* pass 1 runs the vertex stage as its triangles need it (front_end), on the
             * calling thread, also while the pool draws; pass 2 reuses pass 1's vertices,
             * or runs the stage on every thread when there was no pass 1 */
            if (pass == 2 && !pass1)
                vertex_stage(p, m, &f.u, vo);
            if (pass == 1) {
                if (front_end(p, &f, item, m, vo, wire, 0, m->n_tris, 0, e))
                    goto fail;
            } else {
                draw_edges(m, vo, o, !wire || o->hidden_lines, !wire, fb, stats);
            }
        }
        if (pass == 1) {
            if (flush(p, &f, e)) /* the surfaces are complete */
                goto fail;
            drain(p, &f);
            if (!wire)
                for (int k = 0; k < p->n_threads; k++) {
                    stats->pixels_tested += p->ctx[k].tested;
                    stats->pixels_shaded += p->ctx[k].shaded;
                }
            if (show_sky && !wire) /* the sky goes where the surfaces left room */
                sky_stage(p, sky, cam, fb);
        }
    }
    if (o->view == VIEW_DEPTH)
        fb_show_depth(fb);
    else if (o->view == VIEW_OVERDRAW)
        fb_show_overdraw(fb);
    stats->render_ms = timing_now_ms() - t0;
    return 0;
fail: /* nothing may be left drawing once the caller has the frame back */
    drain(p, &f);
    return -1;
}
