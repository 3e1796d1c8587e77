/* frontend.c: the front end of one thread of drawing (see frontend.h). */
#include "frontend.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <stddef.h>
#include <string.h>

#include "clip.h"
#include "cluster.h"
#include "cluster_cull.h"
#include "dag.h"
#include "line.h"
#include "mem.h"
#include "lod.h"
#include "setup.h"

int frontend_init(struct frontend *fe, uint32_t batch_cap, struct err *e)
{
    memset(fe, 0, sizeof *fe);
    if (batch_init(&fe->batch[0], batch_cap, e) || batch_init(&fe->batch[1], batch_cap, e) ||
        !(fe->vq_idx = malloc(3 * (size_t)fe->batch[0].cap * sizeof *fe->vq_idx)) ||
        !(fe->vq_out = malloc(3 * (size_t)fe->batch[0].cap * sizeof *fe->vq_out))) {
        frontend_free(fe);
        return err_set(e, "out of memory for the front end's batches");
    }
    fe->vq_cap = 3 * fe->batch[0].cap;
    return 0;
}

void frontend_free(struct frontend *fe)
{
    for (int i = 0; i < fe->n_items; i++) {
        free(fe->items[i].v);
        free(fe->items[i].facing);
        free(fe->items[i].occ);
        free(fe->items[i].drew);
        edge_table_free(&fe->items[i].edges);
    }
    free(fe->items);
    batch_free(&fe->batch[0]);
    batch_free(&fe->batch[1]);
    free(fe->vq_idx);
    free(fe->vq_out);
    free(fe->vdone);
    free(fe->marks);
    free(fe->pos);
    free(fe->vslot);
    free(fe->occ);
    free(fe->occ_xyz);
    free(fe->occ_pos);
    memset(fe, 0, sizeof *fe);
}

void frontend_begin(struct frontend *fe, const struct frame *f, struct workers *w,
                    struct span_ctx *ctx, int n_ctx)
{
    fe->workers = w && workers_count(w) > 0 ? w : NULL;
    fe->ctx = ctx;
    fe->n_ctx = n_ctx;
    fe->flush_at = fe->workers ? FRONTEND_FLUSH_THREADS : FRONTEND_FLUSH_ONE_THREAD;
    fe->occ_any = false;
    fe->occ_item = NULL;
    batch_reset(&fe->batch[fe->cur]);
    for (int k = 0; k < n_ctx; k++)
        ctx[k] = f->span;
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
static void drain(struct frontend *fe, struct frame *f)
{
    if (!fe->in_flight)
        return;
    struct batch *b = &fe->batch[!fe->cur];
    f->stats->tris_empty += (uint64_t)batch_draw_finish(b, fe->workers);
    batch_reset(b);
    fe->in_flight = false;
}

/* the queued vertices shaded (the back end reads their varyings) */
static void shade_queued(struct frontend *fe, const struct frame *f)
{
    if (fe->vq_n)
        f->k->vertex_shade_many(fe->vq_mesh, &f->u, fe->vq_idx, fe->vq_out, fe->vq_n);
    fe->vq_n = 0;
}

/* the back end for what the front end has set up: one thread draws it now; with threads
 * the pool starts on it (after the batch before it) and the front end goes on with the
 * other batch */
static int flush(struct frontend *fe, struct frame *f, struct err *e)
{
    shade_queued(fe, f); /* (while the pool still draws the batch before) */
    drain(fe, f);
    struct batch *b = &fe->batch[fe->cur];
    if (batch_draw_start(b, f->k->raster[f->o->raster], f->fb->w, f->fb->h, fe->workers,
                         fe->ctx, e))
        return -1;
    if (!fe->workers) {
        f->stats->tris_empty += (uint64_t)batch_draw_finish(b, fe->workers);
        batch_reset(b);
    } else {
        fe->in_flight = true;
        fe->cur = !fe->cur;
    }
    return 0;
}

/* append one triangle (a source triangle or a piece of one) to the batch */
static void add_setup(struct frontend *fe, struct frame *f, const struct vertex_out *a,
                      const struct vertex_out *b, const struct vertex_out *c, uint32_t shade,
                      uint8_t rich)
{
    struct batch *bt = &fe->batch[fe->cur];
    struct setup_tri *t = &bt->tris[bt->n_tris];
    if (setup_triangle(a, b, c, f->fb->w, f->fb->h, t) != SETUP_DRAW)
        return;
    t->shade = shade;
    t->rich = rich;
    bt->n_tris++;
    f->stats->tris_drawn++;
}

/* a triangle through a clipping plane: its pieces, set up and appended (rare: out of the
 * front end's loop, which keeps its registers for the common path) */
static __attribute__((noinline)) void clip_and_add(struct frontend *fe, struct frame *f,
                                                   struct vertex_out *v[3], uint32_t planes,
                                                   int n_var, uint32_t shade, uint8_t rich)
{
    struct batch *bt = &fe->batch[fe->cur];
    struct vertex_out *poly = &bt->verts[bt->n_verts];
    const struct vertex_out *cv[3] = {v[0], v[1], v[2]};
    int n = clip_triangle(cv, planes, n_var, f->u.guard_x, f->u.guard_y, poly);
    for (int k = 0; k < n; k++)
        if (!poly[k].projected) /* a vertex made by clipping */
            vertex_project(&poly[k], f->fb->w, f->fb->h);
    bt->n_verts += (uint32_t)n;
    for (int k = 1; k + 1 < n; k++)
        add_setup(fe, f, &poly[0], &poly[k], &poly[k + 1], shade, rich);
}

/* world position and varyings, once per vertex a drawn triangle uses: now, or queued for
 * vertex_shade_many (VERTEX_QUEUED) when it does them faster together and `now` is false */
static void shade_vertices(struct frontend *fe, const struct mesh *m, const struct frame *f,
                           uint32_t i, struct vertex_out *v[3], bool now)
{
    const bool queue = !now && vertex_shade_batched(m, &f->u);
    for (int k = 0; k < 3; k++) {
        if (v[k]->shaded == VERTEX_SHADED)
            continue;
        f->stats->verts_lit += v[k]->shaded == VERTEX_UNSHADED;
        if (queue && v[k]->shaded == VERTEX_UNSHADED) {
            assert(fe->vq_n < fe->vq_cap); /* three per set-up triangle, emptied per batch */
            v[k]->shaded = VERTEX_QUEUED;
            fe->vq_mesh = m;
            fe->vq_idx[fe->vq_n] = m->tris[i][k];
            fe->vq_out[fe->vq_n++] = v[k];
        } else if (!queue) { /* (a queued vertex is shaded twice: the same floats) */
            vertex_shade(m, &f->u, m->tris[i][k], v[k]);
        }
    }
}

/* the shading record of the last material seen: triangles come in runs of one material */
struct shade_proto {
    int mat;
    struct shade_tri st;
    const struct rich_item *rich; /* the features path's item, or NULL */
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
        st->rich = proto->rich;
        light_base_color(st->mat, item->kd_override, st->tex || st->vcolor, st->base);
    }
    uint32_t shade = bt->n_shades++;
    struct shade_tri *st = &bt->shades[shade];
    *st = proto->st;
    if (proto->rich) /* two-sided lighting turns a back face's normal */
        st->back = !setup_front_facing(v[0], v[1], v[2]);
    if (f->span.mode == SHADE_FLAT)
        flat_terms(&f->u, v[0], v[1], v[2], st->mat->ns, st);
    return shade;
}

/* The features path's item for m (frame.h), its varyings' layout the vertex stage follows
 * (f->u.rich); NULL when the frame has no room (never: FRAME_MAX_RICH covers every item in
 * both passes) */
static const struct rich_item *rich_item(struct frame *f, const struct mesh *m)
{
    if (f->n_rich == FRAME_MAX_RICH)
        return NULL;
    struct rich_item *r = &f->rich[f->n_rich++];
    vertex_rich_layout(m, f->span.mode, f->u.view, f->u.lights.grey, &r->lay);
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++)
            r->nmat[a][b] = f->u.normal_f[a][b];
    r->textures = m->textures;
    r->textures_on = f->o->textures;
    const float(*x)[4] = f->u.model_f;
    float det = x[0][0] * (x[1][1] * x[2][2] - x[1][2] * x[2][1]) -
                x[0][1] * (x[1][0] * x[2][2] - x[1][2] * x[2][0]) +
                x[0][2] * (x[1][0] * x[2][1] - x[1][1] * x[2][0]);
    f->u.model_det = det < 0 ? -1.0f : 1.0f;
    return r;
}

/* What the front end keeps for one item's triangles while it walks them (run by run with
 * clusters): the item, its varyings and culling, the last material's shading record, and
 * the counts of dropped triangles. */
struct tri_walk {
    const struct draw_item *item;
    const struct mesh *m;
    struct vertex_out *vo;
    bool depth_only;
    int n_var;
    uint8_t rich;
    uint64_t n_cut; /* the hierarchy's cut: its triangles in the slice */
    enum cull_mode cull;
    bool by_material;
    struct shade_proto proto;
    uint64_t n_rejected, n_culled, n_no_centre;
    const uint8_t *vmark; /* the hierarchy's cut: the vertices to make (a byte each), or
                             NULL: all */
    struct vertex_pos *pos; /* by position (walk_by_position): each position's share */
    uint32_t *vslot;          /* by position: where vertex i's record is in vo (+ 1), or 0 */
    uint8_t *made;            /* by heads: is vertex i's record vo[i] made (a byte each) */
    uint32_t n_made;          /* by position: records made, vo[0 .. n_made) */
    uint32_t pos_done;        /* by position: positions 0 .. pos_done-1 projected */
    const float *hide;        /* the depth buffer hidden triangles are tested on, or NULL */
    uint64_t n_hidden;
    const float *occ;         /* the occluder depth (struct frontend's occ), or NULL */
    struct frontend_item *drew; /* the item whose drawn triangles are listed, or NULL */
};

/* The clip position of object-space point q: every kernel's vertex_run's doubles in its
 * order (the reference's sums, m4_mul_v4's), so the same bits */
static inline void position_clip(const mat4 *a, const float q[3], double clip[4])
{
    const double x = q[0], y = q[1], z = q[2];
    for (int r = 0; r < 4; r++)
        clip[r] = a->m[r][0] * x + a->m[r][1] * y + a->m[r][2] * z + a->m[r][3] * 1.0;
}

/* How the walk reads a triangle's corners: the vertex stage's records (vertex_run), or
 * only their heads first — outcode, snapped window position and depth (struct vertex_pos,
 * the kernel's position_run) — per position (mesh.h's pos_id: walks_by_position) or per
 * vertex (walks_by_heads), the records made (make_vertex) for the triangles that draw */
enum walk_by { BY_VERTEX, BY_POSITION, BY_HEAD };

/* Heads p0 .. p1-1 (by position: of positions, mesh.h's pos_id; by head: of vertices) as
 * vertex_run makes them for a vertex, kept alone: all the triangle tests read */
static void position_stage(const struct frame *f, const struct mesh *m, struct vertex_pos *pos,
                           uint32_t p0, uint32_t p1, const int by)
{
    if (by == BY_HEAD)
        f->k->position_run(m->verts[0].pos, sizeof *m->verts, &f->u, pos, p0, p1);
    else
        f->k->position_run(m->pos_xyz[0], sizeof *m->pos_xyz, &f->u, pos, p0, p1);
}

/* vertex i's record (vertex_run's bytes: its clip and window positions computed again
 * from its position, the same doubles) when the walk has not made it yet: by position in
 * the next free record of vo (the records drawn triangles read lie together), by heads in
 * vo[i] */
static inline struct vertex_out *make_vertex(const struct frame *f, struct tri_walk *w,
                                             uint32_t i, const int by)
{
    struct vertex_out *o;
    if (by == BY_HEAD) { /* (in place) */
        if (w->made[i])
            return &w->vo[i];
        w->made[i] = 1;
        o = &w->vo[i];
    } else {
        uint32_t s = w->vslot[i];
        if (s)
            return &w->vo[s - 1];
        s = w->n_made++;
        w->vslot[i] = s + 1;
        o = &w->vo[s];
    }
    const uint32_t p = by == BY_HEAD ? i : w->m->pos_id[i];
    const struct vertex_pos *q = &w->pos[p];
    position_clip(&f->u.mvp, by == BY_HEAD ? w->m->verts[i].pos : w->m->pos_xyz[p], o->clip);
    o->outcode = q->outcode;
    o->projected = 0;
    o->shaded = VERTEX_UNSHADED;
    if (!(q->outcode & VERTEX_NEEDS_CLIP)) {
        double win[3];
        viewport_window(o->clip, f->u.fb_w, f->u.fb_h, win);
        o->win[0] = win[0], o->win[1] = win[1];
        o->fx = q->fx, o->fy = q->fy;
        o->projected = 1;
    }
    return o;
}

/* the vertex stage on vertices i0 .. i1-1: all, or the marked ones (in runs; eight at a
 * time past unmarked ones: vmark has eight zero bytes past the end) */
static void vertex_stage(const struct frame *f, const struct tri_walk *w, uint32_t i0,
                         uint32_t i1)
{
    const uint8_t *vmark = w->vmark;
    if (!vmark) {
        f->k->vertex_run(w->m, &f->u, w->vo, i0, i1);
        return;
    }
    for (uint32_t v = i0; v < i1;) {
        uint64_t eight;
        memcpy(&eight, vmark + v, sizeof eight);
        if (!eight) {
            v += 8;
            continue;
        }
        if (!vmark[v]) {
            v++;
            continue;
        }
        uint32_t to = v + 1;
        while (to < i1 && vmark[to])
            to++;
        f->k->vertex_run(w->m, &f->u, w->vo, v, to);
        v = to;
    }
}

/* The window depth setup gives corner v (setup_interp's z_lo is the least of the three, in
 * float: every pixel's depth is clamped to it), for the default depth method */
static inline float corner_depth(const struct vertex_out *v)
{
    const double rw = 1.0 / v->clip[3];
    return (float)(0.5 * v->clip[2] * rw + 0.5);
}

static inline float min3f(float a, float b, float c)
{
    a = b < a ? b : a;
    return c < a ? c : a;
}

/* Is a triangle (or a cluster's triangles) whose depth is at least z_lo everywhere hidden
 * over its pixel box by what the depth buffer holds (test LESS: a fragment at z_lo or behind
 * fails where the buffer is at z_lo or nearer)? strict: by the occluder depth (struct
 * frontend's occ), where it must lie strictly behind at every pixel centre — an occluder is
 * drawn this frame, its own fragments there at that depth or nearer, so a fragment strictly
 * behind it never shows whatever the order, but at a tie the order decides. Boxes of more
 * than max_px pixels are not tested (a triangle's: FRONTEND_HIDDEN_MAX_BOX; a cluster's:
 * FRONTEND_HIDDEN_MAX_RECT). */
static inline bool hidden_behind(const float *depth, int fb_w, const int64_t box[4], float z_lo,
                                 int64_t max_px, const bool strict)
{
    if ((box[2] - box[0] + 1) * (box[3] - box[1] + 1) > max_px)
        return false;
    for (int64_t y = box[1]; y <= box[3]; y++) {
        const float *row = depth + y * fb_w;
        for (int64_t x = box[0]; x <= box[2]; x++)
            if (strict ? !(z_lo > row[x]) : z_lo < row[x])
                return false;
    }
    return true;
}

/* room for one more of item d's drawn triangles; false: out of memory (the list stops) */
static bool drew_room(struct frontend_item *d)
{
    if (d->n_drew < d->drew_cap)
        return true;
    uint32_t cap = d->drew_cap ? 2 * d->drew_cap : 4096;
    uint32_t *g = realloc(d->drew, (size_t)cap * sizeof *g);
    if (!g)
        return false;
    d->drew = g, d->drew_cap = cap;
    return true;
}

/* the triangles list[0 .. n) that passed filter (below): their vertices made (by position:
 * their positions projected), each one's box, hidden test, culling, setup, clipping and
 * shading (frontend.h) */
static inline __attribute__((always_inline)) int
walk(struct frontend *fe, struct frame *f, struct tri_walk *w, const uint32_t *list, uint32_t n,
     const int by, struct err *e)
{
    const bool by_pos = by != BY_VERTEX; /* (by position or by head: the heads first) */
    const struct mesh *m = w->m;
    struct vertex_out *vo = w->vo;
    const bool depth_only = w->depth_only;
    const int n_var = w->n_var;
    const uint8_t rich = w->rich;
    const enum cull_mode cull = w->cull;
    const bool by_material = w->by_material;
    const struct draw_item *item = w->item;
    struct frame_stats *stats = f->stats;
    struct batch *bt = &fe->batch[fe->cur];
    /* counted in locals, added once: through the stats pointer every count would be a
     * memory update the compiler must keep in order with the batch's stores */
    uint64_t n_culled = 0, n_no_centre = 0, n_hidden = 0, n_occluded = 0;
    const float *hide = w->hide, *occ = w->occ;
    struct frontend_item *drew = w->drew;
    const int fb_w = f->fb->w, fb_h = f->fb->h;
    const bool culls = !depth_only && (cull != CULL_NONE || by_material); /* (reads clip) */
    struct vertex_out snapped[3]; /* by position: a triangle's snapped corners for setup */
    for (uint32_t li = 0; li < n; li++) {
        const uint32_t i = list[li];
        const uint32_t *c = m->tris[i];
        struct vertex_out *v[3] = {&vo[c[0]], &vo[c[1]], &vo[c[2]]};
        uint32_t any;
        int64_t box[4] = {0, 0, -1, -1};
        bool unclipped;
        /* (filter kept the triangle: inside the view, and unclipped its box holds a pixel
         * centre; the box is made again here) */
        if (by_pos) { /* the corners' positions: their vertices made only past the box */
            const uint32_t q0 = by == BY_HEAD ? c[0] : m->pos_id[c[0]];
            const uint32_t q1 = by == BY_HEAD ? c[1] : m->pos_id[c[1]];
            const uint32_t q2 = by == BY_HEAD ? c[2] : m->pos_id[c[2]];
            const struct vertex_pos *p0 = &w->pos[q0], *p1 = &w->pos[q1], *p2 = &w->pos[q2];
            any = p0->outcode | p1->outcode | p2->outcode;
            unclipped = !(any & VERTEX_NEEDS_CLIP);
            if (unclipped)
                setup_box_xy(p0->fx, p0->fy, p1->fx, p1->fy, p2->fx, p2->fy, fb_w, fb_h, box);
            if (hide && unclipped &&
                hidden_behind(hide, fb_w, box, min3f(p0->z, p1->z, p2->z),
                              FRONTEND_HIDDEN_MAX_BOX, false)) {
                n_hidden++;
                continue;
            }
            if (occ && unclipped &&
                hidden_behind(occ, fb_w, box, min3f(p0->z, p1->z, p2->z),
                              FRONTEND_HIDDEN_MAX_BOX, true)) {
                n_hidden++, n_occluded++;
                continue;
            }
            if (unclipped && !culls) { /* setup reads the snapped corners alone: the
                                          records wait until it draws the triangle */
                for (int k = 0; k < 3; k++)
                    v[k] = &snapped[k];
                snapped[0].fx = p0->fx, snapped[0].fy = p0->fy;
                snapped[1].fx = p1->fx, snapped[1].fy = p1->fy;
                snapped[2].fx = p2->fx, snapped[2].fy = p2->fy;
            } else {
                v[0] = make_vertex(f, w, c[0], by);
                v[1] = make_vertex(f, w, c[1], by);
                v[2] = make_vertex(f, w, c[2], by);
            }
        } else {
            any = v[0]->outcode | v[1]->outcode | v[2]->outcode;
            unclipped = !(any & VERTEX_NEEDS_CLIP);
            if (unclipped)
                setup_box(v[0], v[1], v[2], fb_w, fb_h, box);
            if (hide && unclipped &&
                hidden_behind(hide, fb_w, box,
                              min3f(corner_depth(v[0]), corner_depth(v[1]), corner_depth(v[2])),
                              FRONTEND_HIDDEN_MAX_BOX, false)) {
                n_hidden++;
                continue;
            }
            if (occ && unclipped &&
                hidden_behind(occ, fb_w, box,
                              min3f(corner_depth(v[0]), corner_depth(v[1]), corner_depth(v[2])),
                              FRONTEND_HIDDEN_MAX_BOX, true)) {
                n_hidden++, n_occluded++;
                continue;
            }
        }
        /* culling: once per source triangle, never per clipped piece */
        if (culls &&
            setup_culled(by_material && m->materials[m->tri_material[i]].sides == MAT_ONE_SIDED
                             ? CULL_BACK
                             : cull,
                         setup_front_facing(v[0], v[1], v[2]))) {
            n_culled++;
            continue;
        }
        if (!batch_has_room(bt) || bt->n_tris >= fe->flush_at) {
            if (flush(fe, f, e))
                return -1;
            bt = &fe->batch[fe->cur]; /* with threads, the other one */
        }
        if (unclipped) {
            /* set up first: most triangles of a dense mesh hold no pixel centre, and their
             * vertices need no lighting and the triangle no shading record */
            struct setup_tri *t = &bt->tris[bt->n_tris];
            if (setup_triangle_in_box(v[0], v[1], v[2], box, t) != SETUP_DRAW) {
                n_no_centre++;
                continue;
            }
            if (by_pos && !culls) /* (the corners' records, made now: see above) */
                for (int k = 0; k < 3; k++)
                    t->v[k] = v[k] = make_vertex(f, w, c[k], by);
            shade_vertices(fe, m, f, i, v, false);
            t->shade = depth_only ? bt->n_shades : add_shade(bt, f, item, m, i, v, &w->proto);
            t->rich = rich;
            bt->n_tris++;
            stats->tris_drawn++;
            if (drew && (!m->features || m->materials[m->tri_material[i]].alpha_mode == MAT_OPAQUE) &&
                drew_room(drew)) /* (a cut-out's pixels may be discarded: no occluder) */
                drew->drew[drew->n_drew++] = i;
            continue;
        }
        shade_vertices(fe, m, f, i, v, true); /* clipping interpolates the varyings */
        uint32_t shade = depth_only ? bt->n_shades : add_shade(bt, f, item, m, i, v, &w->proto);
        stats->tris_clipped++;
        clip_and_add(fe, f, v, any & VERTEX_NEEDS_CLIP, n_var, shade, rich);
    }
    w->n_culled += n_culled;
    w->n_no_centre += n_no_centre;
    w->n_hidden += n_hidden;
    stats->tris_occluded += n_occluded;
    return 0;
}

/* Triangles a .. b-1 (at most FRONTEND_FILTER; with a mask other than ~0, only a + j for
 * mask's bits j: the cut's marked ones in a run): the work just ahead of them first (the
 * vertex stage on the vertices from *vdone on, none when it is m->n_verts: the caller ran
 * it; by position, the positions from w->pos_done on projected and the vertices' mesh data
 * read ahead for the few whose records are made), then the ones outside the view or
 * holding no pixel centre dropped by a short loop of its own, the others' numbers put in
 * list. Their count. (The walk's loop, which can do everything, ran slower for the many it
 * drops: the car at 160x96 4.3 -> 4.1 ms, lost_empire 7.3 -> 6.9.) */
_Static_assert(CLUSTER_MAX_TRIS <= FRONTEND_FILTER, "filter takes a cluster at once");
_Static_assert(offsetof(struct vertex_out, fy) == 4 && offsetof(struct vertex_out, outcode) == 8 &&
                   offsetof(struct vertex_pos, fy) == 4 &&
                   offsetof(struct vertex_pos, outcode) == 8 && sizeof(struct vertex_pos) == 16,
               "filter copies a record's first 16 bytes: fx, fy, outcode");
static inline __attribute__((always_inline)) uint32_t
filter(const struct frame *f, struct tri_walk *w, uint32_t a, uint32_t b, uint32_t *vdone,
       const int by, const uint64_t mask, uint32_t *list)
{
    const bool by_pos = by != BY_VERTEX;
    const struct mesh *m = w->m;
    const struct vertex_out *vo = w->vo;
    const int fb_w = f->fb->w, fb_h = f->fb->h;
    uint32_t verts_done = *vdone, n = 0, rejected = 0, no_centre = 0;
    struct head { /* a record's first 16 bytes: vertex_out's and vertex_pos's alike */
        int32_t fx, fy;
        uint32_t outcode, rest;
    } h[3][FRONTEND_FILTER];
    uint32_t cnt = 0, tri[FRONTEND_FILTER]; /* (masked: lane j's triangle) */
    for (uint64_t todo = mask;; cnt++) { /* (masked: its set bits, lowest first) */
        uint32_t i;
        if (mask == ~0ull) {
            if ((i = a + cnt) >= b)
                break;
        } else {
            if (!todo)
                break;
            i = a + (uint32_t)__builtin_ctzll(todo);
            todo &= todo - 1;
        }
        const uint32_t *c = m->tris[i];
        const uint32_t j = cnt;
        tri[j] = i;
        if (verts_done < m->n_verts) { /* the vertex stage just ahead of the triangles */
            uint32_t hi = c[0] > c[1] ? c[0] : c[1];
            hi = c[2] > hi ? c[2] : hi;
            if (hi >= verts_done) {
                uint32_t to = verts_done + FRONTEND_VERTEX_CHUNK;
                to = hi + 1 > to ? hi + 1 : to;
                to = to < m->n_verts ? to : m->n_verts;
                if (by == BY_POSITION) {
                    /* the vertices' records are made (and lit) for the few triangles
                     * that pass: their mesh data read ahead, as the vertex stage did */
                    for (uint32_t k = verts_done; k < to; k += 2)
                        __builtin_prefetch(&m->verts[k]);
                } else if (by == BY_VERTEX) {
                    vertex_stage(f, w, verts_done, to);
                }
                verts_done = to;
            }
        }
        if (by_pos) {
            const uint32_t q0 = by == BY_HEAD ? c[0] : m->pos_id[c[0]];
            const uint32_t q1 = by == BY_HEAD ? c[1] : m->pos_id[c[1]];
            const uint32_t q2 = by == BY_HEAD ? c[2] : m->pos_id[c[2]];
            uint32_t qh = q0 > q1 ? q0 : q1;
            qh = q2 > qh ? q2 : qh;
            if (qh >= w->pos_done) { /* the heads just ahead (positions: numbered in order of
                                        use) */
                const uint32_t np = by == BY_HEAD ? m->n_verts : m->n_pos;
                uint32_t to = w->pos_done + FRONTEND_VERTEX_CHUNK;
                to = qh + 1 > to ? qh + 1 : to;
                to = to < np ? to : np;
                position_stage(f, m, w->pos, w->pos_done, to, by);
                w->pos_done = to;
            }
            memcpy(&h[0][j], &w->pos[q0], sizeof h[0][j]);
            memcpy(&h[1][j], &w->pos[q1], sizeof h[1][j]);
            memcpy(&h[2][j], &w->pos[q2], sizeof h[2][j]);
        } else {
            memcpy(&h[0][j], &vo[c[0]], sizeof h[0][j]);
            memcpy(&h[1][j], &vo[c[1]], sizeof h[1][j]);
            memcpy(&h[2][j], &vo[c[2]], sizeof h[2][j]);
        }
    }
    for (uint32_t j = cnt; j < FRONTEND_FILTER; j++) /* (the fixed count's spare lanes) */
        for (int k = 0; k < 3; k++)
            h[k][j] = (struct head){0, 0, 0, 0};
    /* setup_box_xy's question for all of them at once, in 32 bits (snapped corners lie
     * within +-2^23: viewport.h), over a fixed count the compiler makes vector code of
     * (SSE2: four at a time), from the corners' records' first 16 bytes copied whole (one
     * load and store each; copied field by field, eight stores a triangle, the 1M sphere
     * lost 3%); a corner not projected (the triangle is clipped: its box is its pieces')
     * counts as 0 */
    int32_t out[FRONTEND_FILTER], keep[FRONTEND_FILTER];
    const int32_t one = VIEWPORT_SUBPIX_ONE, half = one / 2, xmax = fb_w - 1, ymax = fb_h - 1;
    for (uint32_t j = 0; j < FRONTEND_FILTER; j++) {
        const uint32_t all = h[0][j].outcode & h[1][j].outcode & h[2][j].outcode;
        const uint32_t any = h[0][j].outcode | h[1][j].outcode | h[2][j].outcode;
        const int32_t o = ((all & VERTEX_OUT_FRUSTUM) != 0) | ((any & VERTEX_INVALID) != 0);
        const int32_t clip = (any & VERTEX_NEEDS_CLIP) != 0;
        const int32_t ok = clip - 1; /* (all ones when projected) */
        const int32_t x0 = h[0][j].fx & ok, x1 = h[1][j].fx & ok, x2 = h[2][j].fx & ok;
        const int32_t y0 = h[0][j].fy & ok, y1 = h[1][j].fy & ok, y2 = h[2][j].fy & ok;
        int32_t minx = x0 < x1 ? x0 : x1, maxx = x0 < x1 ? x1 : x0;
        int32_t miny = y0 < y1 ? y0 : y1, maxy = y0 < y1 ? y1 : y0;
        minx = x2 < minx ? x2 : minx, maxx = x2 > maxx ? x2 : maxx;
        miny = y2 < miny ? y2 : miny, maxy = y2 > maxy ? y2 : maxy;
        int32_t px0 = (minx - half + one - 1) >> VIEWPORT_SUBPIX_BITS;
        int32_t px1 = (maxx - half) >> VIEWPORT_SUBPIX_BITS;
        int32_t py0 = (miny - half + one - 1) >> VIEWPORT_SUBPIX_BITS;
        int32_t py1 = (maxy - half) >> VIEWPORT_SUBPIX_BITS;
        px0 = px0 < 0 ? 0 : px0, py0 = py0 < 0 ? 0 : py0;
        px1 = px1 > xmax ? xmax : px1, py1 = py1 > ymax ? ymax : py1;
        out[j] = o;
        keep[j] = (o ^ 1) & (clip | ((px0 <= px1) & (py0 <= py1)));
    }
    for (uint32_t j = 0; j < cnt; j++) { /* (each one out, kept, or else holding no centre) */
        rejected += (uint32_t)out[j];
        list[n] = mask == ~0ull ? a + j : tri[j];
        n += (uint32_t)keep[j];
    }
    no_centre = cnt - rejected - n;
    w->n_rejected += rejected;
    w->n_no_centre += no_centre;
    *vdone = verts_done;
    return n;
}

/* triangles a .. b-1 (at most FRONTEND_FILTER) filtered, then the kept ones walked: 0, or
 * -1 (by: a constant at every call, so each walk is compiled for its own) */
static inline __attribute__((always_inline)) int
filter_walk(struct frontend *fe, struct frame *f, struct tri_walk *w, uint32_t a, uint32_t b,
            uint32_t *vdone, const int by, struct err *e)
{
    uint32_t list[FRONTEND_FILTER];
    const uint32_t n = filter(f, w, a, b, vdone, by, ~0ull, list);
    return n && walk(fe, f, w, list, n, by, e) ? -1 : 0;
}

/* By position, a cluster's (or a run's, mask as filter's) triangles a .. b-1: filter
 * projects the positions; the kept triangles' vertex data (read when their records are
 * made and lit) is fetched now, and they are walked after the next cluster's filter, left
 * in late[0 .. *n_late) (the caller walks the last ones): the fetch has a cluster's walk
 * to arrive in. (The next cluster is tested before this one is walked, on the depth so
 * far: a little older, so it finds as many hidden or fewer, never wrongly.) 0, or -1. */
static inline __attribute__((always_inline)) int
filter_late(struct frontend *fe, struct frame *f, struct tri_walk *w, uint32_t a, uint32_t b,
            const uint64_t mask, uint32_t late[CLUSTER_MAX_TRIS], uint32_t *n_late,
            struct err *e)
{
    const struct mesh *m = w->m;
    uint32_t list[CLUSTER_MAX_TRIS], none = m->n_verts;
    const uint32_t n = filter(f, w, a, b, &none, BY_POSITION, mask, list);
    for (uint32_t q = 0; q < n; q++)
        for (int k = 0; k < 3; k++)
            __builtin_prefetch(&m->verts[m->tris[list[q]][k]]);
    if (*n_late && walk(fe, f, w, late, *n_late, BY_POSITION, e))
        return -1;
    memcpy(late, list, n * sizeof *list);
    *n_late = n;
    return 0;
}

/* triangles i0 .. i1-1, FRONTEND_FILTER at a time: filtered, then walked; the vertex stage
 * (or the heads) just ahead of them from *vdone on, as filter says */
static int walk_range(struct frontend *fe, struct frame *f, struct tri_walk *w, uint32_t i0,
                      uint32_t i1, uint32_t *vdone, const int by, struct err *e)
{
    for (uint32_t a = i0; a < i1; a += FRONTEND_FILTER) {
        const uint32_t b = i1 - a > FRONTEND_FILTER ? a + FRONTEND_FILTER : i1;
        if (by == BY_HEAD       ? filter_walk(fe, f, w, a, b, vdone, BY_HEAD, e)
            : by == BY_POSITION ? filter_walk(fe, f, w, a, b, vdone, BY_POSITION, e)
                                : filter_walk(fe, f, w, a, b, vdone, BY_VERTEX, e))
            return -1;
    }
    return 0;
}

/* a buffer of at least n bytes, zeroed */
static int zeroed(uint8_t **buf, size_t *cap, size_t n, struct err *e)
{
    if (n > *cap) {
        uint8_t *g = realloc(*buf, n);
        if (!g)
            return err_set(e, "out of memory for the front end's marks");
        *buf = g;
        *cap = n;
    }
    memset(*buf, 0, n);
    return 0;
}

/* The walk by position's scratch for w's mesh: a record slot per vertex (none made yet)
 * and a head per position (none made yet); by heads a byte per vertex (no record made) and
 * a head per vertex. 0, or -1 out of memory. */
static int positions_begin(struct frontend *fe, struct tri_walk *w, const int by,
                           struct err *e)
{
    const struct mesh *m = w->m;
    if (zeroed((uint8_t **)&fe->vslot, &fe->vslot_cap,
               (size_t)m->n_verts * (by == BY_HEAD ? 1 : sizeof *fe->vslot), e))
        return -1;
    const uint32_t np = by == BY_HEAD ? m->n_verts : m->n_pos; /* (heads: one a vertex) */
    if (np > fe->pos_cap) {
        struct vertex_pos *g = realloc(fe->pos, (size_t)np * sizeof *g);
        if (!g)
            return err_set(e, "out of memory for %u positions", (unsigned)np);
        fe->pos = g;
        fe->pos_cap = np;
    }
    w->pos = fe->pos;
    w->vslot = fe->vslot;
    w->made = (uint8_t *)fe->vslot;
    w->n_made = 0;
    w->pos_done = 0;
    return 0;
}

/* cluster c's verdict (cluster_cull.h) into *out, with the hidden test on the depth drawn
 * so far where w has one (the batch drawn first when it holds FRONTEND_CLUSTER_FLUSH
 * triangles or more): every triangle's box lies in the cluster's rectangle, its corners at
 * r.z_lo or behind, so hidden_behind asks for all of them at once. 0, or -1 (drawing
 * failed). */
static int cluster_verdict(struct frontend *fe, struct frame *f, const struct tri_walk *w,
                           const struct cluster_view *cv, const struct mesh_cluster *c,
                           enum cluster_verdict *out, struct err *e)
{
    struct cluster_rect r;
    *out = cluster_test(cv, c, w->hide || w->occ ? &r : NULL);
    if (*out != CLUSTER_DRAW || !(w->hide || w->occ) || !r.valid)
        return 0;
    const int64_t box[4] = {r.x0, r.y0, r.x1, r.y1};
    if (w->hide) {
        if (fe->batch[fe->cur].n_tris >= FRONTEND_CLUSTER_FLUSH && flush(fe, f, e))
            return -1;
        if (hidden_behind(w->hide, f->fb->w, box, r.z_lo, FRONTEND_HIDDEN_MAX_RECT, false)) {
            *out = CLUSTER_HIDDEN;
            return 0;
        }
    }
    if (w->occ && hidden_behind(w->occ, f->fb->w, box, r.z_lo, FRONTEND_HIDDEN_MAX_RECT, true)) {
        *out = CLUSTER_HIDDEN; /* (what the depth so far did not find: the occluders' own) */
        f->stats->clusters_occluded++;
    }
    return 0;
}

/* Triangles i0 .. i1-1 by clusters (cluster.h, cluster_cull.h), in the file's order (which
 * decides ties of depth): each cluster tested whole first — outside the view, facing away,
 * between pixel centres, or (with the hidden test on) behind the depth drawn so far over
 * its whole rectangle, after the batch is drawn when it holds FRONTEND_CLUSTER_FLUSH
 * triangles — and dropped before its vertices are made; the others' vertices made and
 * their triangles walked as without clusters. */
static int walk_clusters(struct frontend *fe, struct frame *f, struct tri_walk *w,
                         uint32_t i0, uint32_t i1, const int by, struct err *e)
{
    const struct mesh *m = w->m;
    const struct mesh_clusters *cs = m->clusters;
    if (by != BY_VERTEX && positions_begin(fe, w, by, e))
        return -1;
    if (by == BY_HEAD)
        w->pos_done = m->n_verts; /* (made below, by each cluster's v_need and v_end: filter
                                     has none to make ahead) */
    uint32_t vdone = 0; /* vertices (or heads) below it made, or read by no cluster still to
                           come (by position: unused, filter makes the positions ahead) */
    struct cluster_view cv;
    cluster_view_init(&cv, f->u.model, f->u.mvp, f->u.eye, f->u.ortho, f->u.view_back,
                      f->fb->w, f->fb->h, w->cull, w->by_material);
    struct frame_stats *st = f->stats;
    uint64_t dropped[CLUSTER_VERDICTS] = {0}, clusters[CLUSTER_VERDICTS] = {0}; /* by verdict:
                                                                triangles, clusters */
    uint32_t late[CLUSTER_MAX_TRIS], n_late = 0; /* by position: the last cluster's kept
                                                    triangles, still to walk */
    for (uint32_t id = i0 / CLUSTER_MAX_TRIS; id < cs->n; id++) {
        const struct mesh_cluster *c = &cs->c[id];
        if (c->tri_first >= i1)
            break;
        const uint32_t a = c->tri_first > i0 ? c->tri_first : i0;
        const uint32_t b = c->tri_first + c->n_tris < i1 ? c->tri_first + c->n_tris : i1;
        enum cluster_verdict cvd;
        if (cluster_verdict(fe, f, w, &cv, c, &cvd, e))
            return -1;
        clusters[cvd] += c->tri_first >= i0; /* (with slices: the one with its first) */
        if (cvd != CLUSTER_DRAW) {
            dropped[cvd] += b - a;
            continue;
        }
        if (by == BY_POSITION) {
            if (filter_late(fe, f, w, a, b, ~0ull, late, &n_late, e))
                return -1;
            continue;
        }
        /* the vertex stage (or the heads') from the lowest vertex this or a later cluster
         * reads (those below it that dropped clusters alone read are never made) to this
         * one's last */
        vdone = vdone > c->v_need ? vdone : c->v_need;
        if (vdone < c->v_end) {
            if (by == BY_HEAD)
                position_stage(f, m, w->pos, vdone, c->v_end, BY_HEAD);
            else
                vertex_stage(f, w, vdone, c->v_end);
            vdone = c->v_end;
        }
        uint32_t all = m->n_verts;
        if (by == BY_HEAD ? filter_walk(fe, f, w, a, b, &all, BY_HEAD, e)
                          : filter_walk(fe, f, w, a, b, &all, BY_VERTEX, e))
            return -1;
    }
    if (n_late && walk(fe, f, w, late, n_late, BY_POSITION, e))
        return -1;
    w->n_rejected += dropped[CLUSTER_FRUSTUM];
    w->n_culled += dropped[CLUSTER_FACING];
    w->n_no_centre += dropped[CLUSTER_NO_CENTRE];
    w->n_hidden += dropped[CLUSTER_HIDDEN];
    for (int k = 0; k < CLUSTER_VERDICTS; k++)
        st->clusters_tested += clusters[k];
    st->clusters_drawn += clusters[CLUSTER_DRAW];
    st->clusters_frustum += clusters[CLUSTER_FRUSTUM];
    st->clusters_facing += clusters[CLUSTER_FACING];
    st->clusters_no_centre += clusters[CLUSTER_NO_CENTRE];
    st->clusters_hidden += clusters[CLUSTER_HIDDEN];
    return 0;
}

/* Triangles i0 .. i1-1 by position (mesh.h's pos_id): the positions projected just ahead
 * of the triangles (once each, where every vertex was positioned before: lost_empire's
 * 450k vertices are 97k positions), each triangle rejected and boxed from its corners'
 * positions, and only the vertices of the triangles that pass made (their records the
 * same bits as the vertex stage's: vertex_run on each). */
static int walk_by_position(struct frontend *fe, struct frame *f, struct tri_walk *w,
                            uint32_t i0, uint32_t i1, const int by, struct err *e)
{
    if (positions_begin(fe, w, by, e))
        return -1;
    uint32_t vdone = by == BY_HEAD ? w->m->n_verts : 0; /* (heads: made by filter ahead) */
    return walk_range(fe, f, w, i0, i1, &vdone, by, e);
}

/* lod.h's lod_pixels_per_unit for an item's spheres in object space, its per-frame parts
 * once: pixels per object-space unit at the nearest point of sphere (c, r) */
struct ppu {
    double m[3][4], scale; /* the model matrix's rows, its largest stretch */
    vec3 eye, fwd;
    double near, k, ortho; /* k: fb_h / (2 tan(fov / 2)); ortho > 0: fb_h / view height */
};

static void ppu_init(struct ppu *q, const struct frame *f)
{
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 4; c++)
            q->m[r][c] = f->u.model.m[r][c];
    q->scale = frame_item_scale(f->u.model);
    const struct camera *cam = f->cam;
    q->eye = cam->eye;
    q->fwd = v3_norm(v3_sub(cam->target, cam->eye));
    q->near = cam->near;
    q->k = f->fb->h / (2 * tan(cam->fov_deg * (M_PI / 360.0)));
    q->ortho = cam->ortho_height > 0 ? f->fb->h / cam->ortho_height : 0;
}

static inline double ppu_at(const struct ppu *q, const float c[3], float r)
{
    if (q->ortho > 0)
        return q->ortho * q->scale;
    double z = -r * q->scale;
    for (int a = 0; a < 3; a++) {
        double w = q->m[a][0] * c[0] + q->m[a][1] * c[1] + q->m[a][2] * c[2] + q->m[a][3];
        z += (w - (a == 0 ? q->eye.x : a == 1 ? q->eye.y : q->eye.z)) *
             (a == 0 ? q->fwd.x : a == 1 ? q->fwd.y : q->fwd.z);
    }
    z = z > q->near ? z : q->near;
    return q->k / z * q->scale;
}

/* the cut's marked triangles (a bit each in tmark) in runs, in the mesh's order, the vertex
 * stage on the marked vertices just ahead of them */
static int cut_marked(struct frontend *fe, struct frame *f, struct tri_walk *w, uint64_t *tmark,
                      size_t words, uint32_t i0, uint32_t i1, struct err *e)
{
    uint32_t vdone = 0;
    for (size_t wd = i0 >> 6; wd < words && wd * 64 < i1;) {
        uint64_t bits = tmark[wd];
        if (!bits) {
            wd++;
            continue;
        }
        const uint32_t a = (uint32_t)(wd * 64) + (uint32_t)__builtin_ctzll(bits);
        uint64_t rest = ~bits & (~0ull << (a & 63)); /* the run's end: the first unmarked */
        while (!rest && ++wd < words)
            rest = ~tmark[wd];
        const uint32_t b = wd < words ? (uint32_t)(wd * 64) + (uint32_t)__builtin_ctzll(rest)
                                      : (uint32_t)(words * 64);
        const uint32_t lo = a > i0 ? a : i0, hi = b < i1 ? b : i1;
        if (lo < hi && walk_range(fe, f, w, lo, hi, &vdone, BY_VERTEX, e))
            return -1;
        if (wd < words) /* (word wd's bits below b are done) */
            tmark[wd] &= ~0ull << (b % 64);
        if (b >= i1)
            break;
    }
    return 0;
}

/* The cut's marked triangles by the hierarchy mesh's runs of 64 (cluster.h: run k is mark
 * word k), in the mesh's order: a run with a marked triangle tested whole as walk_clusters
 * tests a cluster — with the hidden test on the depth drawn so far, which the hierarchy's
 * own clusters, tested before anything is drawn, cannot have — and dropped (its marked
 * triangles counted in dropped[] by verdict), or its marked triangles walked, all at once
 * (filter's mask): by vertex after its vertex stage; by position walked after the next
 * run's filter as walk_clusters does; by heads after its heads. (Its box holds its
 * unmarked triangles too: only larger.) */
static int cut_runs(struct frontend *fe, struct frame *f, struct tri_walk *w,
                    const struct cluster_view *cv, const uint64_t *tmark, uint32_t i0,
                    uint32_t i1, const int by, uint64_t dropped[CLUSTER_VERDICTS],
                    struct err *e)
{
    const struct mesh *m = w->m;
    const struct mesh_clusters *cs = m->clusters;
    if (by != BY_VERTEX && positions_begin(fe, w, by, e))
        return -1;
    if (by == BY_HEAD)
        w->pos_done = m->n_verts; /* (made run by run below) */
    uint32_t vdone = 0, late[CLUSTER_MAX_TRIS], n_late = 0;
    for (uint32_t id = i0 / CLUSTER_MAX_TRIS; id < cs->n; id++) {
        const struct mesh_cluster *c = &cs->c[id];
        if (c->tri_first >= i1)
            break;
        uint64_t bits = tmark[id];
        if (c->tri_first < i0)
            bits &= ~0ull << (i0 - c->tri_first);
        if (i1 - c->tri_first < 64)
            bits &= (1ull << (i1 - c->tri_first)) - 1;
        if (!bits)
            continue;
        enum cluster_verdict cvd;
        if (cluster_verdict(fe, f, w, cv, c, &cvd, e))
            return -1;
        if (cvd != CLUSTER_DRAW) {
            dropped[cvd] += (uint64_t)__builtin_popcountll(bits);
            continue;
        }
        if (by == BY_POSITION) { /* the run's marked triangles at once */
            if (filter_late(fe, f, w, c->tri_first, c->tri_first + c->n_tris, bits, late,
                            &n_late, e))
                return -1;
            continue;
        }
        vdone = vdone > c->v_need ? vdone : c->v_need;
        if (vdone < c->v_end) { /* the run's heads, or its vertex stage */
            if (by == BY_HEAD)
                position_stage(f, m, w->pos, vdone, c->v_end, BY_HEAD);
            else
                vertex_stage(f, w, vdone, c->v_end);
            vdone = c->v_end;
        }
        /* then its marked triangles at once (filter's mask: one pass of its lanes, where a
         * stretch at a time paid a full pass for each; `by` a constant at each call) */
        uint32_t list[CLUSTER_MAX_TRIS], all = m->n_verts, n;
        const uint32_t a = c->tri_first, b = c->tri_first + c->n_tris;
        n = by == BY_HEAD ? filter(f, w, a, b, &all, BY_HEAD, bits, list)
                          : filter(f, w, a, b, &all, BY_VERTEX, bits, list);
        if (n && (by == BY_HEAD ? walk(fe, f, w, list, n, BY_HEAD, e)
                                : walk(fe, f, w, list, n, BY_VERTEX, e)))
            return -1;
    }
    return n_late && walk(fe, f, w, late, n_late, BY_POSITION, e) ? -1 : 0;
}

/* The hierarchy's cut (dag.h) for triangles i0 .. i1-1 of its mesh: each cluster whose own
 * error projects to at most lod_px and its parent's to more, unless culled whole
 * (cluster_cull.h), marks its triangles in the slice (a bit each) and, by vertex, their
 * vertices (a byte each); then the marked triangles are walked in the mesh's order: by
 * vertex, the vertex stage on the marked vertices just ahead of them, by the mesh's runs
 * with the hidden test on (cut_runs), else in runs of marked triangles (cut_marked); by
 * position (`by`: a mesh walks_by_position takes), by the mesh's runs, each run's marked
 * triangles at once, by heads instead when the runs the cut touches hold fewer vertices
 * than the mesh has positions. */
static int walk_cut(struct frontend *fe, struct frame *f, struct tri_walk *w, uint32_t i0,
                    uint32_t i1, const int by, struct err *e)
{
    const struct mesh *m = w->m;
    const struct mesh_dag *d = m->dag;
    const size_t words = ((size_t)m->n_opaque + 63) / 64;
    const bool vmarks = by == BY_VERTEX; /* (by position the walk makes what it needs) */
    if ((vmarks && zeroed(&fe->vdone, &fe->vdone_cap, (size_t)m->n_verts + 8, e)) ||
        zeroed((uint8_t **)&fe->marks, &fe->marks_cap, words * sizeof *fe->marks, e))
        return -1;
    uint64_t *tmark = fe->marks;
    uint8_t *vmark = fe->vdone;
    struct cluster_view cv;
    cluster_view_init(&cv, f->u.model, f->u.mvp, f->u.eye, f->u.ortho, f->u.view_back,
                      f->fb->w, f->fb->h, w->cull, w->by_material);
    struct frame_stats *st = f->stats;
    struct ppu pu;
    ppu_init(&pu, f);
    const double tau = f->o->lod_px;
    uint64_t dropped[CLUSTER_VERDICTS] = {0};
    for (uint32_t k = 0; k < d->n; k++) {
        const struct dag_cluster *c = &d->c[k];
        if (c->tri_hi < i0 || c->tri_lo >= i1)
            continue;
        if (!dag_cut_takes(c, c->error > 0 ? c->error * ppu_at(&pu, c->center, c->radius) : 0,
                           c->p_error >= 0 ? c->p_error * ppu_at(&pu, c->p_center, c->p_radius) : 0,
                           tau))
            continue;
        const bool whole = c->tri_lo >= i0 && c->tri_hi < i1;
        uint32_t n = c->n_tris;
        if (!whole) {
            n = 0;
            for (uint32_t q = 0; q < c->n_tris; q++) {
                const uint32_t t = dag_tri(d, c, q);
                n += t >= i0 && t < i1;
            }
        }
        const bool counts = c->tri_lo >= i0;
        st->dag_cut += counts;
        st->dag_levels |= 1u << (c->level < 31 ? c->level : 31);
        st->dag_tris += n;
        w->n_cut += n;
        st->clusters_tested += counts;
        enum cluster_verdict cvd = cluster_test(&cv, &c->box, NULL);
        if (cvd != CLUSTER_DRAW) {
            dropped[cvd] += n;
            if (cvd == CLUSTER_FRUSTUM)
                st->clusters_frustum += counts;
            else if (cvd == CLUSTER_FACING)
                st->clusters_facing += counts;
            else
                st->clusters_no_centre += counts;
            continue;
        }
        st->clusters_drawn += counts;
        for (uint32_t q = 0; q < c->n_tris; q++) {
            const uint32_t t = dag_tri(d, c, q);
            if (whole || (t >= i0 && t < i1)) {
                tmark[t >> 6] |= 1ull << (t & 63);
                if (vmarks && !(whole && c->n_verts))
                    for (int j = 0; j < 3; j++)
                        vmark[m->tris[t][j]] = 1;
            }
        }
        if (whole && vmarks && c->n_verts) /* (its copies: consecutive) */
            memset(vmark + c->vert_first, 1, c->n_verts);
    }
    w->vmark = vmarks ? vmark : NULL;
    int by_cut = by;
    if (by == BY_POSITION) { /* by heads when the runs the cut touches have fewer vertices
                                than the mesh has positions (a far view of a block world:
                                most of level 0 replaced by coarser clusters) */
        uint64_t heads = 0;
        uint32_t vd = 0;
        for (uint32_t id = i0 / CLUSTER_MAX_TRIS; id < m->clusters->n && heads < m->n_pos; id++)
            if (tmark[id]) {
                const struct mesh_cluster *c = &m->clusters->c[id];
                vd = vd > c->v_need ? vd : c->v_need;
                heads += c->v_end > vd ? c->v_end - vd : 0;
                vd = c->v_end > vd ? c->v_end : vd;
            }
        by_cut = heads < m->n_pos ? BY_HEAD : BY_POSITION;
    }
    if (m->clusters && (w->hide || by == BY_POSITION)) { /* the marked triangles by the mesh's
                                                            runs, hidden ones dropped */
        if (cut_runs(fe, f, w, &cv, tmark, i0, i1, by_cut, dropped, e)) {
            w->vmark = NULL;
            return -1;
        }
    } else if (cut_marked(fe, f, w, tmark, words, i0, i1, e)) {
        w->vmark = NULL;
        return -1;
    }
    w->vmark = NULL;
    w->n_rejected += dropped[CLUSTER_FRUSTUM];
    w->n_no_centre += dropped[CLUSTER_NO_CENTRE];
    w->n_culled += dropped[CLUSTER_FACING];
    w->n_hidden += dropped[CLUSTER_HIDDEN];
    return 0;
}

/* by position: the walk makes the vertex stage's records of the triangles that pass their
 * box alone, for a mesh whose vertices share positions (mesh.h keeps pos_id for at most one
 * position for every two vertices: lost_empire, 0.22, gains 17%; where every vertex has a
 * position of its own, the sports car, it lost 14%), with more triangles than the
 * framebuffer has pixels (most then hold no pixel centre: lost_empire at 160x96; at
 * 640x480, 225k triangles on 307k pixels, it lost 4%). With clusters, the clusters kept
 * are walked by position (lost_empire by clusters and by vertex lost 25% framed at
 * 160x96, and won 11% from inside the world, where most clusters lie outside the view). */
static bool walks_by_position(const struct mesh *m, int fb_w, int fb_h)
{
    return m->pos_id && 2 * (uint64_t)m->n_pos <= m->n_verts &&
           m->n_tris > (uint64_t)fb_w * (uint64_t)fb_h;
}

/* by heads (render_opts.h, RENDER_HEADS_RATIO): as by position with every vertex a
 * position of its own, the heads made from the vertices' positions in place */
static bool walks_by_heads(const struct mesh *m, int fb_w, int fb_h, int ratio)
{
    return ratio >= 0 && m->n_verts > (uint64_t)ratio * (uint64_t)fb_w * (uint64_t)fb_h;
}

/* The occluders of item d — the triangles of m it drew last frame, when m is the level it
 * drew then — into fe->occ at this frame's view: their corners positioned as the vertex
 * stage positions them (the kernel's position_run: the same snapped window positions and
 * depths), and at each pixel centre strictly inside one (a rasterizer covers those, whatever
 * its rule for edges) the farthest of its corners' depths kept where it is nearer than what
 * is there: setup clamps every pixel's depth to its corners' range, so the triangle, drawn
 * this frame, puts its own depth there at most that. One that needs clipping is left out.
 * 0, or -1 out of memory (fe->occ as it was). */
#define OCC_NARROW 24 /* pixels: an occluder's box narrower is tested centre by centre */
static int occluders_draw(struct frontend *fe, const struct frame *f, const struct mesh *m,
                          const struct frontend_item *d)
{
    if (d->occ_level != m || !d->n_occ)
        return 0;
    const int fb_w = f->fb->w, fb_h = f->fb->h;
    const size_t npx = (size_t)fb_w * (size_t)fb_h, nc = (size_t)d->n_occ * 3;
    if (npx > fe->occ_cap) {
        float *g = malloc(npx * sizeof *g);
        if (!g)
            return -1;
        free(fe->occ);
        fe->occ = g, fe->occ_cap = npx;
        fe->occ_any = false;
    }
    if (nc > fe->occ_xyz_cap) {
        float *x = malloc(nc * 3 * sizeof *x);
        struct vertex_pos *q = malloc(nc * sizeof *q);
        if (!x || !q) {
            free(x), free(q);
            return -1;
        }
        free(fe->occ_xyz), free(fe->occ_pos);
        fe->occ_xyz = x, fe->occ_pos = q, fe->occ_xyz_cap = nc;
    }
    if (!fe->occ_any) {
        float *occ = fe->occ; /* (a local: the stores may not alias fe) */
        for (size_t i = 0; i < npx; i++)
            occ[i] = INFINITY;
        fe->occ_any = true;
    }
    const uint32_t n_occ = d->n_occ;
    for (uint32_t q = 0; q < n_occ; q++) { /* (a mesh freed and another made at its address:
                                              its own triangles, drawn or not as any other) */
        /* (the corners a few triangles on fetched now: they lie all over the mesh) */
        if (q + 16 < n_occ && d->occ[q + 16] < m->n_opaque)
            __builtin_prefetch(m->tris[d->occ[q + 16]]);
        if (q + 8 < n_occ && d->occ[q + 8] < m->n_opaque) {
            const uint32_t *c = m->tris[d->occ[q + 8]];
            __builtin_prefetch(&m->verts[c[0]]);
            __builtin_prefetch(&m->verts[c[1]]);
            __builtin_prefetch(&m->verts[c[2]]);
        }
        const uint32_t *c = m->tris[d->occ[q] < m->n_opaque ? d->occ[q] : 0];
        for (int k = 0; k < 3; k++)
            memcpy(&fe->occ_xyz[9 * (size_t)q + 3 * (size_t)k], m->verts[c[k]].pos,
                   3 * sizeof *fe->occ_xyz);
    }
    f->k->position_run(fe->occ_xyz, 3 * sizeof *fe->occ_xyz, &f->u, fe->occ_pos, 0, (uint32_t)nc);
    const int64_t one = VIEWPORT_SUBPIX_ONE, half = one / 2;
    uint64_t drawn = 0;
    for (size_t t = 0; t < nc; t += 3) {
        const struct vertex_pos *a = &fe->occ_pos[t], *b = a + 1, *c = a + 2;
        const uint32_t i = d->occ[t / 3];
        if ((a->outcode | b->outcode | c->outcode) & VERTEX_NEEDS_CLIP || i >= m->n_opaque ||
            (m->features && m->materials[m->tri_material[i]].alpha_mode != MAT_OPAQUE))
            continue; /* (a cut-out is a feature: mesh.h) */
        int64_t box[4];
        if (!setup_box_xy(a->fx, a->fy, b->fx, b->fy, c->fx, c->fy, fb_w, fb_h, box))
            continue;
        const int64_t ax = a->fx, ay = a->fy, bx = b->fx, by = b->fy, cx = c->fx, cy = c->fy;
        const int64_t area = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
        if (area == 0)
            continue;
        const int64_t sg = area > 0 ? 1 : -1;
        float z = a->z > b->z ? a->z : b->z;
        z = c->z > z ? c->z : z;
        /* the edge functions (exact: whole numbers of 1/256 px squared) at the box's first
         * centre, stepped by rows and columns; a centre is inside where all three are
         * positive: tested one by one in a narrow box, and in a wide one each row's run
         * found from where each edge crosses zero */
        int64_t e[3], sx[3], sy[3];
        {
            const int64_t px0 = box[0] * one + half, py0 = box[1] * one + half;
            const int64_t ex[3][2] = {{bx - ax, by - ay}, {cx - bx, cy - by}, {ax - cx, ay - cy}};
            const int64_t ox[3][2] = {{ax, ay}, {bx, by}, {cx, cy}};
            for (int k = 0; k < 3; k++) {
                e[k] = (ex[k][0] * (py0 - ox[k][1]) - ex[k][1] * (px0 - ox[k][0])) * sg;
                sx[k] = -ex[k][1] * one * sg;
                sy[k] = ex[k][0] * one * sg;
            }
        }
        const bool narrow = box[2] - box[0] < OCC_NARROW;
        for (int64_t y = box[1]; y <= box[3]; y++, e[0] += sy[0], e[1] += sy[1], e[2] += sy[2]) {
            float *row = fe->occ + y * fb_w;
            if (narrow) {
                int64_t e0 = e[0], e1 = e[1], e2 = e[2];
                for (int64_t x = box[0]; x <= box[2]; x++, e0 += sx[0], e1 += sx[1], e2 += sx[2]) {
                    const float r = row[x]; /* (stored whatever it is: no branch to miss) */
                    row[x] = (e0 > 0) & (e1 > 0) & (e2 > 0) & (z < r) ? z : r;
                }
                continue;
            }
            int64_t lo = box[0], hi = box[2];
            for (int k = 0; k < 3 && lo <= hi; k++) { /* e = e[k] + sx[k] (x - box[0]) > 0 */
                if (sx[k] > 0) { /* from x - box[0] = floor(-e / sx) + 1 on */
                    const int64_t q = -e[k] >= 0 ? -e[k] / sx[k] : -((e[k] + sx[k] - 1) / sx[k]);
                    lo = box[0] + q + 1 > lo ? box[0] + q + 1 : lo;
                } else if (sx[k] < 0) { /* up to x - box[0] = ceil(e / -sx) - 1 */
                    const int64_t q = e[k] >= 0 ? (e[k] - sx[k] - 1) / -sx[k] : -(-e[k] / -sx[k]);
                    hi = box[0] + q - 1 < hi ? box[0] + q - 1 : hi;
                } else if (e[k] <= 0) {
                    hi = lo - 1;
                }
            }
            for (int64_t x = lo; x <= hi; x++)
                row[x] = z < row[x] ? z : row[x];
        }
        drawn++;
    }
    f->stats->occluders += drawn;
    return 0;
}

bool frontend_by_clusters(const struct mesh *m, const struct render_opts *o, bool wire)
{
    return m->clusters && o->cluster_cull == CLUSTER_CULL_ON && !wire &&
           o->view != VIEW_WIRE_OVERLAY && !dag_is_cut_mesh(m);
}

int frontend_triangles(struct frontend *fe, struct frame *f, const struct draw_item *item,
                       const struct mesh *m, struct vertex_out *vo, bool depth_only,
                       uint32_t i0, uint32_t i1, uint32_t verts_from, struct err *e)
{
    const struct render_opts *o = f->o;
    struct tri_walk w = {.item = item, .m = m, .vo = vo, .depth_only = depth_only,
                         .proto = {.mat = -1}};
    w.n_var = depth_only ? 0 : m->colors ? VARY_COLOR + 3 : vertex_varying_count(o->shade, o->view, f->u.lights.grey);
    /* a mesh with material features: the features path (its own varyings, shade.h) */
    f->u.rich = NULL;
    if (!depth_only && m->features && (w.proto.rich = rich_item(f, m))) {
        f->u.rich = &w.proto.rich->lay;
        w.n_var = -w.proto.rich->lay.n; /* (clip.h: the features path's all[]) */
    }
    w.rich = w.proto.rich != NULL;
    /* culling: --cull, or with auto the materials' sides (glTF's single-sided ones) */
    w.cull = o->cull;
    w.by_material = w.cull == CULL_AUTO && m->one_sided == MESH_SIDES_SOME;
    if (w.cull == CULL_AUTO)
        w.cull = m->one_sided == MESH_SIDES_ALL ? CULL_BACK : CULL_NONE;
    const bool wire = f->span.mode == SHADE_WIRE;
    const bool clusters = !depth_only && i1 <= m->n_opaque &&
                          frontend_by_clusters(m, o, wire);
    const bool cut = dag_is_cut_mesh(m) && !depth_only && !wire && o->view != VIEW_WIRE_OVERLAY;
    /* by position (walks_by_position): from the first vertex on, and only where no one else
     * reads the item's records (not wireframe's edges, not the hidden-line pre-pass) */
    const bool heads_ok = !cut && (verts_from == 0 || clusters) && i0 < i1 && !depth_only &&
                          !wire && o->view != VIEW_WIRE_OVERLAY;
    const bool cut_pos = cut && m->clusters && walks_by_position(m, f->fb->w, f->fb->h);
    const int by = cut_pos                                      ? BY_POSITION
                   : !heads_ok                                  ? BY_VERTEX
                   : walks_by_position(m, f->fb->w, f->fb->h) ? BY_POSITION
                   : walks_by_heads(m, f->fb->w, f->fb->h, o->heads_ratio) ? BY_HEAD
                                                                 : BY_VERTEX;
    if (by != BY_VERTEX && !cut) /* (the cut's: its own triangles, counted below) */
        f->stats->tris_by_position += i1 - i0;
    /* hidden triangles (frontend.h): on the depth buffer the batches drawn so far wrote —
     * one thread's (with a pool, the batch in flight is still writing it) */
    if (o->hidden_cull == HIDDEN_CULL_ON && !fe->workers && !depth_only &&
        f->fb->depth_mode == DEPTH_Z && !f->fb->overdraw && f->span.mode != SHADE_WIRE &&
        o->view != VIEW_WIRE_OVERLAY)
        w.hide = f->fb->depth;
    /* occluders (occluders_draw; frontend.h, "Occluders"): with --hidden-cull and where the
     * depth buffer is ours to read in its measure (as the hidden test, but threads may read
     * them), not a cut, a rasterizer whose coverage holds every strictly inside centre, and
     * no culling (an occluder must be drawn: one facing away this frame would not be) */
    struct frontend_item *d = fe->occ_item;
    fe->occ_item = NULL;
    const bool occ_ok = d && o->occluders != OCCLUDERS_OFF &&
                        o->hidden_cull == HIDDEN_CULL_ON && !depth_only && !cut &&
                        f->fb->depth_mode == DEPTH_Z && !f->fb->overdraw &&
                        f->span.mode != SHADE_WIRE && o->view != VIEW_WIRE_OVERLAY &&
                        (o->raster == RASTER_EDGE || o->raster == RASTER_TILED);
    const uint64_t occ0 = f->stats->occluders, hid0 = f->stats->tris_occluded,
                   cl0 = f->stats->clusters_occluded;
    bool occ_drawn = false;
    if (occ_ok && w.cull == CULL_NONE && !w.by_material) {
        if (d->occ_rest)
            d->occ_rest--;
        else if (occluders_draw(fe, f, m, d))
            return err_set(e, "out of memory for occluders");
        else
            occ_drawn = true;
        d->n_drew = 0;
        w.drew = d->occ_rest ? NULL : d; /* (resting, it lists only for the frame after) */
    } else if (d) {
        d->n_occ = 0;
    }
    if (occ_ok && fe->occ_any)
        w.occ = fe->occ;
    int rc = cut        ? walk_cut(fe, f, &w, i0, i1, by, e)
             : clusters ? walk_clusters(fe, f, &w, i0, i1, by, e)
             : by != BY_VERTEX ? walk_by_position(fe, f, &w, i0, i1, by, e)
                        : walk_range(fe, f, &w, i0, i1, &verts_from, BY_VERTEX, e);
    if (rc)
        return -1;
    if (occ_drawn) { /* what they hid that the depth so far did not, in triangles walked:
                        too little for their cost, and they sit out FRONTEND_OCC_REST frames */
        const uint64_t n = f->stats->occluders - occ0,
                       hid = (f->stats->clusters_occluded - cl0) * CLUSTER_MAX_TRIS +
                             (f->stats->tris_occluded - hid0);
        if ((double)hid >= FRONTEND_OCC_PAYS * (double)n || o->occluders == OCCLUDERS_ALWAYS)
            d->occ_strikes = 0;
        else if (++d->occ_strikes >= 2)
            d->occ_rest = FRONTEND_OCC_REST, d->occ_strikes = 0;
    }
    if (w.drew) { /* this frame's drawn triangles: the next frame's occluders */
        uint32_t *t = d->occ, tc = d->occ_cap;
        d->occ = d->drew, d->occ_cap = d->drew_cap, d->n_occ = d->n_drew;
        d->drew = t, d->drew_cap = tc, d->n_drew = 0;
        d->occ_level = m;
    }
    shade_queued(fe, f);
    struct frame_stats *stats = f->stats;
    stats->tris_in += cut ? w.n_cut : i1 - i0;
    stats->tris_by_position += cut && by != BY_VERTEX ? w.n_cut : 0;
    stats->tris_rejected += w.n_rejected;
    stats->tris_culled += w.n_culled;
    stats->tris_no_centre += w.n_no_centre;
    stats->tris_hidden += w.n_hidden;
    return 0;
}

/* A triangle's state for the outline (frontend_edges). */
enum { TRI_GONE = 0, TRI_FRONT = 1, TRI_BACK = 2, TRI_SHOWN = 4 };

static uint8_t tri_state(const struct vertex_out *const v[3], enum cull_mode cull)
{
    if ((v[0]->outcode | v[1]->outcode | v[2]->outcode) & VERTEX_INVALID)
        return TRI_GONE;
    int front = setup_front_facing(v[0], v[1], v[2]);
    uint8_t s = front ? TRI_FRONT : TRI_BACK;
    if (!(v[0]->outcode & v[1]->outcode & v[2]->outcode & VERTEX_OUT_FRUSTUM) &&
        !(cull != CULL_NONE && setup_culled(cull, front)))
        s |= TRI_SHOWN;
    return s;
}

/* Every edge of every triangle drawn (the wireframe as it always was). */
static void all_edges(const struct mesh *m, const struct vertex_out *vo,
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
        enum cull_mode cull = o->cull == CULL_AUTO ? CULL_NONE : o->cull;
        if (cull != CULL_NONE && setup_culled(cull, setup_front_facing(v[0], v[1], v[2]))) {
            stats->tris_culled += !overlay;
            continue;
        }
        for (int k = 0; k < 3; k++)
            line_draw_clip(fb, v[k]->clip, v[(k + 1) % 3]->clip, o->wire_color, depth_test);
        stats->tris_drawn += !overlay;
    }
}

static double win_len(const struct vertex_out *a, const struct vertex_out *b)
{
    double dx = a->win[0] - b->win[0], dy = a->win[1] - b->win[1];
    return sqrt(dx * dx + dy * dy);
}

void frontend_edges(struct frontend *fe, int it, const struct mesh *m,
                    const struct vertex_out *vo, const struct render_opts *o, bool depth_test,
                    bool overlay, struct fb *fb, struct frame_stats *stats)
{
    struct frontend_item *iv = it < fe->n_items ? &fe->items[it] : NULL;
    if (overlay || o->wire == WIRE_ALL || !iv) {
        all_edges(m, vo, o, depth_test, overlay, fb, stats);
        return;
    }
    struct err ignored;
    if (iv->edges.mesh != m || iv->edges.n_tris != m->n_tris)
        edge_table_build(&iv->edges, m, &ignored); /* out of memory: every edge, below */
    if (m->n_tris > iv->facing_cap) {
        free(iv->facing);
        iv->facing = malloc(m->n_tris);
        iv->facing_cap = iv->facing ? m->n_tris : 0;
    }
    if (!iv->edges.e || !iv->facing) {
        all_edges(m, vo, o, depth_test, overlay, fb, stats);
        return;
    }
    enum cull_mode cull = o->cull == CULL_AUTO ? CULL_NONE : o->cull;
    /* the model's projected area, front and back faces apart (a closed mesh: either is its
     * silhouette's area, about; an open one: the larger) */
    double area[2] = {0, 0};
    for (uint32_t i = 0; i < m->n_tris; i++) {
        const struct vertex_out *v[3] = {&vo[m->tris[i][0]], &vo[m->tris[i][1]],
                                         &vo[m->tris[i][2]]};
        uint8_t s = iv->facing[i] = tri_state(v, cull);
        if ((s & TRI_SHOWN) && o->wire == WIRE_AUTO && v[0]->projected && v[1]->projected &&
            v[2]->projected)
            area[(s & TRI_BACK) != 0] +=
                fabs((v[1]->win[0] - v[0]->win[0]) * (v[2]->win[1] - v[0]->win[1]) -
                     (v[2]->win[0] - v[0]->win[0]) * (v[1]->win[1] - v[0]->win[1])) / 2;
    }
    bool outline = o->wire == WIRE_OUTLINE;
    if (o->wire == WIRE_AUTO) { /* the edges' projected length per pixel of that area */
        double len = 0;
        for (uint32_t k = 0; k < iv->edges.n; k++) {
            const struct edge *ed = &iv->edges.e[k];
            bool shown = (iv->facing[ed->t0] & TRI_SHOWN) ||
                         (ed->t1 != EDGE_NONE && (iv->facing[ed->t1] & TRI_SHOWN));
            if (shown && vo[ed->v0].projected && vo[ed->v1].projected)
                len += win_len(&vo[ed->v0], &vo[ed->v1]);
        }
        double a = area[0] > area[1] ? area[0] : area[1];
        outline = len > WIRE_DENSITY_MAX * a;
    }
    if (!outline) { /* readable: every edge, exactly as --wire all draws them */
        all_edges(m, vo, o, depth_test, overlay, fb, stats);
        return;
    }
    for (uint32_t i = 0; i < m->n_tris; i++) {
        uint8_t s = iv->facing[i];
        stats->tris_in++;
        if (s & TRI_SHOWN)
            stats->tris_drawn++;
        else if (s == TRI_GONE || !(s & (TRI_FRONT | TRI_BACK)) ||
                 cull == CULL_NONE || !setup_culled(cull, s & TRI_FRONT))
            stats->tris_rejected++;
        else
            stats->tris_culled++;
    }
    for (uint32_t k = 0; k < iv->edges.n; k++) {
        const struct edge *ed = &iv->edges.e[k];
        uint8_t s0 = iv->facing[ed->t0], s1 = ed->t1 != EDGE_NONE ? iv->facing[ed->t1] : 0;
        if (!(s0 & TRI_SHOWN) && !(s1 & TRI_SHOWN))
            continue;
        if (outline && ed->t1 != EDGE_NONE && !ed->crease && s0 != TRI_GONE && s1 != TRI_GONE &&
            (s0 & (TRI_FRONT | TRI_BACK)) == (s1 & (TRI_FRONT | TRI_BACK)))
            continue; /* inside the outline: both faces turn the same way, no crease */
        line_draw_clip(fb, vo[ed->v0].clip, vo[ed->v1].clip, o->wire_color, depth_test);
    }
}

struct vertex_out *frontend_item_verts(struct frontend *fe, int it, uint32_t n, struct err *e)
{
    if (it >= fe->n_items) {
        struct frontend_item *ni = realloc(fe->items, (size_t)(it + 1) * sizeof *ni);
        if (!ni)
            return err_set(e, "out of memory for %d draw items", it + 1), NULL;
        memset(ni + fe->n_items, 0, (size_t)(it + 1 - fe->n_items) * sizeof *ni);
        fe->items = ni;
        fe->n_items = it + 1;
    }
    struct frontend_item *iv = &fe->items[it];
    if (n > iv->cap) { /* 64-byte aligned: each half of a vertex is one cache line */
        void *nv = NULL;
        if (posix_memalign(&nv, 64, (size_t)n * sizeof *iv->v))
            return err_set(e, "out of memory for %u vertices", n), NULL;
        mem_big(nv, (size_t)n * sizeof *iv->v);
        free(iv->v); /* the vertex stage rewrites every vertex each frame: nothing to keep */
        iv->v = nv;
        iv->cap = n;
    }
    return iv->v;
}

int frontend_finish(struct frontend *fe, struct frame *f, struct err *e)
{
    int rc = flush(fe, f, e);
    drain(fe, f);
    return rc;
}

void frontend_abandon(struct frontend *fe, struct frame *f)
{
    drain(fe, f);
}
