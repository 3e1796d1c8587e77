/* test_vertex.c: the vertex stage's lighting, several vertices at a time (vertex_shade_many:
 * a vertex per SIMD lane) against one at a time (vertex_shade) — every byte of every vertex
 * record the same, in every mode it batches, on every instruction set the machine has. */
#include <stdlib.h>
#include <string.h>

#include "light.h"
#include "span.h"
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
    const char *isas[] = {"sse2", "avx2"};
    static struct vertex_out one[N_VERTS], many[N_VERTS];
    struct vertex_out *outs[N_VERTS];
    uint32_t idx[N_VERTS];
    for (int is = 0; is < 2; is++) {
        if (span_isa_set(isas[is]))
            continue; /* (no AVX2 here) */
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
            vertex_shade_many(&m, &u, idx, outs, N_VERTS);
            int differ = 0;
            for (int i = 0; i < N_VERTS; i++)
                differ += memcmp(&one[i], &many[i], sizeof one[i]) != 0;
            if (differ)
                test_fail(t, __FILE__, __LINE__, "%s, case %zu: %d of %d vertices differ",
                          isas[is], c, differ, N_VERTS);
            /* the lighting reached the records (not all zero) */
            CHECK(one[3].shaded == 1 && one[3].var[0] == verts[3].uv[0]);
        }
    }
    span_isa_set("auto");
}
