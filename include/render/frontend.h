/* frontend.h: the front end of one thread of drawing — vertex stage, trivial rejection,
 * culling, clipping and triangle setup of a draw item's triangles, appended to a batch
 * (batch.h) that the back end draws, and the edges of wireframe as lines.
 *
 * By clusters (--cluster-cull, on by default; frontend_by_clusters says for which meshes):
 * the item's clusters (scene/cluster.h) in the file's order, each first tested whole
 * (cluster_cull.h: outside the view, facing away, between pixel centres, or hidden behind
 * the depth drawn so far over its rectangle, after the batch is drawn when it holds
 * FRONTEND_CLUSTER_FLUSH triangles or more) and dropped before any of its vertices is
 * made; the vertex stage then runs from the cluster's v_need to its v_end (walking by
 * position: its positions are projected just ahead, as below), and its triangles go
 * through the steps below as any others (the sports car at 160x96: 44% of its clusters
 * hidden, 6% between pixel centres).
 *
 * For each triangle of an item, in order:
 *     the vertex stage just ahead of it (kernel.h's vertex_run, in chunks of at least
 *       FRONTEND_VERTEX_CHUNK vertices: each unique vertex positioned once a frame) — or,
 *       walking by position (a mesh with mesh.h's pos_id, drawn from its first vertex, not
 *       by clusters, not as wireframe or its pre-pass), each distinct position projected
 *       once instead (outcode, snapped window position; lost_empire: 97k positions for
 *       450k vertices), read ahead in the same chunks; or walking by heads (a mesh with
 *       more vertices than render_opts.heads_ratio times the pixels: the 1M sphere at
 *       160x96), the same with every vertex its own position
 *     trivial reject (all corners outside one frustum plane, or a corner not finite)
 *     its pixel box (setup_box): no pixel centre in it, dropped (most triangles of a dense
 *       mesh at terminal sizes); by position both from the corners' positions, and the
 *       corners' records made (vertex_run's bytes, from the position, into the next free
 *       records: those drawn triangles read lie together) only once setup draws the
 *       triangle (setup.c reads the snapped corners alone) — before culling when culling
 *       reads their clip positions, for clipping
 *     hidden (--hidden-cull, on by default; "Hidden" below): an unclipped triangle whose
 *       nearest corner is at or behind the depth buffer over its whole pixel box, dropped
 *       before its corners' records are made or lit
 *     facing and culling, once per source triangle
 *     setup.c: edge equations and the tie rule; covering no centre of a box of a few
 *       pixels, dropped before its vertices are lit
 *     its vertices' world positions and varyings (vertex_shade, or queued for
 *       vertex_shade_many), its shading record (flat: its lighting)
 *     clip.c: polygon clipping, only when outcodes say a corner is outside the near/far
 *       planes or the x/y guard band; each piece set up
 * Every FRONTEND_FLUSH_ONE_THREAD set-up triangles (FRONTEND_FLUSH_THREADS with a pool) and
 * at the end the batch goes to the back end: batch_draw_start on the pool (or now, on this
 * thread), while the front end fills the other of its two batches.
 *
 * Hidden. setup.c clamps every pixel's depth to the corners' range (setup_interp's z_lo,
 * in float), and the depth test is LESS: a triangle whose least corner depth is at or
 * behind what the depth buffer holds at every pixel of its box draws no fragment, now or
 * later (the buffer only comes nearer). The front end asks that of each triangle that
 * passes its box, on the depth the batches sent so far wrote (the current batch's
 * triangles are not in it yet: fewer found, none wrongly), and drops those it holds for:
 * no vertex made or lit, no setup, no shading record. The picture is the same bytes
 * (tests/unit/test_hidden.c). Only where the buffer is ours to read and in that measure:
 * the default depth method (DEPTH_Z), no overdraw count, not wireframe or its pre-pass,
 * and one thread drawing each batch as it goes out (the slices plan's threads each their
 * own buffer; with a pool the batch in flight is still writing it: off). Boxes of more
 * than FRONTEND_HIDDEN_MAX_BOX pixels are not tested (a large triangle is most often
 * seen, and reading its box would cost what drawing it does). Which triangles are found
 * depends on when batches go out: frame_stats.tris_hidden counts them, and tris_drawn is
 * smaller by as many (lost_empire at 160x96: 11.9k hidden of the 23.8k triangles that
 * pass their box, the car 20.8k of 30.0k; README, "Hidden triangles"). *
 * Occluders (--occluders, with --hidden-cull; on by default). The hidden test reads only
 * what the file's order drew before, so a surface drawn late hides nothing. Each draw item
 * keeps the triangles of its level it drew in the last frame (set up with a pixel centre,
 * unclipped, not a cut-out: struct frontend_item's occ), and before it is walked they are
 * drawn at this frame's view into a depth of the front end's own (occluders_draw): their
 * corners positioned by the kernel's position_run (the vertex stage's snapped positions and
 * depths), and at each pixel centre strictly inside one (every rasterizer covers those) the
 * farthest of its corners' depths kept where nearer. Setup clamps a triangle's depth to its
 * corners' range, so at such a centre the occluder, drawn again this frame, puts a depth
 * there at most that; a cluster (its box's nearest corner) or a triangle (its nearest
 * corner) strictly behind it at every centre of its box draws nothing that shows, in any
 * order — and the occluder nearest at a centre can never itself be found behind, so it is
 * drawn. Strictly: an equal depth is a tie, which the file's order decides. The buffer
 * does not change while the frame is walked, so threads may read it (tiles and slices
 * alike: a slice's occluders are what it drew). Not with face culling (an occluder facing
 * away this frame is not drawn), a hierarchy's cut (its triangles change every frame),
 * another depth method, the overdraw view, wireframe, or a rasterizer other than edge or
 * tiled. The picture is the same bytes (tests/unit/test_hidden.c, along a moving camera);
 * frame_stats.occluders counts them and tris_occluded, clusters_occluded what they hid (of
 * tris_hidden, clusters_hidden). The first frame has none. They are tested after the depth
 * so far (so clusters_occluded, tris_occluded are what that did not find), and where they
 * find little — a convex model, whose far side the file's order already hides — they cost
 * more than they save: FRONTEND_OCC_PAYS below rests them.
 *
 * Owns: per-item vertex outputs and the two batches, allocated once and reused across
 * frames, so a frame performs no allocation once the largest mesh has been seen. One per
 * thread that runs a front end: the tiles plan has one, the slices plan one per slice. */
#ifndef RASTTY_FRONTEND_H
#define RASTTY_FRONTEND_H

#include <stdbool.h>
#include <stdint.h>

#include "batch.h"
#include "edges.h"
#include "frame.h"
#include "scene.h"
#include "workers.h"

/* One thread draws a batch right after setting it up: a smaller batch finds the vertex
 * records its interpolation setup reads still in the caches (lost_empire at 160x96: a drawn
 * triangle for every 16 set up, 8192 drawn ones span ~16 MB of vertex records; 16.8 -> 13.8
 * ms with 1024). Several threads draw one batch while the front end sets up the next:
 * batches small enough that the first is handed over early. */
#define FRONTEND_FLUSH_ONE_THREAD 1024
#define FRONTEND_FLUSH_THREADS 512
/* The vertex stage runs in chunks of at least this many vertices just before the first
 * triangle that uses them: it then reads vertex records still in the caches (a mesh whose
 * triangles come in the order of their vertices, as exporters write them; any other order
 * makes the chunks larger, up to the whole mesh at once). With threads too: run on every
 * thread first, the dense models' records (57 MB for lost_empire) were out of the caches
 * again when the front end read them (car 2 threads 7.9 -> 7.2 ms). */
#define FRONTEND_VERTEX_CHUNK 512
/* Triangles filtered at a time (frontend.c, filter): outside the view or holding no pixel
 * centre, dropped by a short loop before the walk takes the rest */
#define FRONTEND_FILTER 64
/* The largest pixel box the hidden test reads ("Hidden" above) */
#define FRONTEND_HIDDEN_MAX_BOX 1024
/* a cluster's rectangle read for the hidden test, at most (pixels) */
#define FRONTEND_HIDDEN_MAX_RECT 4096
/* Occluders ("Occluders" above) pay when what they hide beyond the depth so far, in
 * triangles walked (a cluster: CLUSTER_MAX_TRIS), is FRONTEND_OCC_PAYS times their number
 * or more; an item whose occluders hid less in two frames running (the first list after a
 * frame without them holds every triangle drawn, the overdrawn too) draws none for the next
 * FRONTEND_OCC_REST frames (it still lists what it draws), then tries again
 * (--occluders always: never rests) */
#define FRONTEND_OCC_PAYS 1.5
#define FRONTEND_OCC_REST 8
/* before a cluster's hidden test, a batch of this many triangles or more is drawn first
 * (the car at 160x96, the fastest of 7 runs: 0 4.35 ms, 16 4.30, 64 4.27-4.35, 256 4.39,
 * only when full 4.47) */
#define FRONTEND_CLUSTER_FLUSH 64

struct frontend {
    /* vertex-stage output per draw item, reused across frames (64-byte aligned: each half of
     * a vertex record is one cache line) */
    struct frontend_item {
        struct vertex_out *v;
        uint32_t cap;
        const struct mesh *level; /* the level of detail this frame draws (chosen once) */
        struct edge_table edges;  /* wire outline: the level's edges (built when first drawn) */
        uint8_t *facing;          /* wire outline: per triangle, scratch */
        uint32_t facing_cap;
        /* occluders (frontend.c's occluders_draw): the triangles of `level` the last frame
         * drew (set up with a pixel centre, unclipped), and this frame's, being listed */
        uint32_t *occ, n_occ, occ_cap;
        const struct mesh *occ_level;
        uint32_t *drew, n_drew, drew_cap;
        uint8_t occ_rest;    /* frames its occluders sit out (they hid too little) */
        uint8_t occ_strikes; /* frames running its occluders hid too little */
    } *items;
    int n_items;
    /* set-up triangles: front end -> back end. With a pool, the pool draws one batch while
     * the front end fills the other: batch[cur] is being filled, batch[!cur] is being
     * drawn when in_flight */
    struct batch batch[2];
    int cur;
    bool in_flight;
    /* the back end the batches go to (frontend_use) */
    struct workers *workers;  /* NULL: this thread draws each batch at once */
    struct span_ctx *ctx;     /* one per thread of the back end */
    int n_ctx;
    uint32_t flush_at;        /* set-up triangles that make the back end run */
    /* vertices of set-up triangles waiting for vertex_shade_many: shaded together before the
     * back end reads them; at most three per set-up triangle */
    uint32_t *vq_idx;
    struct vertex_out **vq_out;
    uint32_t vq_n, vq_cap;
    const struct mesh *vq_mesh;
    /* the hierarchy's cut (dag.h, walk_cut), for the item being walked: which vertices the
     * vertex stage makes (a byte each), which triangles may draw (a bit each); cleared per
     * item */
    uint8_t *vdone;
    uint64_t *marks;
    size_t vdone_cap, marks_cap;
    /* positions (mesh.h's pos_id), for the item being walked by position: each projected
     * once (n_pos of them), and per vertex where its record is (slot + 1, 0: not made) */
    struct vertex_pos *pos;
    uint32_t *vslot;
    size_t pos_cap, vslot_cap;
    /* the occluder depth of this frame (occluders_draw): per pixel, the farthest corner of
     * the nearest last-frame triangle whose inside holds its centre (INFINITY: none); the
     * item whose occluders the next frontend_triangles draws and whose triangles it lists
     * (the plan sets it; NULL: none) */
    float *occ;
    size_t occ_cap;
    bool occ_any;
    struct frontend_item *occ_item;
    float *occ_xyz;
    struct vertex_pos *occ_pos;
    size_t occ_xyz_cap;
};

/* Batches of batch_cap set-up triangles (tests: the picture must not depend on it). 0 or
 * -1 with e set (out of memory). */
int frontend_init(struct frontend *fe, uint32_t batch_cap, struct err *e);
void frontend_free(struct frontend *fe);
/* The back end for this frame: w's threads and this one (ctx[0] .. ctx[n_ctx - 1]: one span
 * context per thread, filled from f's template), or this thread alone (w NULL, n_ctx 1).
 * Empties the batch being filled. */
void frontend_begin(struct frontend *fe, const struct frame *f, struct workers *w,
                    struct span_ctx *ctx, int n_ctx);
/* Item it's vertex-stage output array, grown to n (kept across frames); NULL and e set when
 * out of memory. */
struct vertex_out *frontend_item_verts(struct frontend *fe, int it, uint32_t n, struct err *e);
/* Does the front end walk m's opaque triangles by clusters under o, wire: wireframe shading
 * (and so make their vertices itself: the caller's verts_from is not read)? --cluster-cull
 * on, a mesh with clusters that is not a hierarchy's cut, not wireframe or its overlay
 * (their edges read every vertex). A mesh walked by position keeps that walk for the
 * clusters kept. */
bool frontend_by_clusters(const struct mesh *m, const struct render_opts *o, bool wire);
/* The front end for the item's triangles i0 .. i1-1 of m (the item's mesh at the level of
 * detail drawn; no triangle uses a vertex below verts_from: the vertex stage starts there)
 * with vertex records vo; depth_only: the hidden-line pre-pass (every face, whatever the
 * culling; no shading records). 0 or -1 (out of memory). */
int frontend_triangles(struct frontend *fe, struct frame *f, const struct draw_item *item,
                       const struct mesh *m, struct vertex_out *vo, bool depth_only,
                       uint32_t i0, uint32_t i1, uint32_t verts_from, struct err *e);
/* The surfaces are complete: what is set up goes to the back end, and every batch is drawn
 * before this returns (the counts of pixels are then in the span contexts). 0 or -1. */
int frontend_finish(struct frontend *fe, struct frame *f, struct err *e);
/* Nothing may be left drawing once the caller has the frame back: joins the pool after a
 * failure. */
void frontend_abandon(struct frontend *fe, struct frame *f);

/* Triangle edges of m (item it's mesh at its level; vertex records vo, positioned) as
 * lines, depth-tested when asked: every edge, or with o->wire the outline (render_opts.h,
 * edges.h). `overlay` edges decorate a shaded frame: they are not counted as the frame's
 * triangles, and are always every edge. */
void frontend_edges(struct frontend *fe, int it, const struct mesh *m,
                    const struct vertex_out *vo, const struct render_opts *o, bool depth_test,
                    bool overlay, struct fb *fb, struct frame_stats *stats);

#endif
