/* frame.c: one frame's constants and the stages every plan shares (see frame.h). */
#include "frame.h"

#include <math.h>
#include <string.h>

#include "dag.h"
#include "light.h"
#include "lod.h"

void frame_init(struct frame *f, const struct camera *cam, const struct render_opts *o,
                const struct kernel_set *ks, struct fb *fb, struct frame_stats *stats)
{
    memset(f, 0, sizeof *f);
    f->o = o;
    f->cam = cam;
    f->ks = ks;
    f->k = ks->by_size[SPAN_SIZE_LARGE];
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
    kernel_choose_span(ks, &f->span);
}

void frame_item(struct frame *f, const struct draw_item *item, mat4 pv)
{
    struct vertex_uniforms *u = &f->u;
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

double frame_item_scale(mat4 m)
{
    double best = 0;
    for (int j = 0; j < 3; j++) {
        double s = sqrt(m.m[0][j] * m.m[0][j] + m.m[1][j] * m.m[1][j] + m.m[2][j] * m.m[2][j]);
        best = s > best ? s : best;
    }
    return best;
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

bool frame_item_outside(const struct draw_item *item, mat4 mvp, double scale, bool counts,
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

const struct mesh *frame_item_level(const struct draw_item *item, const struct camera *cam,
                                    int fb_w, int fb_h, const struct render_opts *o, double scale,
                                    struct frame_stats *stats)
{
    const struct mesh *m = item->mesh;
    int level = 0;
    /* the cluster hierarchy under clusters, and under auto where the mesh has a hierarchy
     * and no chain (the background build makes one or the other: the viewer's L key goes
     * from clusters to auto); not for wireframe: its edges and hidden-line pass read every
     * triangle of the mesh they get. The front end chooses its cut */
    const bool cut = o->lod == LOD_CLUSTERS || (o->lod == LOD_AUTO && lod_level_count(m) == 1);
    const struct mesh_dag *dag = cut && o->shade != SHADE_WIRE && o->view != VIEW_WIRE_OVERLAY
                                     ? dag_of(m)
                                     : NULL;
    if (dag)
        return &dag->mesh;
    if (o->lod != LOD_OFF) {
        vec3 c = m4_mul_point(item->model, v3(m->center[0], m->center[1], m->center[2]));
        double px = lod_pixels_per_unit(cam, fb_h, c, m->radius * scale) * scale;
        double px_c = lod_pixels_per_unit(cam, fb_h, c, 0) * scale; /* (at the centre) */
        level = lod_choose(m, o->lod, o->lod_ratio, o->lod_px, px, lod_share(m, px_c, fb_w, fb_h));
    }
    stats->lod_min = stats->lod_min < 0 || level < stats->lod_min ? level : stats->lod_min;
    stats->lod_max = level > stats->lod_max ? level : stats->lod_max;
    return lod_level(m, level);
}

/* the clear, in bands of 16 rows */
struct clear_job {
    struct fb *fb;
    const uint8_t *bg;
};

static void clear_band(void *arg, size_t y0, size_t y1)
{
    const struct clear_job *j = arg;
    fb_clear_rows(j->fb, j->bg, (int)y0, (int)y1);
}

void frame_clear(struct workers *w, struct fb *fb, const uint8_t bg[3])
{
    struct clear_job j = {fb, bg};
    workers_for(w, (size_t)fb->h, 16, clear_band, &j);
}

/* the vertex stage, in chunks of vertices */
struct vertex_job {
    const struct kernel *k;
    const struct mesh *m;
    const struct vertex_uniforms *u;
    struct vertex_out *out;
};

static void vertex_chunk(void *arg, size_t i0, size_t i1)
{
    const struct vertex_job *j = arg;
    j->k->vertex_run(j->m, j->u, j->out, (uint32_t)i0, (uint32_t)i1);
}

void frame_vertices(struct workers *w, const struct kernel *k, const struct mesh *m,
                    const struct vertex_uniforms *u, struct vertex_out *out)
{
    struct vertex_job j = {k, m, u, out};
    /* chunks of 4096 vertices, smaller for small meshes so that every thread gets some
     * (a chunk is at least 256 vertices: less is not worth a hand-over) */
    size_t threads = (size_t)workers_count(w) + 1;
    size_t per = (m->n_verts + 2 * threads - 1) / (2 * threads);
    size_t chunk = per < 256 ? 256 : per > 4096 ? 4096 : per;
    workers_for(w, m->n_verts, chunk, vertex_chunk, &j);
}

/* the sky, in bands of 8 rows */
struct sky_job {
    const struct kernel *k;
    const struct skybox *sky;
    const struct camera *cam;
    struct fb *fb;
};

static void sky_band(void *arg, size_t y0, size_t y1)
{
    const struct sky_job *j = arg;
    j->k->sky_rows(j->sky, j->cam, j->fb, (int)y0, (int)y1);
}

void frame_sky(struct workers *w, const struct kernel *k, const struct skybox *sky,
               const struct camera *cam, struct fb *fb)
{
    struct sky_job j = {k, sky, cam, fb};
    workers_for(w, (size_t)fb->h, 8, sky_band, &j);
}
