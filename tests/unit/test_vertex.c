/* test_vertex.c: the vertex stage in every kernel (kernel.h) against one vertex at a time:
 * the lighting, several vertices at a time (vertex_shade_many: a vertex per SIMD lane)
 * against vertex_shade, and the positions (vertex_run, position_run) against vertex.h's one
 * at a time — every byte of every vertex record the same, in every mode, on every
 * instruction set the machine has. */
#include <stdlib.h>
#include <string.h>

#include "kernel.h"
#include "light.h"
#include "test.h"
#include "vertex.h"

#define N_VERTS 45 /* five groups of eight and a few left over */

static float rnd(uint32_t *s)
{
    *s = *s * 1664525u + 1013904223u;
    return (float)(*s >> 8) / (float)(1u << 24) * 2.0f - 1.0f;
}

TEST(vertex_shade_many_is_vertex_shade)
{
    struct mesh_vertex verts[N_VERTS];
    uint16_t vmat[N_VERTS];
    struct material mats[2];
    memset(mats, 0, sizeof mats);
    mats[0].ns = 32, mats[1].ns = 10;
    uint32_t seed = 7;
    for (int i = 0; i < N_VERTS; i++) {
        for (int c = 0; c < 3; c++)
            verts[i].pos[c] = rnd(&seed), verts[i].nrm[c] = rnd(&seed);
        verts[i].uv[0] = rnd(&seed), verts[i].uv[1] = rnd(&seed);
        vmat[i] = i >= 20 && i % 3 == 0; /* groups of one Ns, then mixed ones */
    }
    struct mesh m;
    memset(&m, 0, sizeof m);
    m.verts = verts, m.n_verts = N_VERTS, m.materials = mats, m.n_materials = 2;
    m.vert_material = vmat;

    struct vertex_uniforms u;
    memset(&u, 0, sizeof u);
    const float model[3][4] = {{0.8f, -0.3f, 0.1f, 0.2f}, {0.25f, 0.9f, -0.2f, -0.1f},
                               {-0.1f, 0.3f, 1.1f, 0.05f}};
    const float normal[3][3] = {{1.1f, 0.2f, -0.3f}, {-0.2f, 0.95f, 0.1f}, {0.3f, -0.1f, 0.9f}};
    memcpy(u.model_f, model, sizeof model);
    memcpy(u.normal_f, normal, sizeof normal);
    u.eye = v3(0.3, 0.5, 3);
    u.view_back = v3_norm(v3(0.1, 0.2, 1));
    struct render_opts ro;
    render_opts_default(&ro);

    static const struct {
        enum shade_mode shade;
        enum debug_view view;
        int ortho, n_lights;
    } cases[] = {{SHADE_GOURAUD, VIEW_COLOR, 0, 1}, {SHADE_GOURAUD, VIEW_COLOR, 0, 2},
                 {SHADE_GOURAUD, VIEW_COLOR, 1, 1}, {SHADE_PHONG, VIEW_COLOR, 0, 1},
                 {SHADE_UNLIT, VIEW_NORMALS, 0, 1}, {SHADE_FLAT, VIEW_COLOR, 0, 1}};
    static const enum kernel_isa isas[] = {KERNEL_REF, KERNEL_SSE2, KERNEL_AVX2_8, KERNEL_AVX2_4};
    int kernels = 0;
    static struct vertex_out one[N_VERTS], many[N_VERTS];
    struct vertex_out *outs[N_VERTS];
    uint32_t idx[N_VERTS];
    for (int is = 0; is < 4; is++) {
        if (!kernel_set(isas[is]))
            continue; /* (no AVX2 here) */
        const struct kernel *k = kernel_set(isas[is])->by_size[SPAN_SIZE_LARGE];
        kernels++;
        for (size_t c = 0; c < sizeof cases / sizeof *cases; c++) {
            u.shade = cases[c].shade, u.view = cases[c].view, u.ortho = cases[c].ortho;
            ro.n_lights = cases[c].n_lights;
            ro.lights[1].dir = v3(-1, 0.5, 1);
            ro.lights[1].color = v3(0.3, 0.2, 0.6); /* not grey */
            light_env_init(&u.lights, &ro);
            CHECK(u.lights.grey == (cases[c].n_lights == 1));
            memset(one, 0, sizeof one);
            memset(many, 0, sizeof many);
            for (int i = 0; i < N_VERTS; i++) {
                vertex_shade(&m, &u, (uint32_t)i, &one[i]);
                idx[i] = (uint32_t)(N_VERTS - 1 - i); /* any order */
                outs[i] = &many[idx[i]];
            }
            k->vertex_shade_many(&m, &u, idx, outs, N_VERTS);
            int differ = 0;
            for (int i = 0; i < N_VERTS; i++)
                differ += memcmp(&one[i], &many[i], sizeof one[i]) != 0;
            if (differ)
                test_fail(t, __FILE__, __LINE__, "%s, case %zu: %d of %d vertices differ",
                          k->name, c, differ, N_VERTS);
            /* the lighting reached the records (not all zero) */
            CHECK(one[3].shaded == VERTEX_SHADED && one[3].var[0] == verts[3].uv[0]);
        }
    }
    CHECK(kernels >= 2);
}

TEST(vertex_run_is_the_reference)
{
    /* positions, outcodes and snapped window positions of vertices in and around the view
     * (inside, beyond the guard band, behind the eye, through the near plane) by every
     * kernel against the reference kernel's: the same bytes */
    enum { N = 61 };
    struct mesh_vertex verts[N];
    uint32_t seed = 11;
    for (int i = 0; i < N; i++)
        for (int c = 0; c < 3; c++)
            verts[i].pos[c] = rnd(&seed) * (i % 7 == 0 ? 400.0f : 3.0f);
    verts[5].pos[1] = NAN, verts[13].pos[0] = INFINITY; /* (not finite: invalid) */
    verts[22].pos[0] = 0.2f, verts[22].pos[1] = 0.4f, verts[22].pos[2] = 1.5f; /* (w 0) */
    struct mesh m;
    memset(&m, 0, sizeof m);
    m.verts = verts, m.n_verts = N;
    struct vertex_uniforms u;
    memset(&u, 0, sizeof u);
    struct camera cam;
    camera_default(&cam);
    cam.eye = v3(0.2, 0.4, 1.5);
    u.fb_w = 160, u.fb_h = 96;
    u.mvp = m4_mul(camera_proj(&cam, 160.0 / 96), camera_view(&cam));
    u.guard_x = 1.0 + 2.0 * VERTEX_GUARD_PX / u.fb_w;
    u.guard_y = 1.0 + 2.0 * VERTEX_GUARD_PX / u.fb_h;
    static struct vertex_out ref[N], out[N];
    /* the reference: vertex.h's functions one vertex at a time (the kernels run four at a
     * time, a lane each) */
    memset(ref, 0, sizeof ref);
    for (int i = 0; i < N; i++) {
        const float *p = verts[i].pos;
        vec4 c = m4_mul_v4(u.mvp, (vec4){p[0], p[1], p[2], 1});
        ref[i].clip[0] = c.x, ref[i].clip[1] = c.y, ref[i].clip[2] = c.z, ref[i].clip[3] = c.w;
        ref[i].outcode = vertex_outcode(ref[i].clip, u.guard_x, u.guard_y);
        ref[i].shaded = VERTEX_UNSHADED;
        if (!(ref[i].outcode & VERTEX_NEEDS_CLIP))
            vertex_project(&ref[i], u.fb_w, u.fb_h);
    }
    int clipped = 0, projected = 0, invalid = 0;
    for (int i = 0; i < N; i++)
        clipped += (ref[i].outcode & VERTEX_NEEDS_CLIP) != 0, projected += ref[i].projected,
            invalid += (ref[i].outcode & VERTEX_INVALID) != 0;
    CHECK(clipped > 5 && projected > 20);
    CHECK_EQ_INT(invalid, 2);
    static const enum kernel_isa isas[] = {KERNEL_REF, KERNEL_SSE2, KERNEL_AVX2_8, KERNEL_AVX2_4};
    for (int is = 0; is < 4; is++) {
        if (!kernel_set(isas[is]))
            continue;
        memset(out, 0, sizeof out);
        kernel_set(isas[is])->by_size[SPAN_SIZE_LARGE]->vertex_run(&m, &u, out, 0, 30);
        static const struct vertex_out untouched; /* (a run writes its own records alone) */
        CHECK(memcmp(&out[30], &untouched, sizeof untouched) == 0);
        kernel_set(isas[is])->by_size[SPAN_SIZE_LARGE]->vertex_run(&m, &u, out, 30, N);
        CHECK(memcmp(ref, out, sizeof ref) == 0);
        /* the same positions alone (the walk by position's share of each record) */
        float xyz[N][3];
        struct vertex_pos pos[N], want[N];
        memset(want, 0, sizeof want);
        for (int i = 0; i < N; i++) {
            memcpy(xyz[i], verts[i].pos, sizeof xyz[i]);
            want[i].outcode = ref[i].outcode;
            if (ref[i].projected) {
                double win[3];
                viewport_window(ref[i].clip, u.fb_w, u.fb_h, win);
                want[i].fx = ref[i].fx, want[i].fy = ref[i].fy, want[i].z = (float)win[2];
            }
        }
        const struct kernel *kk = kernel_set(isas[is])->by_size[SPAN_SIZE_LARGE];
        memset(pos, 0xff, sizeof pos);
        kk->position_run(xyz[0], sizeof xyz[0], &u, pos, 0, 29);
        CHECK(pos[29].outcode == 0xffffffffu && pos[30].outcode == 0xffffffffu);
        kk->position_run(xyz[0], sizeof xyz[0], &u, pos, 29, N);
        CHECK(memcmp(want, pos, sizeof want) == 0);
        /* the vertices' positions in place (the walk by vertex heads), the same */
        memset(pos, 0xff, sizeof pos);
        kk->position_run(verts[0].pos, sizeof verts[0], &u, pos, 0, 7);
        kk->position_run(verts[0].pos, sizeof verts[0], &u, pos, 7, N);
        CHECK(memcmp(want, pos, sizeof want) == 0);
    }
}
