/* test_clusters.c: clusters (scene/cluster.h) and their culling (render/cluster_cull.h) —
 * every cluster's box holds its triangles' corners and its cone their normals, its vertex
 * reach (v_need, v_end) is exact, and a frame drawn with --cluster-cull on is the same bytes as
 * with it off, from hundreds of random views (inside the model, crossing the near plane,
 * partly off screen, sub-pixel far away, orthographic, mirrored and stretched), every
 * culling mode, both thread splits, with coplanar duplicate triangles whose order decides
 * ties of depth; while clusters are dropped for every reason. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cluster.h"
#include "gen_mesh.h"
#include "pipeline.h"
#include "test.h"

/* a displaced sphere grid (rows x 2 rows, radius ~1), then its first `dup` triangles again
 * with material 1 (the same positions: every pixel they cover is a tie of depth, which the
 * file's order decides); material 0 red, 1 green and one-sided (glTF's rule under --cull
 * auto: the mesh is MESH_SIDES_SOME) */
static int bumpy(struct mesh *m, int rows, int dup)
{
    if (gen_bumpy_sphere(m, rows, dup, 0, 180))
        return -1;
    m->materials = calloc(2, sizeof *m->materials);
    if (!m->materials)
        return -1;
    m->n_materials = 2;
    for (int i = 0; i < 2; i++) {
        m->materials[i].kd[i] = 1;
        m->materials[i].ks[0] = m->materials[i].ks[1] = m->materials[i].ks[2] = 0.5f;
        m->materials[i].ns = 32;
        m->materials[i].texture = -1;
    }
    m->materials[1].sides = MAT_ONE_SIDED;
    m->one_sided = MESH_SIDES_SOME;
    return 0;
}

/* is p inside cluster c's box (exactly, in double)? */
static bool in_box(const struct mesh_cluster *c, const float *p)
{
    double d[3] = {(double)p[0] - c->center[0], (double)p[1] - c->center[1],
                   (double)p[2] - c->center[2]};
    /* the axes are orthonormal to float rounding: coordinates by dot products, with the
     * slack half[] was widened by */
    for (int a = 0; a < 3; a++) {
        double s = d[0] * c->axis[a][0] + d[1] * c->axis[a][1] + d[2] * c->axis[a][2];
        if (fabs(s) > (double)c->half[a] * (1 + 1e-5) + 1e-6)
            return false;
    }
    return true;
}

TEST(clusters_hold_their_triangles_and_the_vertices_they_need)
{
    struct mesh m;
    REQUIRE(bumpy(&m, 40, 300) == 0);
    REQUIRE(cluster_build(&m) == 0);
    const struct mesh_clusters *cs = m.clusters;
    REQUIRE(cs && cs->n == (m.n_opaque + CLUSTER_MAX_TRIS - 1) / CLUSTER_MAX_TRIS);
    CHECK(cluster_bytes(&m) < (size_t)m.n_tris * 2); /* (a sixth of the index buffer) */
    uint32_t seen = 0, cones = 0, skips = 0;
    for (uint32_t k = 0; k < cs->n; k++) {
        const struct mesh_cluster *c = &cs->c[k];
        CHECK_EQ_INT(c->tri_first, seen); /* runs of the file's triangles, in order */
        seen += c->n_tris;
        /* every vertex of this cluster and every later one lies at v_need or above, this
         * one's below v_end, and v_need is the least such (the front end skips below it) */
        uint32_t lo = UINT32_MAX, hi = 0;
        for (uint32_t ti = c->tri_first; ti < m.n_opaque; ti++)
            for (int j = 0; j < 3; j++) {
                lo = m.tris[ti][j] < lo ? m.tris[ti][j] : lo;
                if (ti < c->tri_first + c->n_tris)
                    hi = m.tris[ti][j] + 1 > hi ? m.tris[ti][j] + 1 : hi;
            }
        CHECK_EQ_INT(c->v_need, lo);
        CHECK_EQ_INT(c->v_end, hi);
        skips += k && c->v_need > cs->c[k - 1].v_need;
        bool box_ok = true, cone_ok = true;
        for (uint32_t ti = c->tri_first; ti < c->tri_first + c->n_tris; ti++) {
            for (int j = 0; j < 3; j++)
                box_ok &= in_box(c, m.verts[m.tris[ti][j]].pos);
            if (!(c->flags & CLUSTER_NO_CONE)) {
                const float *p0 = m.verts[m.tris[ti][0]].pos, *p1 = m.verts[m.tris[ti][1]].pos,
                            *p2 = m.verts[m.tris[ti][2]].pos;
                vec3 n = v3_norm(v3_cross(v3(p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]),
                                          v3(p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2])));
                cone_ok &= v3_dot(n, v3(c->cone_axis[0], c->cone_axis[1], c->cone_axis[2])) >=
                           c->cone_cos - 1e-6;
            }
        }
        cones += !(c->flags & CLUSTER_NO_CONE);
        CHECK(box_ok);
        CHECK(cone_ok);
    }
    CHECK_EQ_INT(seen, m.n_opaque);
    CHECK(cones > cs->n / 2);
    CHECK(skips > cs->n / 4); /* (a grid's rows: most clusters leave vertices behind) */
    mesh_free(&m);
}

TEST(mirrored_tangents_drop_the_clusters_they_make_stale)
{
    /* uvs mirrored across x = 0 (u = |x|): the triangles there disagree on handedness, and
     * mesh_tangents splits their vertices into twins, renumbering triangles' corners: the
     * clusters' vertex reach (v_need, v_end) would be stale, so they go */
    struct mesh m;
    REQUIRE(bumpy(&m, 20, 0) == 0);
    for (uint32_t v = 0; v < m.n_verts; v++)
        m.verts[v].uv[0] = fabsf(m.verts[v].pos[0]), m.verts[v].uv[1] = m.verts[v].pos[1];
    m.has_uvs = true;
    REQUIRE(cluster_build(&m) == 0 && m.clusters);
    const uint32_t nv = m.n_verts;
    REQUIRE(mesh_tangents(&m, false) == 0);
    CHECK(m.n_verts > nv); /* (twins made) */
    CHECK(m.clusters == NULL);
    mesh_free(&m);
}

TEST(cluster_culling_draws_the_same_bytes_from_every_view)
{
    struct mesh m;
    REQUIRE(bumpy(&m, 48, 2000) == 0);
    REQUIRE(cluster_build(&m) == 0);
    struct pipeline *p = pipeline_new();
    REQUIRE(p);
    struct fb a, b;
    REQUIRE(fb_init(&a, 80, 48, false, NULL) == 0 && fb_init(&b, 80, 48, false, NULL) == 0);
    unsigned seed = 24;
    uint64_t why[4] = {0, 0, 0, 0}, differ = 0, cases = 0, drawn = 0;
    for (int view = 0; view < 160; view++) {
        struct camera cam;
        camera_default(&cam);
        /* near (inside the bumps, through the near plane) to far (sub-pixel) */
        double dist = view % 5 == 0 ? gen_rnd(&seed, 0.6, 1.3) : exp(gen_rnd(&seed, log(1.5), log(300)));
        double th = gen_rnd(&seed, 0, 2 * M_PI), el = gen_rnd(&seed, -1.4, 1.4);
        cam.eye = v3(dist * cos(el) * cos(th), dist * sin(el), dist * cos(el) * sin(th));
        /* aimed off the centre: partly off screen */
        cam.target = v3(gen_rnd(&seed, -1.2, 1.2), gen_rnd(&seed, -1.2, 1.2), gen_rnd(&seed, -1.2, 1.2));
        cam.fov_deg = gen_rnd(&seed, 10, 90);
        cam.near = view % 7 == 0 ? gen_rnd(&seed, 0.2, 2) : 0.05;
        cam.far = view % 11 == 0 ? dist : 1000;
        if (view % 9 == 0)
            cam.ortho_height = gen_rnd(&seed, 0.05, 4);
        struct draw_item item = {.mesh = &m, .model = m4_identity()};
        if (view % 4 == 1) /* mirrored: every winding turns */
            item.model = m4_scale(v3(-1, 1, 1));
        if (view % 4 == 2) /* stretched and turned */
            item.model = m4_mul(m4_rotate(v3(1, 2, 3), gen_rnd(&seed, 0, 360)),
                                m4_scale(v3(1, 0.3, 2)));
        for (int cull = 0; cull < CULL_COUNT; cull++)
            for (int split = SPLIT_TILES; split <= SPLIT_SLICES; split++) {
                struct render_opts o;
                render_opts_default(&o);
                o.cull = (enum cull_mode)cull;
                o.split = (enum thread_split)split;
                o.threads = 2;
                o.shade = view % 3 == 0 ? SHADE_FLAT : SHADE_PHONG;
                /* (which triangles --hidden-cull drops depends on when batches go out,
                 * and so on the clusters dropped before: off, the account below holds) */
                o.hidden_cull = HIDDEN_CULL_OFF;
                struct frame_stats st = {0}, st_off = {0};
                o.cluster_cull = CLUSTER_CULL_OFF;
                REQUIRE(pipeline_draw(p, &item, 1, NULL, &cam, &o, &a, &st_off, NULL) == 0);
                o.cluster_cull = CLUSTER_CULL_ON;
                REQUIRE(pipeline_draw(p, &item, 1, NULL, &cam, &o, &b, &st, NULL) == 0);
                cases++;
                differ += memcmp(a.rgb, b.rgb, (size_t)a.w * a.h * 3) != 0 ||
                          memcmp(a.depth, b.depth, (size_t)a.w * a.h * sizeof *a.depth) != 0;
                why[1] += st.clusters_frustum, why[2] += st.clusters_facing;
                why[3] += st.clusters_no_centre;
                drawn += st.pixels_shaded > 0;
                /* the triangles' account adds up either way */
                CHECK_EQ_INT(st.tris_in, st_off.tris_in);
                CHECK_EQ_INT(st.tris_drawn, st_off.tris_drawn);
                CHECK_EQ_INT(st.clusters_hidden, 0);
                CHECK_EQ_INT(st.clusters_tested, st.clusters_frustum + st.clusters_facing +
                                                     st.clusters_no_centre + st.clusters_drawn);
            }
    }
    CHECK_EQ_INT(differ, 0);
    CHECK(cases == 160 * CULL_COUNT * 2);
    CHECK(drawn > cases / 2); /* (most views see the model) */
    CHECK(why[1] > 0 && why[2] > 0 && why[3] > 0); /* every reason dropped clusters */
    pipeline_destroy(p);
    fb_free(&a);
    fb_free(&b);
    mesh_free(&m);
}

/* The front end's filter (frontend.c: its box question in 32 bits, many at a time) drops
 * only triangles that hold no pixel centre: a grid of half-pixel cells whose corners sit on
 * pixel centres and between them, seen orthographically (8 px a unit, the grid's corners
 * exactly on the snapping grid), covers every pixel centre in its rectangle, whichever
 * triangle owns it by the tie rule — at every offset of the grid, both diagonals, with
 * clusters on and off. Every pixel drawn is counted: a centre a dropped triangle owned is
 * left black. */
TEST(filter_keeps_every_triangle_that_owns_a_pixel_centre)
{
    enum { G = 40 };                 /* cells a side: 20 px */
    const double cell = 1.0 / 16.0; /* half a pixel */
    struct fb fb;
    REQUIRE(fb_init(&fb, 80, 48, false, NULL) == 0);
    struct pipeline *p = pipeline_new();
    REQUIRE(p);
    int frames = 0, bad = 0;
    for (int diag = 0; diag < 2; diag++)
        for (int off = 0; off < 8; off++) { /* offsets in quarter pixels, both axes */
            float pos[(G + 1) * (G + 1) * 3];
            struct mesh_corner c[G * G * 6];
            for (int y = 0; y <= G; y++)
                for (int x = 0; x <= G; x++) {
                    float *q = &pos[3 * (y * (G + 1) + x)];
                    q[0] = (float)((x - G / 2) * cell + off / 32.0);
                    q[1] = (float)((y - G / 2) * cell + (off * 3 % 8) / 32.0);
                    q[2] = 0;
                }
            for (int k = 0; k < G * G; k++) {
                uint32_t x = (uint32_t)(k % G), y = (uint32_t)(k / G), W = G + 1;
                uint32_t P[4] = {y * W + x, y * W + x + 1, (y + 1) * W + x + 1, (y + 1) * W + x};
                static const int o[2][6] = {{0, 1, 2, 0, 2, 3}, {0, 1, 3, 1, 2, 3}};
                for (int j = 0; j < 6; j++)
                    c[6 * k + j] = (struct mesh_corner){P[o[diag][j]], MESH_NONE, MESH_NONE};
            }
            struct mesh_source src = {.pos = pos, .n_pos = (G + 1) * (G + 1), .corners = c,
                                      .n_tris = 2 * G * G};
            struct mesh m;
            memset(&m, 0, sizeof m);
            REQUIRE(mesh_build(&src, &m, NULL) == 0);
            m.materials = calloc(1, sizeof *m.materials);
            REQUIRE(m.materials);
            m.n_materials = 1;
            m.materials[0].kd[0] = m.materials[0].kd[1] = m.materials[0].kd[2] = 1;
            m.materials[0].texture = -1;
            REQUIRE(cluster_build(&m) == 0);
            struct draw_item it = {.mesh = &m, .model = m4_identity()};
            struct camera cam;
            camera_default(&cam);
            cam.ortho_height = 6; /* 48 px: 8 a unit */
            for (int cl = 0; cl < 2; cl++) {
                struct render_opts o;
                render_opts_default(&o);
                o.shade = SHADE_UNLIT;
                o.cluster_cull = cl ? CLUSTER_CULL_ON : CLUSTER_CULL_OFF;
                struct frame_stats st;
                REQUIRE(pipeline_draw(p, &it, 1, NULL, &cam, &o, &fb, &st, NULL) == 0);
                frames++;
                /* the pixel centres inside the grid's rectangle, strictly */
                const double x0 = 40 + 8 * (-G / 2 * cell + off / 32.0);
                const double y0 = 24 - 8 * (G / 2 * cell + (off * 3 % 8) / 32.0);
                int missing = 0, inside = 0;
                for (int py = 0; py < fb.h; py++)
                    for (int px = 0; px < fb.w; px++) {
                        const double cx = px + 0.5, cy = py + 0.5;
                        if (cx <= x0 || cx >= x0 + G / 2 || cy <= y0 || cy >= y0 + G / 2)
                            continue;
                        inside++;
                        const uint8_t *rgb = &fb.rgb[3 * (py * fb.w + px)];
                        missing += rgb[0] + rgb[1] + rgb[2] == 0;
                    }
                CHECK(inside >= 18 * 18);
                bad += missing > 0;
                CHECK_EQ_INT(missing, 0);
                CHECK(st.tris_no_centre > st.tris_drawn); /* (most cells hold none) */
            }
            mesh_free(&m);
        }
    printf("    %d frames, %d with a pixel centre missing\n", frames, bad);
    pipeline_destroy(p);
    fb_free(&fb);
}
