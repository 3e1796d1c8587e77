/* pipeline.c: one frame over a list of draw items (see pipeline.h). */
#include "pipeline.h"

#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "clip.h"
#include "line.h"
#include "raster.h"
#include "setup.h"
#include "shade.h"
#include "vertex.h"

struct pipeline {
    struct vertex_out *verts; /* vertex-stage output, reused across frames */
    uint32_t cap;
};

struct pipeline *pipeline_new(void)
{
    return calloc(1, sizeof(struct pipeline));
}

void pipeline_destroy(struct pipeline *p)
{
    if (p)
        free(p->verts);
    free(p);
}

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
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

static void draw_setup(const struct vertex_out *a, const struct vertex_out *b,
                       const struct vertex_out *c, int n_var, enum shade_mode mode,
                       const struct render_opts *o, const struct shade_ctx *sc,
                       const struct shade_tri *st, struct fb *fb, struct frame_stats *stats)
{
    struct setup_tri t;
    /* the depth pre-pass of hidden-line wireframe draws every face, whatever the culling */
    enum cull_mode cull = mode == SHADE_WIRE ? CULL_NONE : o->cull;
    switch (setup_triangle(a, b, c, fb->w, fb->h, cull, n_var, &t)) {
    case SETUP_DRAW:
        stats->tris_drawn++;
        raster_triangle(&t, sc, st, fb, stats);
        break;
    case SETUP_CULLED:
        stats->tris_culled++;
        break;
    default:
        break;
    }
}

/* Filled triangles of one item; mode SHADE_WIRE = depth only. */
static void draw_filled(const struct mesh *m, const struct vertex_out *vo,
                        const struct vertex_uniforms *u, const struct draw_item *item,
                        enum shade_mode mode, int n_var, const struct render_opts *o,
                        const struct shade_ctx *sc, struct fb *fb, struct frame_stats *stats)
{
    struct vertex_out poly[CLIP_MAX_VERTS];
    for (uint32_t i = 0; i < m->n_tris; i++) {
        const struct vertex_out *v[3] = {&vo[m->tris[i][0]], &vo[m->tris[i][1]],
                                         &vo[m->tris[i][2]]};
        uint32_t all = v[0]->outcode & v[1]->outcode & v[2]->outcode;
        uint32_t any = v[0]->outcode | v[1]->outcode | v[2]->outcode;
        stats->tris_in++;
        if ((all & VERTEX_OUT_FRUSTUM) || (any & VERTEX_INVALID)) {
            stats->tris_rejected++;
            continue;
        }
        struct shade_tri st;
        st.mat = &m->materials[m->tri_material[i]];
        st.tex = NULL;
        if (o->textures)
            st.tex = item->texture_override ? item->texture_override
                     : st.mat->texture >= 0 ? &m->textures[st.mat->texture]
                                            : NULL;
        light_base_color(st.mat, item->kd_override, st.tex != NULL, st.base);
        if (mode == SHADE_FLAT)
            flat_terms(u, v[0], v[1], v[2], st.mat->ns, &st);
        if (!(any & VERTEX_NEEDS_CLIP)) {
            draw_setup(v[0], v[1], v[2], n_var, mode, o, sc, &st, fb, stats);
            continue;
        }
        stats->tris_clipped++;
        int n = clip_triangle(v, any & VERTEX_NEEDS_CLIP, n_var, u->guard_x, u->guard_y, poly);
        for (int k = 1; k + 1 < n; k++)
            draw_setup(&poly[0], &poly[k], &poly[k + 1], n_var, mode, o, sc, &st, fb, stats);
    }
}

/* Sign of the triangle's screen-space orientation from clip coordinates, valid even when a
 * corner is behind the eye: det[x y w] has the sign of the window-space area times w0 w1 w2. */
static int front_facing_clip(const double *a, const double *b, const double *c)
{
    double det = a[0] * (b[1] * c[3] - c[1] * b[3]) - b[0] * (a[1] * c[3] - c[1] * a[3]) +
                 c[0] * (a[1] * b[3] - b[1] * a[3]);
    return det > 0; /* counter-clockwise in GL window coordinates */
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
        if (o->cull != CULL_NONE) {
            int front = front_facing_clip(v[0]->clip, v[1]->clip, v[2]->clip);
            if ((o->cull == CULL_BACK && !front) || (o->cull == CULL_FRONT && front)) {
                stats->tris_culled += !overlay;
                continue;
            }
        }
        for (int k = 0; k < 3; k++)
            line_draw_clip(fb, v[k]->clip, v[(k + 1) % 3]->clip, o->wire_color, depth_test);
        stats->tris_drawn += !overlay;
    }
}

/* grow the vertex-output scratch to n (kept across frames) */
static int reserve(struct pipeline *p, uint32_t n, struct err *e)
{
    if (n <= p->cap)
        return 0;
    struct vertex_out *nv = realloc(p->verts, (size_t)n * sizeof *nv);
    if (!nv)
        return err_set(e, "out of memory for %u vertices", n);
    p->verts = nv;
    p->cap = n;
    return 0;
}

int pipeline_draw(struct pipeline *p, const struct draw_item *items, int n_items,
                  const struct skybox *sky, const struct camera *cam,
                  const struct render_opts *o, struct fb *fb, struct frame_stats *stats,
                  struct err *e)
{
    double t0 = now_ms();
    memset(stats, 0, sizeof *stats);
    fb_clear(fb, o->background);
    double aspect = (double)fb->w / fb->h;
    mat4 view = camera_view(cam), proj = camera_proj(cam, aspect);
    mat4 pv = m4_mul(proj, view);

    struct vertex_uniforms u;
    memset(&u, 0, sizeof u);
    u.eye = cam->eye;
    u.ortho = cam->ortho_height > 0;
    u.view_back = camera_back(cam);
    u.fb_w = fb->w;
    u.fb_h = fb->h;
    u.guard_x = 1.0 + 2.0 * VERTEX_GUARD_PX / fb->w;
    u.guard_y = 1.0 + 2.0 * VERTEX_GUARD_PX / fb->h;
    u.shade = o->shade;
    u.view = o->view;
    light_env_init(&u.lights, o);
    float eye[3] = {(float)cam->eye.x, (float)cam->eye.y, (float)cam->eye.z};
    float back[3] = {(float)u.view_back.x, (float)u.view_back.y, (float)u.view_back.z};
    struct shade_ctx sc;
    shade_ctx_init(&sc, o, eye, u.ortho, back);
    enum shade_mode mode = o->view == VIEW_NORMALS ? SHADE_PHONG : o->shade;
    int n_var = vertex_varying_count(o->shade, o->view);

    bool show_sky = sky && (o->view == VIEW_COLOR || o->view == VIEW_WIRE_OVERLAY);
    bool wire = mode == SHADE_WIRE;
    /* wire frames have no surface colour: the sky goes everywhere, before anything else */
    if (show_sky && wire)
        skybox_draw(sky, cam, fb);
    /* pass 1: surfaces (wire: depth only, for hidden lines); pass 2: edges, depth-tested
     * against every item's surfaces when asked. Each pass transforms an item's vertices
     * itself (cheap next to drawing), so no pass keeps more than one item's vertices. */
    bool pass1 = !wire || o->hidden_lines;
    bool pass2 = wire || o->view == VIEW_WIRE_OVERLAY;
    for (int pass = 1; pass <= 2; pass++) {
        if ((pass == 1 && !pass1) || (pass == 2 && !pass2))
            continue;
        if (pass == 2 && show_sky && !wire) /* the sky goes where pass 1 drew nothing */
            skybox_draw(sky, cam, fb);
        /* a culled item is counted once: by the first pass that looks at it */
        bool counts = pass == 1 || !pass1;
        for (int it = 0; it < n_items; it++) {
            const struct draw_item *item = &items[it];
            const struct mesh *m = item->mesh;
            if (m->n_tris == 0)
                continue;
            u.model = item->model;
            u.normal_matrix = m4_normal_matrix(item->model);
            u.mvp = m4_mul(pv, item->model);
            if (sphere_outside(m, u.mvp, max_scale(item->model))) {
                if (counts) {
                    stats->meshes_culled++;
                    stats->tris_in += m->n_tris;
                    stats->tris_culled += m->n_tris;
                }
                continue;
            }
            if (reserve(p, m->n_verts, e))
                return -1;
            vertex_run(m, &u, p->verts);
            if (pass == 2) {
                draw_edges(m, p->verts, o, !wire || o->hidden_lines, !wire, fb, stats);
            } else if (wire) { /* depth-only pre-pass; its counts are not the frame's */
                struct frame_stats pre = {0};
                draw_filled(m, p->verts, &u, item, SHADE_WIRE, 0, o, &sc, fb, &pre);
            } else {
                draw_filled(m, p->verts, &u, item, mode, n_var, o, &sc, fb, stats);
            }
        }
    }
    if (show_sky && !wire && !pass2) /* the sky goes where the surfaces left room */
        skybox_draw(sky, cam, fb);
    if (o->view == VIEW_DEPTH)
        fb_show_depth(fb);
    else if (o->view == VIEW_OVERDRAW)
        fb_show_overdraw(fb);
    stats->render_ms = now_ms() - t0;
    return 0;
}
