/* test_hidden.c: hidden triangles (--hidden-cull; render/frontend.h, "Hidden") — a frame
 * drawn with them dropped is the same bytes, colour and depth, as with every triangle
 * drawn: from a hundred random views of two bumpy spheres, one in front of the other, with
 * coplanar duplicate triangles whose order decides ties of depth; both walks (by position:
 * the faceted sphere, whose vertices share positions; by vertex: the smooth one), every
 * kernel this build and CPU have, every shading mode, one thread and two (slices; by tiles
 * two threads leave it off: the batch in flight writes the depth buffer meanwhile), and
 * the features path (a material with an alpha cutout), with whole clusters hidden too
 * (cluster_cull.h: the smooth sphere is walked by clusters; every third view by its
 * vertices' heads, render_opts.h) against a frame with neither;
 * while many triangles and clusters are dropped. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cluster.h"
#include "gen_mesh.h"
#include "kernel.h"
#include "mtl.h"
#include "pipeline.h"
#include "test.h"

/* gen_mesh.h's displaced sphere, the copies and every fifth triangle of material 1; crease
 * 0: every face its own normals (vertices share positions: walked by position), 180:
 * smooth. Material 0 grey, 1 red, with an alpha cutout it passes (the features path) when
 * `cutout`. */
static int sphere(struct mesh *m, int rows, int dup, float crease, bool cutout)
{
    if (gen_bumpy_sphere(m, rows, dup, 5, crease))
        return -1;
    m->materials = calloc(2, sizeof *m->materials);
    if (!m->materials)
        return -1;
    m->n_materials = 2;
    mtl_default(&m->materials[0], "grey");
    mtl_default(&m->materials[1], "red");
    m->materials[0].kd[0] = m->materials[0].kd[1] = m->materials[0].kd[2] = 0.6f;
    m->materials[1].kd[0] = 1, m->materials[1].kd[1] = m->materials[1].kd[2] = 0.1f;
    if (cutout) { /* (above the cutoff: drawn, by the features path) */
        m->materials[1].alpha = 0.7f;
        m->materials[1].alpha_mode = MAT_MASK;
        m->materials[1].alpha_cutoff = 0.5f;
        m->materials[1].features = true;
        m->features = true;
    }
    return 0;
}

TEST(hidden_triangles_dropped_change_no_byte_from_any_view)
{
    struct mesh faceted, smooth;
    REQUIRE(sphere(&faceted, 40, 1500, 0, false) == 0);
    REQUIRE(sphere(&smooth, 40, 1500, 180, true) == 0);
    REQUIRE(faceted.pos_id && !smooth.pos_id); /* the two walks */
    /* clusters on both: the smooth one is walked by them (the faceted one by position, which
     * is preferred where it applies) */
    REQUIRE(cluster_build(&faceted) == 0 && cluster_build(&smooth) == 0);
    struct pipeline *p = pipeline_new();
    REQUIRE(p);
    struct fb a, b;
    REQUIRE(fb_init(&a, 80, 48, false, NULL) == 0 && fb_init(&b, 80, 48, false, NULL) == 0);
    REQUIRE(faceted.n_tris > 80 * 48); /* (denser than the framebuffer: by position) */
    static const enum shade_mode modes[] = {SHADE_PHONG, SHADE_GOURAUD, SHADE_FLAT, SHADE_UNLIT};
    unsigned seed = 25;
    uint64_t cases = 0, differ = 0, hidden = 0, some = 0, by_pos = 0, by_clusters = 0,
             by_heads = 0;
    for (int view = 0; view < 100; view++) {
        struct camera cam;
        camera_default(&cam);
        double dist = view % 5 == 0 ? gen_rnd(&seed, 0.8, 1.5) : exp(gen_rnd(&seed, log(2), log(60)));
        double th = gen_rnd(&seed, 0, 2 * M_PI), el = gen_rnd(&seed, -1.4, 1.4);
        cam.eye = v3(dist * cos(el) * cos(th), dist * sin(el), dist * cos(el) * sin(th));
        cam.target = v3(gen_rnd(&seed, -1, 1), gen_rnd(&seed, -1, 1), gen_rnd(&seed, -1, 1));
        cam.fov_deg = gen_rnd(&seed, 15, 80);
        if (view % 9 == 0)
            cam.ortho_height = gen_rnd(&seed, 0.5, 6);
        /* the two spheres overlapping, in either order in the list */
        struct draw_item items[2] = {
            {.mesh = &faceted, .model = m4_identity()},
            {.mesh = &smooth,
             .model = m4_mul(m4_translate(v3(gen_rnd(&seed, -1, 1), gen_rnd(&seed, -1, 1),
                                             gen_rnd(&seed, -1.5, 1.5))),
                             m4_rotate(v3(1, 2, 3), gen_rnd(&seed, 0, 360)))}};
        if (view % 2) {
            struct draw_item tmp = items[0];
            items[0] = items[1], items[1] = tmp;
        }
        for (int k = KERNEL_REF; k <= KERNEL_AVX2_4; k++) {
            if (!kernel_set((enum kernel_isa)k))
                continue; /* (not in this build, or not on this CPU) */
            for (int run = 0; run < 3; run++) { /* one thread; two by slices; two by tiles */
                struct render_opts o;
                render_opts_default(&o);
                o.kernel = (enum kernel_isa)k;
                o.shade = modes[(view + k) % 4];
                o.threads = run ? 2 : 1;
                o.split = run == 1 ? SPLIT_SLICES : SPLIT_TILES;
                struct frame_stats st = {0}, st_off = {0};
                /* against every triangle drawn: no clusters, nothing hidden */
                o.hidden_cull = HIDDEN_CULL_OFF;
                o.cluster_cull = CLUSTER_CULL_OFF;
                REQUIRE(pipeline_draw(p, items, 2, NULL, &cam, &o, &a, &st_off, NULL) == 0);
                o.hidden_cull = HIDDEN_CULL_ON;
                o.cluster_cull = CLUSTER_CULL_ON;
                /* every third view the smooth one by its vertices' heads (render_opts.h) */
                const bool heads = view % 3 == 0;
                o.heads_ratio = heads ? 0 : RENDER_HEADS_RATIO;
                REQUIRE(pipeline_draw(p, items, 2, NULL, &cam, &o, &b, &st, NULL) == 0);
                if (heads && run == 0) /* (the faceted one by position, the smooth one by
                                          heads: every triangle by its heads) */
                    CHECK_EQ_INT(st.tris_by_position, st.tris_in);
                by_heads += heads && st.tris_by_position == st.tris_in;
                cases++;
                differ += memcmp(a.rgb, b.rgb, (size_t)a.w * a.h * 3) != 0 ||
                          memcmp(a.depth, b.depth, (size_t)a.w * a.h * sizeof *a.depth) != 0;
                CHECK_EQ_INT(st_off.tris_hidden, 0);
                if (run == 2) /* (a pool's batch in flight writes the depth buffer: off; the
                                 occluders, of the frame before, hide alone) */
                    CHECK_EQ_INT(st.tris_hidden, st.tris_occluded);
                hidden += st.tris_hidden;
                some += st.tris_hidden > 0;
                by_clusters += st.clusters_hidden > 0;
                by_pos += st.tris_by_position > 0;
                /* every triangle accounted for, the dropped ones among them */
                CHECK_EQ_INT(st.tris_in, st_off.tris_in);
                CHECK(st.tris_drawn + st.tris_hidden + st.tris_no_centre >=
                      st_off.tris_drawn + st_off.tris_no_centre);
                CHECK(st.tris_drawn <= st_off.tris_drawn);
            }
        }
    }
    printf("    %llu frames, %llu differ; %llu with triangles hidden (%llu in all), %llu with "
           "clusters hidden, %llu walked by position\n",
           (unsigned long long)cases, (unsigned long long)differ, (unsigned long long)some,
           (unsigned long long)hidden, (unsigned long long)by_clusters,
           (unsigned long long)by_pos);
    CHECK_EQ_INT(differ, 0);
    CHECK(some > cases / 3);
    CHECK(by_clusters > cases / 10);
    CHECK(by_pos > cases / 4);
    CHECK(by_heads > cases / 6);
    fb_free(&a);
    fb_free(&b);
    pipeline_destroy(p);
    mesh_free(&faceted);
    mesh_free(&smooth);
}

/* A square card of two triangles facing +z at z = 0, then the same two again with material
 * 1: coplanar duplicates whose first copy (red) wins every tie, facing an orthographic
 * camera down -z with one depth at every corner (a tie an occluder test must not take). */
static int card(struct mesh *m)
{
    static const float pos[] = {-0.6f, -0.6f, 0, 0.6f, -0.6f, 0, 0.6f, 0.6f, 0, -0.6f, 0.6f, 0};
    static const uint32_t q[] = {0, 1, 2, 0, 2, 3, 0, 1, 2, 0, 2, 3};
    static const uint16_t tm[] = {0, 0, 1, 1};
    struct mesh_corner c[12];
    for (int i = 0; i < 12; i++)
        c[i] = (struct mesh_corner){q[i], MESH_NONE, MESH_NONE};
    struct mesh_source src = {.pos = pos, .n_pos = 4, .corners = c, .n_tris = 4,
                              .tri_material = tm};
    memset(m, 0, sizeof *m);
    if (mesh_build(&src, m, NULL) || !(m->materials = calloc(2, sizeof *m->materials)))
        return -1;
    m->n_materials = 2;
    mtl_default(&m->materials[0], "red");
    mtl_default(&m->materials[1], "blue");
    m->materials[0].kd[1] = m->materials[0].kd[2] = 0;
    m->materials[1].kd[0] = m->materials[1].kd[1] = 0;
    return 0;
}

/* Occluders (--occluders; frontend.h, "Occluders"): each item's triangles the last frame
 * drew, drawn first at this frame's view, hide what lies strictly behind them. Along a
 * camera path — small steps and jumps, the items' order swapped, one sphere turning, every
 * shading mode, one thread, two by slices and two by tiles (where the depth buffer is off
 * limits and the occluders hide alone) — every frame is the same bytes, colour and depth,
 * as a frame drawn with nothing culled, the coplanar duplicates, a cut-out whose pixels
 * are all discarded (no occluder), and every fifth frame a card of duplicates seen face on
 * (their ties: the test must be strict) included; and the occluders hide clusters and
 * triangles in most frames. */
TEST(occluders_of_the_last_frame_change_no_byte_as_the_camera_moves)
{
    struct mesh faceted, smooth;
    REQUIRE(sphere(&faceted, 40, 1500, 0, false) == 0);
    REQUIRE(sphere(&smooth, 40, 1500, 180, true) == 0);
    smooth.materials[1].alpha = 0.3f; /* (under the cutoff: every pixel discarded) */
    REQUIRE(cluster_build(&faceted) == 0 && cluster_build(&smooth) == 0);
    struct mesh sq;
    REQUIRE(card(&sq) == 0);
    struct pipeline *p = pipeline_new(), *q = pipeline_new();
    REQUIRE(p && q);
    struct fb a, b;
    REQUIRE(fb_init(&a, 80, 48, false, NULL) == 0 && fb_init(&b, 80, 48, false, NULL) == 0);
    static const enum shade_mode modes[] = {SHADE_PHONG, SHADE_GOURAUD, SHADE_FLAT, SHADE_UNLIT};
    unsigned seed = 7;
    uint64_t frames = 0, differ = 0, some = 0, occluders = 0, tris = 0, clusters = 0;
    for (int run = 0; run < 3; run++) { /* one thread; two by slices; two by tiles */
        double th = 0.3, el = 0.4, dist = 3;
        for (int view = 0; view < 60; view++) {
            if (view % 15 == 14) { /* a jump */
                th = gen_rnd(&seed, 0, 2 * M_PI), el = gen_rnd(&seed, -1.2, 1.2);
                dist = exp(gen_rnd(&seed, log(1.5), log(20)));
            } else { /* a step */
                th += gen_rnd(&seed, -0.08, 0.12), el += gen_rnd(&seed, -0.05, 0.05);
                dist *= gen_rnd(&seed, 0.95, 1.06);
            }
            struct camera cam;
            camera_default(&cam);
            cam.eye = v3(dist * cos(el) * cos(th), dist * sin(el), dist * cos(el) * sin(th));
            const bool face_on = view % 5 == 4 || view % 5 == 0; /* (two in a row: the card's
                                                                   own triangles occlude) */
            if (face_on) {
                cam.eye = v3(0.1 * (view % 3), 0, 4);
                cam.target = v3(0.1 * (view % 3), 0, 0);
                cam.ortho_height = 3;
            }
            struct draw_item items[3] = {
                {.mesh = &faceted, .model = m4_identity()},
                {.mesh = &smooth,
                 .model = m4_mul(m4_translate(v3(0.4, 0.2, 0.3)),
                                 m4_rotate(v3(1, 2, 3), 3.0 * view))},
                {.mesh = &sq, .model = m4_translate(v3(0, 0, 1.5))}};
            if (view / 20 == 1) { /* (the order swapped for a stretch: each item keeps its
                                     place's occluders, of another mesh: none) */
                struct draw_item tmp = items[0];
                items[0] = items[1], items[1] = tmp;
            }
            struct render_opts o;
            render_opts_default(&o);
            o.shade = modes[view % 4];
            o.threads = run ? 2 : 1;
            o.split = run == 1 ? SPLIT_SLICES : SPLIT_TILES;
            struct frame_stats st = {0}, st_off = {0};
            o.hidden_cull = HIDDEN_CULL_OFF;
            o.cluster_cull = CLUSTER_CULL_OFF;
            REQUIRE(pipeline_draw(q, items, 3, NULL, &cam, &o, &a, &st_off, NULL) == 0);
            o.hidden_cull = HIDDEN_CULL_ON;
            o.cluster_cull = CLUSTER_CULL_ON;
            o.occluders = OCCLUDERS_ALWAYS; /* (in every frame, paying or not) */
            REQUIRE(pipeline_draw(p, items, 3, NULL, &cam, &o, &b, &st, NULL) == 0);
            frames++;
            differ += memcmp(a.rgb, b.rgb, (size_t)a.w * a.h * 3) != 0 ||
                      memcmp(a.depth, b.depth, (size_t)a.w * a.h * sizeof *a.depth) != 0;
            CHECK_EQ_INT(st_off.occluders, 0);
            some += st.tris_occluded + st.clusters_occluded > 0;
            occluders += st.occluders, tris += st.tris_occluded, clusters += st.clusters_occluded;
            CHECK(st.tris_occluded <= st.tris_hidden && st.clusters_occluded <= st.clusters_hidden);
        }
    }
    printf("    %llu frames, %llu differ; %llu with something behind the occluders (%llu "
           "occluders, %llu clusters and %llu triangles behind them in all)\n",
           (unsigned long long)frames, (unsigned long long)differ, (unsigned long long)some,
           (unsigned long long)occluders, (unsigned long long)clusters,
           (unsigned long long)tris);
    CHECK_EQ_INT(differ, 0);
    CHECK(some > frames / 2);
    CHECK(clusters > 0 && tris > 0);
    fb_free(&a);
    fb_free(&b);
    pipeline_destroy(p);
    pipeline_destroy(q);
    mesh_free(&faceted);
    mesh_free(&smooth);
    mesh_free(&sq);
}
