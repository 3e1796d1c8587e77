/* reorder.c: does reordering a mesh for the vertex cache and overdraw pay in rastty?
 * (`make bench`, from tests/bench_lod.sh; numbers, never verdicts.)
 *
 *   build/bench/reorder MODEL... [--frames N]
 *
 * A GPU transforms a vertex again when it has left its small post-transform cache, and shades
 * a pixel again when a nearer triangle comes later; meshoptimizer's reorderings cut both.
 * rastty's vertex stage transforms every vertex once a frame whatever the order, so the
 * question is memory locality and overdraw. Each model is drawn in three triangle orders:
 *   source   as loaded (the file's order)
 *   vcache   meshopt_optimizeVertexCache, then meshopt_optimizeVertexFetch (vertices in order
 *            of first use)
 *   overdraw vcache, then meshopt_optimizeOverdraw (threshold 1.05), then the vertex fetch
 * framed from (2,1,3) as the chart draws it, at 160x96 and 640x480, one thread, phong. The
 * orders take turns, each drawn twice and its second frame timed in CPU time of the thread
 * (less sensitive than wall time to other work on the machine); medians over N rounds, and
 * the pixels shaded (overdraw included) per frame. */
#include <meshoptimizer.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "pipeline.h"
#include "scene.h"
#include "timing.h"

enum { SOURCE, VCACHE, OVERDRAW, N_ORDERS };
static const char *const order_names[N_ORDERS] = {"source", "vcache", "overdraw"};

static double cpu_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}

/* reorder m's triangles (and then its vertices) in place; tri_material follows the corners */
static int reorder(struct mesh *m, int order)
{
    size_t ni = (size_t)m->n_tris * 3;
    unsigned *a = malloc(ni * sizeof *a), *b = malloc(ni * sizeof *b);
    unsigned *remap = malloc((size_t)m->n_verts * sizeof *remap);
    struct mesh_vertex *nv = malloc((size_t)m->n_verts * sizeof *nv);
    uint16_t *nm = malloc((size_t)m->n_verts * sizeof *nm);
    if (!a || !b || !remap || !nv || !nm)
        return -1;
    memcpy(a, m->tris, ni * sizeof *a);
    meshopt_optimizeVertexCache(b, a, ni, m->n_verts);
    if (order == OVERDRAW)
        meshopt_optimizeOverdraw(a, b, ni, m->verts[0].pos, m->n_verts, sizeof *m->verts, 1.05f);
    else
        memcpy(a, b, ni * sizeof *a);
    size_t n = meshopt_optimizeVertexFetchRemap(remap, a, ni, m->n_verts);
    for (uint32_t v = 0; v < m->n_verts; v++)
        if (remap[v] != ~0u) {
            nv[remap[v]] = m->verts[v];
            nm[remap[v]] = m->vert_material[v];
        }
    for (size_t i = 0; i < ni; i++)
        a[i] = remap[a[i]];
    free(m->verts);
    free(m->vert_material);
    m->verts = nv;
    m->vert_material = nm;
    m->n_verts = (uint32_t)n;
    memcpy(m->tris, a, ni * sizeof *a);
    for (uint32_t t = 0; t < m->n_tris; t++)
        m->tri_material[t] = m->vert_material[m->tris[t][0]];
    free(m->colors); /* not drawn */
    m->colors = NULL;
    free(a);
    free(b);
    free(remap);
    return mesh_share_positions(m); /* (mesh.h: after moving vertices) */
}

int main(int argc, char **argv)
{
    int frames = 15;
    for (int i = 1; i + 1 < argc; i++)
        if (strcmp(argv[i], "--frames") == 0)
            frames = atoi(argv[i + 1]);
    if (frames < 1)
        frames = 1;
    printf("-- vertex-cache / overdraw reordering (meshoptimizer): median CPU ms per frame, one "
           "thread, pixels shaded\n");
    printf("  %-16s %-8s", "model", "size");
    for (int o = 0; o < N_ORDERS; o++)
        printf(" %10s %8s", order_names[o], "px");
    printf("\n");
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--frames") == 0) {
            i++;
            continue;
        }
        struct scene s[N_ORDERS];
        struct err e;
        int ok = 1;
        for (int o = 0; o < N_ORDERS && ok; o++) {
            if (scene_load(argv[i], &s[o], &e)) {
                fprintf(stderr, "reorder: %s\n", e.msg);
                return 1;
            }
            for (int k = 0; k < s[o].n_meshes; k++)
                if (o != SOURCE && reorder(&s[o].meshes[k], o))
                    ok = 0;
        }
        if (!ok) {
            fprintf(stderr, "reorder: out of memory\n");
            return 1;
        }
        const char *base = strrchr(argv[i], '/');
        base = base ? base + 1 : argv[i];
        static const int sizes[2][2] = {{160, 96}, {640, 480}};
        for (int z = 0; z < 2; z++) {
            int w = sizes[z][0], h = sizes[z][1];
            struct camera cam;
            camera_default(&cam);
            cam.eye = v3(2, 1, 3);
            camera_frame_box(&cam, s[0].bound_lo, s[0].bound_hi, (double)w / h);
            struct render_opts ro;
            render_opts_default(&ro);
            ro.threads = 1;
            struct fb fb;
            struct pipeline *p = pipeline_new();
            double *ms = calloc((size_t)N_ORDERS * frames, sizeof *ms);
            uint64_t shaded[N_ORDERS] = {0};
            if (!p || !ms || fb_init(&fb, w, h, false, &e))
                return 1;
            for (int r = 0; r < frames; r++)
                for (int o = 0; o < N_ORDERS; o++) {
                    struct frame_stats st;
                    double t0 = 0;
                    for (int rep = 0; rep < 2; rep++) {
                        t0 = cpu_ms();
                        if (pipeline_draw(p, s[o].items, s[o].n_items, NULL, &cam, &ro, &fb, &st,
                                          &e))
                            return 1;
                    }
                    ms[o * frames + r] = cpu_ms() - t0;
                    shaded[o] = st.pixels_shaded;
                }
            printf("  %-16.16s %-8s", base, h == 96 ? "160x96" : "640x480");
            for (int o = 0; o < N_ORDERS; o++)
                printf(" %10.3f %8llu", timing_median(ms + o * frames, frames),
                       (unsigned long long)shaded[o]);
            printf("\n");
            free(ms);
            fb_free(&fb);
            pipeline_destroy(p);
        }
        for (int o = 0; o < N_ORDERS; o++)
            scene_free(&s[o]);
    }
    return 0;
}
