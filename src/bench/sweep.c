/* sweep.c: stress sweeps — where each method fails (see sweep.h). Every scene is built here
 * in memory, so a sweep needs no files; every exact answer is computed here from the scene's
 * definition (ray casts, box integrals, counting), never from the renderer's own numbers. */
#include "sweep.h"

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "mesh.h"
#include "pipeline.h"
#include "psnr.h"
#include "ssaa.h"

/* ---- building scenes ---- */

struct build {
    float *pos, *uv;
    struct mesh_corner *corners;
    uint32_t n_pos, cap_pos, n_tris, cap_tris;
    bool oom;
};

static uint32_t b_vert(struct build *b, double x, double y, double z, double u, double v)
{
    if (b->n_pos == b->cap_pos) {
        uint32_t cap = b->cap_pos ? 2 * b->cap_pos : 256;
        float *np = realloc(b->pos, (size_t)cap * 3 * sizeof *np);
        float *nu = np ? realloc(b->uv, (size_t)cap * 2 * sizeof *nu) : NULL;
        if (np)
            b->pos = np;
        if (!nu) {
            b->oom = true;
            return 0;
        }
        b->uv = nu;
        b->cap_pos = cap;
    }
    float *p = b->pos + 3 * b->n_pos, *t = b->uv + 2 * b->n_pos;
    p[0] = (float)x, p[1] = (float)y, p[2] = (float)z;
    t[0] = (float)u, t[1] = (float)v;
    return b->n_pos++;
}

static void b_tri(struct build *b, uint32_t i, uint32_t j, uint32_t k)
{
    if (b->n_tris == b->cap_tris) {
        uint32_t cap = b->cap_tris ? 2 * b->cap_tris : 256;
        struct mesh_corner *nc = realloc(b->corners, (size_t)cap * 3 * sizeof *nc);
        if (!nc) {
            b->oom = true;
            return;
        }
        b->corners = nc;
        b->cap_tris = cap;
    }
    struct mesh_corner *c = b->corners + 3 * b->n_tris++;
    c[0] = (struct mesh_corner){i, i, MESH_NONE};
    c[1] = (struct mesh_corner){j, j, MESH_NONE};
    c[2] = (struct mesh_corner){k, k, MESH_NONE};
}

/* the mesh, with one material: kd 1 (so an override texture or kd shows as it is) */
static int b_mesh(struct build *b, struct mesh *m, struct err *e)
{
    memset(m, 0, sizeof *m);
    int rc = -1;
    if (b->oom) {
        err_set(e, "out of memory");
    } else {
        struct mesh_source src = {.pos = b->pos, .uv = b->uv, .n_pos = b->n_pos,
                                  .n_uv = b->n_pos, .corners = b->corners,
                                  .n_tris = b->n_tris};
        if (mesh_build(&src, m, e) == 0) {
            if (!(m->materials = calloc(1, sizeof *m->materials))) {
                mesh_free(m);
                err_set(e, "out of memory");
            } else {
                struct material *mt = &m->materials[0];
                snprintf(mt->name, sizeof mt->name, "sweep");
                mt->kd[0] = mt->kd[1] = mt->kd[2] = 1;
                mt->ks[0] = mt->ks[1] = mt->ks[2] = 0.5f;
                mt->ns = 32;
                mt->texture = -1;
                m->n_materials = 1;
                rc = 0;
            }
        }
    }
    free(b->pos);
    free(b->uv);
    free(b->corners);
    memset(b, 0, sizeof *b);
    return rc;
}

/* a draw item of m where it stands (identity model), with the texture tex or the colour kd
 * over its material's (either NULL: not) */
static struct draw_item b_item(const struct mesh *m, const struct texture *tex, const float *kd)
{
    return (struct draw_item){.mesh = m, .model = m4_identity(), .texture_override = tex,
                              .kd_override = kd};
}

/* 256 x 256, red = column, green = row from the bottom: bilinear sampling gives back the
 * texel coordinate (u*256 - 0.5, v*256 - 0.5) as colour */
static int ramp_texture(struct texture *t, struct err *e)
{
    uint8_t *px = malloc(256 * 256 * 4);
    if (!px)
        return err_set(e, "out of memory");
    for (int row = 0; row < 256; row++)
        for (int x = 0; x < 256; x++) {
            uint8_t *p = px + 4 * (row * 256 + x);
            p[0] = (uint8_t)x, p[1] = (uint8_t)(255 - row), p[2] = 128, p[3] = 255;
        }
    int rc = texture_from_rgba(256, 256, px, t, e);
    free(px);
    return rc;
}

/* ---- drawing ---- */

struct rig {
    struct pipeline *p;
    struct fb fb; /* with the overdraw counter */
    struct ssaa ss;
};

static int rig_init(struct rig *r, int w, int h, struct err *e)
{
    memset(r, 0, sizeof *r);
    if (!(r->p = pipeline_new()))
        return err_set(e, "out of memory");
    return fb_init(&r->fb, w, h, true, e);
}

static void rig_free(struct rig *r)
{
    ssaa_free(&r->ss);
    fb_free(&r->fb);
    pipeline_destroy(r->p);
}

static int rig_draw(struct rig *r, const struct draw_item *items, int n,
                    const struct camera *cam, const struct render_opts *o, struct err *e)
{
    struct frame_stats st;
    return ssaa_draw(&r->ss, r->p, items, n, NULL, cam, o, &r->fb, &st, e);
}

/* covered pixels whose stored depth is NaN or infinite */
static long count_nan(const struct fb *fb)
{
    long n = 0;
    for (size_t i = 0; i < (size_t)fb->w * fb->h; i++)
        n += fb_covered(fb, i) && !isfinite(fb->depth[i]);
    return n;
}

/* The ray through the centre of pixel (px, py): direction d with d . forward = 1, so the
 * point eye + t d lies at view depth t. */
struct view_rays {
    vec3 eye, f, r, u;
    double sx, sy; /* tan(fov/2) * aspect, tan(fov/2) */
    int w, h;
};

static void rays_init(struct view_rays *v, const struct camera *c, int w, int h)
{
    v->eye = c->eye;
    v->f = v3_norm(v3_sub(c->target, c->eye));
    v->r = v3_norm(v3_cross(v->f, c->up));
    v->u = v3_cross(v->r, v->f);
    v->sy = tan(c->fov_deg * M_PI / 360);
    v->sx = v->sy * w / h;
    v->w = w, v->h = h;
}

static vec3 ray_dir(const struct view_rays *v, double px, double py)
{
    double x = (2 * px / v->w - 1) * v->sx, y = (1 - 2 * py / v->h) * v->sy;
    return v3_add(v->f, v3_add(v3_scale(v->r, x), v3_scale(v->u, y)));
}

static void finish(struct sweep_result *r)
{
    for (int m = 0; m < r->n_methods; m++) {
        r->fail_at[m] = -1;
        for (int s = 0; s < r->n_steps && r->fail_at[m] < 0; s++)
            if (r->error[s][m] > r->threshold || r->nan[s][m] > 0) /* NAN error: no data */
                r->fail_at[m] = s;
    }
}

/* where the theory column (extra) says method m fails: its first step past the threshold */
static void predict_from_extra(struct sweep_result *r, int m)
{
    r->predicted[m] = NAN;
    for (int s = 0; s < r->n_steps && isnan(r->predicted[m]); s++)
        if (r->extra[s][m] > r->threshold)
            r->predicted[m] = r->param[s];
}

/* pixel coordinates (x right, y down) of a world point; the point must be in front */
static void project(const struct view_rays *v, vec3 p, double *x_out, double *y_out)
{
    vec3 d = v3_sub(p, v->eye);
    double t = v3_dot(d, v->f);
    *x_out = (v3_dot(d, v->r) / t / v->sx + 1) * 0.5 * v->w;
    *y_out = (1 - v3_dot(d, v->u) / t / v->sy) * 0.5 * v->h;
}

/* weights of p in the 2-D triangle a b c */
static void bary2(const double a[2], const double b[2], const double c[2], const double p[2],
                  double l_out[3])
{
    double den = (b[1] - c[1]) * (a[0] - c[0]) + (c[0] - b[0]) * (a[1] - c[1]);
    l_out[0] = ((b[1] - c[1]) * (p[0] - c[0]) + (c[0] - b[0]) * (p[1] - c[1])) / den;
    l_out[1] = ((c[1] - a[1]) * (p[0] - c[0]) + (a[0] - c[0]) * (p[1] - c[1])) / den;
    l_out[2] = 1 - l_out[0] - l_out[1];
}

/* ---- the sweeps as data ---- */

/* What one step draws. */
struct sweep_frame {
    const struct draw_item *items;
    int n_items;
    struct camera cam;
};

/* A method compared that is not one value of one axis: a filter with a supersampling
 * factor (minification's). */
struct sweep_combo {
    const char *name; /* as a flag value: ssaa4 is --ssaa 4 */
    enum tex_filter filter;
    enum ssaa_method ssaa;
};

/* One sweep, as the table below (sweeps[]) holds it; sweep.h says what each one measures and
 * why. sweep_run walks an entry: the result's words, steps and methods from here; the scene
 * (init); for every step (step -1 first, when `reference`) its placement (step), drawn with
 * every method and scored (measure); then the failure points, a theory column's predictions
 * and the theory's words (predict); release last, whatever happened. A scene's state is
 * ctx_size bytes, zeroed before init (release must take it in any state init leaves). */
struct sweep_def {
    const char *name;       /* --sweep NAME */
    const char *what;       /* one line: the scene and the method axis */
    const char *param_name; /* what is varied */
    const char *error_name; /* what is measured */
    const char *extra_name; /* a second measure, or NULL */
    bool extra_is_theory;   /* extra predicts error: a method is predicted to fail at the
                             * first step where it passes the threshold */
    double threshold;       /* fails when error > threshold (or a NaN/inf appears) */
    /* the threshold in words: a printf format given two doubles, the threshold (times 100
     * when fails_percent) and the PSNR an RMS error of the threshold means (either may go
     * unused) */
    const char *fails;
    bool fails_percent;
    bool xlog, ylog, reversed; /* how to plot: log axes; param decreasing */
    /* the range: the n_steps values in steps[], or, without steps, 10^(log0 + s / per_decade)
     * for s = 0 .. n_steps-1 (a step may replace its value with the one it reached) */
    const double *steps;
    int n_steps;
    double log0, per_decade;
    bool reference;         /* first a step -1 (param 0), drawn with method 0 only: the
                             * picture the steps are compared with */
    /* the methods: every value of the render_opts field `field`, named by `axis` (the
     * default is value 0); without an axis the n_combos combos, the default default_combo.
     * Every method draws with render_opts_default, unlit, bilinear when `bilinear`. */
    const struct render_enum *axis;
    size_t field;
    const struct sweep_combo *combos;
    int n_combos, default_combo;
    bool bilinear;
    /* the scene */
    size_t ctx_size;
    int (*init)(void *ctx, int w, int h, struct err *e);
    int (*step)(void *ctx, double *param, struct sweep_frame *out, struct err *e);
    void (*measure)(void *ctx, const struct fb *fb, const struct render_opts *o, int s, int m,
                    struct sweep_result *r);
    /* the theory: in words when it needs no numbers, else written by predict (r->theory,
     * and holds_until) once the steps are measured and the predictions made */
    const char *theory;
    void (*predict)(void *ctx, struct sweep_result *r);
    void (*release)(void *ctx);
};

#define COUNT(a) ((int)(sizeof(a) / sizeof((a)[0])))

/* ---- grazing ---- */

static const double gz_deg[] = {90, 85, 80, 75, 60, 45, 30, 20, 15, 10, 7, 5, 3, 2, 1};
/* the quad: corners (x, z) on y = 0 and their uvs; triangles 0 1 2 and 0 2 3 */
static const double gz_x[4] = {-1, 1, 1, -1}, gz_z[4] = {1, 1, -1, -1};
static const double gz_u[4] = {0.02, 0.98, 0.98, 0.02}, gz_v[4] = {0.02, 0.02, 0.98, 0.98};

struct grazing {
    int w, h;
    struct mesh m;
    struct texture tex;
    struct draw_item item;
    struct view_rays v;  /* this step's camera */
    double corner[4][2]; /* the quad's corners in pixels */
};

static int grazing_init(void *ctx, int w, int h, struct err *e)
{
    struct grazing *g = ctx;
    g->w = w, g->h = h;
    struct build b = {0};
    for (int i = 0; i < 4; i++)
        b_vert(&b, gz_x[i], 0, gz_z[i], gz_u[i], gz_v[i]);
    b_tri(&b, 0, 1, 2);
    b_tri(&b, 0, 2, 3);
    if (b_mesh(&b, &g->m, e) || ramp_texture(&g->tex, e))
        return -1;
    g->item = b_item(&g->m, &g->tex, NULL);
    return 0;
}

static int grazing_step(void *ctx, double *param, struct sweep_frame *f, struct err *e)
{
    (void)e;
    struct grazing *g = ctx;
    double th = *param * M_PI / 180;
    camera_default(&f->cam);
    f->cam.eye = v3(0, 3 * sin(th), 3 * cos(th));
    f->cam.target = v3(0, 0, 0);
    f->cam.up = v3(0.5, 0.866, 0);
    rays_init(&g->v, &f->cam, g->w, g->h);
    for (int i = 0; i < 4; i++)
        project(&g->v, v3(gz_x[i], 0, gz_z[i]), &g->corner[i][0], &g->corner[i][1]);
    f->items = &g->item;
    f->n_items = 1;
    return 0;
}

static void grazing_measure(void *ctx, const struct fb *fb, const struct render_opts *o, int s,
                            int k, struct sweep_result *r)
{
    (void)o;
    const struct grazing *g = ctx;
    const struct view_rays *v = &g->v;
    double sum = 0, sum_affine = 0;
    long n = 0;
    for (int py = 0; py < g->h; py++)
        for (int px = 0; px < g->w; px++) {
            size_t i = (size_t)py * g->w + px;
            if (!fb_covered(fb, i))
                continue;
            /* the ray's hit on y = 0, and half a pixel around it: all inside */
            bool inside = true;
            double x = 0, z = 0;
            for (int q = 0; q < 5 && inside; q++) {
                double ox = q == 1 ? -0.5 : q == 2 ? 0.5 : 0;
                double oy = q == 3 ? -0.5 : q == 4 ? 0.5 : 0;
                vec3 d = ray_dir(v, px + 0.5 + ox, py + 0.5 + oy);
                if (!(d.y < 0)) {
                    inside = false;
                    break;
                }
                double t = -v->eye.y / d.y;
                double hx = v->eye.x + t * d.x, hz = v->eye.z + t * d.z;
                inside = fabs(hx) < 1 && fabs(hz) < 1;
                if (q == 0)
                    x = hx, z = hz;
            }
            if (!inside)
                continue;
            double tu = (0.02 + 0.96 * (x + 1) / 2) * 256 - 0.5;
            double tv = (0.02 + 0.96 * (1 - z) / 2) * 256 - 0.5;
            const uint8_t *c = fb->rgb + 3 * i;
            sum += fmax(fabs(c[0] - floor(tu + 0.5)), fabs(c[1] - floor(tv + 0.5)));
            n++;
            if (k == PERSP_AFFINE) { /* the same, interpolated in screen space */
                int t1 = x + z >= 0 ? 1 : 2; /* triangle 0 1 2 or 0 2 3 */
                const int idx[3] = {0, t1, t1 + 1};
                double l[3], pc[2] = {px + 0.5, py + 0.5}, au = 0, av = 0;
                bary2(g->corner[idx[0]], g->corner[idx[1]], g->corner[idx[2]], pc, l);
                for (int j = 0; j < 3; j++)
                    au += l[j] * gz_u[idx[j]], av += l[j] * gz_v[idx[j]];
                au = au * 256 - 0.5, av = av * 256 - 0.5;
                sum_affine += fmax(fabs(floor(au + 0.5) - floor(tu + 0.5)),
                                   fabs(floor(av + 0.5) - floor(tv + 0.5)));
            }
        }
    r->error[s][k] = n ? sum / n : NAN; /* NAN: too small to measure */
    r->extra[s][k] = k == PERSP_AFFINE ? (n ? sum_affine / n : NAN) : NAN;
    r->nan[s][k] = count_nan(fb);
}

static void grazing_predict(void *ctx, struct sweep_result *r)
{
    (void)ctx;
    snprintf(r->theory, sizeof r->theory,
             "affine interpolates uv linearly in screen space while 1/w varies across each "
             "triangle: exact from straight above (90 deg, w constant), then its error grows "
             "as the angle flattens; the theory column interpolates the corners' uvs linearly "
             "between their projections in double and predicts failure at %g deg. Spans are "
             "exact every n pixels and bend in between: they fail later (shorter spans "
             "later); correct divides per pixel and never fails.",
             r->predicted[PERSP_AFFINE]);
}

static void grazing_release(void *ctx)
{
    struct grazing *g = ctx;
    texture_free(&g->tex);
    mesh_free(&g->m);
}

/* ---- depthrange ---- */

#define DR_FAR 100.0
#define DR_DIST 20.0
#define DR_GAP 0.01
#define DR_SLOPE 0.02 /* the quads tilt: depth sweeps across the steps */

/* the spacing of floats around v */
static double float_step(double v)
{
    float f = (float)fabs(v);
    return (double)nextafterf(f, INFINITY) - (double)f;
}

/* Theory: the fraction of pixels where the quads tie in the method's stored measure, from
 * each pixel's ray hits on the two planes (view depth t; window depth z01 = far/(far-near)
 * (1 - near/t)): a tie has probability max(0, 1 - d/q) for values d apart stored with step q. */
static double depth_ties(const struct camera *cam, int w, int h, enum depth_mode m)
{
    struct view_rays v;
    rays_init(&v, cam, w, h);
    double n = cam->near, f = cam->far, sum = 0;
    for (int py = 0; py < h; py++)
        for (int px = 0; px < w; px++) {
            vec3 d = ray_dir(&v, px + 0.5, py + 0.5); /* eye at the origin, looking down -z */
            double t_near = DR_DIST / (1 + DR_SLOPE * d.y);
            double t_far = (DR_DIST + DR_GAP) / (1 + DR_SLOPE * d.y);
            double z_near = f / (f - n) * (1 - n / t_near), z_far = f / (f - n) * (1 - n / t_far);
            double dd, q;
            switch (m) {
            case DEPTH_Z16: dd = z_far - z_near, q = 1 / 65535.0; break;
            case DEPTH_W: dd = t_far - t_near, q = float_step(t_far); break;
            case DEPTH_RZ: dd = z_far - z_near, q = float_step(1 - z_far); break;
            default: dd = z_far - z_near, q = float_step(z_far); break;
            }
            sum += dd < q ? 1 - dd / q : 0;
        }
    return sum / ((double)w * h);
}


struct depthrange {
    int w, h;
    struct mesh m[2]; /* m[0] the farther quad (drawn first), m[1] the nearer */
    struct draw_item items[2];
    struct camera cam; /* this step's */
};

static int depthrange_init(void *ctx, int w, int h, struct err *e)
{
    struct depthrange *d = ctx;
    d->w = w, d->h = h;
    double half_w = 1.3 * DR_DIST * tan(25 * M_PI / 180) * w / h + 2, half_h = half_w;
    for (int q = 0; q < 2; q++) {
        struct build b = {0};
        double z = -(DR_DIST + (q == 0 ? DR_GAP : 0));
        b_vert(&b, -half_w, -half_h, z - DR_SLOPE * half_h, 0, 0);
        b_vert(&b, half_w, -half_h, z - DR_SLOPE * half_h, 0, 0);
        b_vert(&b, half_w, half_h, z + DR_SLOPE * half_h, 0, 0);
        b_vert(&b, -half_w, half_h, z + DR_SLOPE * half_h, 0, 0);
        b_tri(&b, 0, 1, 2);
        b_tri(&b, 0, 2, 3);
        if (b_mesh(&b, &d->m[q], e))
            return -1;
    }
    static const float green[3] = {0, 1, 0}, red[3] = {1, 0, 0};
    d->items[0] = b_item(&d->m[0], NULL, green);
    d->items[1] = b_item(&d->m[1], NULL, red);
    return 0;
}

static int depthrange_step(void *ctx, double *param, struct sweep_frame *f, struct err *e)
{
    (void)e;
    struct depthrange *d = ctx;
    camera_default(&d->cam);
    d->cam.eye = v3(0, 0, 0);
    d->cam.target = v3(0, 0, -1);
    d->cam.far = DR_FAR;
    d->cam.near = DR_FAR / *param; /* param: the far/near ratio */
    f->cam = d->cam;
    f->items = d->items;
    f->n_items = 2;
    return 0;
}

static void depthrange_measure(void *ctx, const struct fb *fb, const struct render_opts *o,
                               int s, int k, struct sweep_result *r)
{
    (void)o;
    const struct depthrange *d = ctx;
    long far = 0, n = 0;
    for (size_t i = 0; i < (size_t)d->w * d->h; i++) {
        const uint8_t *c = fb->rgb + 3 * i;
        n += c[0] > 0 || c[1] > 0;
        far += c[1] > c[0];
    }
    r->error[s][k] = n ? (double)far / n : 1;
    r->nan[s][k] = count_nan(fb);
    r->extra[s][k] = depth_ties(&d->cam, d->w, d->h, (enum depth_mode)k);
}

static void depthrange_predict(void *ctx, struct sweep_result *r)
{
    (void)ctx;
    /* the closed form for the quads' centre: step = q D^2 (ratio - 1) / far */
    double kk = DR_FAR * DR_GAP / (0.99 * DR_DIST * DR_DIST);
    snprintf(r->theory, sizeof r->theory,
             "a stored value with step q ties two depths d apart (the farther, drawn first, "
             "wins) in a fraction 1 - d/q of the pixels once q > d. In window depth a step q "
             "spans q D^2 (ratio - 1) / far units at distance D, so the quads 0.01 apart tie "
             "in more than 1%% from ratio = 1 + far gap / (0.99 q D^2): z16 (q = 1/65535) at "
             "%.0f, z (float: q = 2^-24 for depths in [0.5, 1)) at %.0f; w and rz keep "
             "float's 24 bits relative to the stored value (gap/D = 5e-4 >> 2^-24): never. "
             "The theory column evaluates the tie fraction per pixel; it predicts failure "
             "at %.4g (z16) and %.4g (z). Both round each pixel's depth once (float z "
             "evaluates its plane as a float base plus a small part, setup.h), so their ties "
             "fall pixel by pixel as predicted.",
             1 + kk * 65535, 1 + kk * 16777216.0, r->predicted[DEPTH_Z16], r->predicted[DEPTH_Z]);
}

static void depthrange_release(void *ctx)
{
    struct depthrange *d = ctx;
    mesh_free(&d->m[0]);
    mesh_free(&d->m[1]);
}

/* ---- magnitude ---- */

/* uncovered pixels not 4-connected to the border through uncovered pixels */
static long enclosed_background(const struct fb *fb, uint8_t *seen, int *stack)
{
    int w = fb->w, h = fb->h, top = 0;
    memset(seen, 0, (size_t)w * h);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            int i = y * w + x;
            if ((x == 0 || y == 0 || x == w - 1 || y == h - 1) && !fb_covered(fb, (size_t)i) &&
                !seen[i]) {
                seen[i] = 1;
                stack[top++] = i;
            }
        }
    while (top) {
        int i = stack[--top], x = i % w, y = i / w;
        const int nb[4][2] = {{x - 1, y}, {x + 1, y}, {x, y - 1}, {x, y + 1}};
        for (int k = 0; k < 4; k++) {
            if (nb[k][0] < 0 || nb[k][1] < 0 || nb[k][0] >= w || nb[k][1] >= h)
                continue;
            int j = nb[k][1] * w + nb[k][0];
            if (!seen[j] && !fb_covered(fb, (size_t)j)) {
                seen[j] = 1;
                stack[top++] = j;
            }
        }
    }
    long n = 0;
    for (int i = 0; i < w * h; i++)
        n += !seen[i] && !fb_covered(fb, (size_t)i);
    return n;
}

/* a UV sphere of radius 1 around c, shared vertices (watertight), poles single vertices */
static void sphere(struct build *b, vec3 c, int stacks, int slices)
{
    uint32_t top = b_vert(b, c.x, c.y + 1, c.z, 0, 0);
    uint32_t first = b->n_pos;
    for (int i = 1; i < stacks; i++) {
        double ph = M_PI * i / stacks;
        for (int j = 0; j < slices; j++) {
            double th = 2 * M_PI * j / slices;
            b_vert(b, c.x + sin(ph) * cos(th), c.y + cos(ph), c.z - sin(ph) * sin(th), 0, 0);
        }
    }
    uint32_t bottom = b_vert(b, c.x, c.y - 1, c.z, 0, 0);
    for (int j = 0; j < slices; j++) {
        int j1 = (j + 1) % slices;
        b_tri(b, top, first + (uint32_t)j, first + (uint32_t)j1);
        for (int i = 0; i + 2 < stacks; i++) {
            uint32_t a = first + (uint32_t)(i * slices + j);
            uint32_t a1 = first + (uint32_t)(i * slices + j1);
            uint32_t d = a + (uint32_t)slices, d1 = a1 + (uint32_t)slices;
            b_tri(b, a, d, d1);
            b_tri(b, a, d1, a1);
        }
        uint32_t l = first + (uint32_t)((stacks - 2) * slices);
        b_tri(b, l + (uint32_t)j, bottom, l + (uint32_t)j1);
    }
}


struct magnitude {
    int w, h;
    uint8_t *ref;  /* the sphere at the origin: covered pixels */
    uint8_t *seen; /* enclosed_background's scratch */
    int *stack;
    struct mesh m; /* this step's sphere */
    struct draw_item item;
};

static int magnitude_init(void *ctx, int w, int h, struct err *e)
{
    struct magnitude *g = ctx;
    g->w = w, g->h = h;
    g->ref = malloc((size_t)w * h);
    g->seen = malloc((size_t)w * h);
    g->stack = malloc((size_t)w * h * sizeof *g->stack);
    return g->ref && g->seen && g->stack ? 0 : err_set(e, "out of memory");
}

static int magnitude_step(void *ctx, double *param, struct sweep_frame *f, struct err *e)
{
    struct magnitude *g = ctx;
    double t = *param; /* the distance; 0 for the reference */
    vec3 c = v3(t / sqrt(3), t / sqrt(3), t / sqrt(3));
    mesh_free(&g->m);
    struct build b = {0};
    sphere(&b, c, 16, 32);
    if (b_mesh(&b, &g->m, e))
        return -1;
    static const float blue[3] = {0.2f, 0.6f, 0.9f};
    g->item = b_item(&g->m, NULL, blue);
    camera_default(&f->cam);
    f->cam.target = v3((float)c.x, (float)c.y, (float)c.z); /* where the input says it is */
    f->cam.eye = v3_add(f->cam.target, v3(0.3, 0.4, 3 - 0.05));
    f->items = &g->item;
    f->n_items = 1;
    return 0;
}

static void magnitude_measure(void *ctx, const struct fb *fb, const struct render_opts *o,
                              int s, int k, struct sweep_result *r)
{
    (void)o;
    struct magnitude *g = ctx;
    size_t n_px = (size_t)g->w * g->h;
    if (s < 0) { /* the reference */
        for (size_t i = 0; i < n_px; i++)
            g->ref[i] = fb_covered(fb, i);
        return;
    }
    long jitter = 0;
    for (size_t i = 0; i < n_px; i++)
        jitter += g->ref[i] != fb_covered(fb, i);
    r->error[s][k] = (double)enclosed_background(fb, g->seen, g->stack);
    r->extra[s][k] = (double)jitter;
    r->nan[s][k] = count_nan(fb);
}

static void magnitude_predict(void *ctx, struct sweep_result *r)
{
    const struct magnitude *g = ctx;
    /* a coordinate x = T/sqrt(3) in float moves in steps of 2^(floor(log2 x) - 23); the
     * shape is gone when that step reaches a pixel (world size at the sphere's distance) */
    double px_world = 2 * 3 * tan(25 * M_PI / 180) / g->h;
    double runs_out = sqrt(3) * ldexp(1, (int)ceil(log2(px_world)) + 23);
    r->holds_until = runs_out;
    snprintf(r->theory, sizeof r->theory,
             "coverage is exact on the snapped vertices and a watertight mesh shares them, so "
             "no crack can open while the vertices mean anything; the input's own float "
             "precision runs out when a coordinate's float step (2^-23 of it) reaches a pixel "
             "(%.3g units here): from T = %.3g on. Jitter starts earlier, once that step "
             "passes the 1/256-pixel snap.", px_world, runs_out);
}

static void magnitude_release(void *ctx)
{
    struct magnitude *g = ctx;
    mesh_free(&g->m);
    free(g->ref);
    free(g->seen);
    free(g->stack);
}

/* ---- sliver ---- */

/* The rectangle lives on the pixel-centre lattice: an orthographic view one unit a pixel,
 * the centre C on a pixel centre, the long axis A = (2, 1) and the short one B = (-1, 2)
 * (pixels, y down: lattice directions, about 26.6 degrees off the rows). Corners and ring
 * points are C + t A + s B with integer t, s, so spokes run exactly through pixel centres,
 * where the tie rule alone decides which triangle draws them. Half-width b = 2 (8.9 pixels
 * across), half-length a = the aspect ratio times b (even). */
#define SL_B 2
#define SL_RING 3 /* points on each long side between the corners */


static const double sl_axis_a[2] = {2, 1}, sl_axis_b[2] = {-1, 2}; /* A and B, pixels */

struct sliver {
    int w, h;
    struct texture tex;
    struct camera cam; /* orthographic, one unit a pixel */
    double cx, cy;     /* C, pixels */
    long a;            /* this step's half-length */
    struct mesh m;     /* this step's fan */
    struct draw_item item;
};

static int sliver_init(void *ctx, int w, int h, struct err *e)
{
    struct sliver *g = ctx;
    g->w = w, g->h = h;
    if (ramp_texture(&g->tex, e))
        return -1;
    camera_default(&g->cam);
    g->cam.ortho_height = h; /* one unit = one pixel */
    g->cx = floor(w / 2.0) + 0.5, g->cy = floor(h / 2.0) + 0.5;
    return 0;
}

/* param: the aspect ratio wanted, replaced by the one drawn (a / b, a even) */
static int sliver_step(void *ctx, double *param, struct sweep_frame *f, struct err *e)
{
    struct sliver *g = ctx;
    const double *A = sl_axis_a, *B = sl_axis_b, cx = g->cx, cy = g->cy;
    int w = g->w, h = g->h;
    double want_aspect = *param;
    long a = 2 * lround(want_aspect * SL_B / 2); /* even: ring points on the lattice */
    a = a < 2 ? 2 : a;
    *param = (double)a / SL_B;
    g->a = a;
    /* the ring as (t, s): each long side at t = -a, -a/2, 0, a/2, a, plus the point that
     * makes a horizontal spoke (t = 4 on s = -2: C + (10, 0)) and one that makes a
     * vertical spoke (t = 1 on s = 2: C + (0, 5)) when they fit */
    long side[2][6];
    int ns[2] = {0, 0};
    for (int k = 0; k < 2; k++) {
        long extra = k == 0 ? 4 : 1;
        for (int i = 0; i <= SL_RING + 1; i++) {
            long t = -a + 2 * a * i / (SL_RING + 1);
            if (extra > t - 2 * a / (SL_RING + 1) && extra < t && extra > -a)
                side[k][ns[k]++] = extra;
            side[k][ns[k]++] = t;
        }
    }
    long ring[12][2];
    int n = 0;
    for (int i = 0; i < ns[0]; i++) /* the side s = -b, t from -a to a */
        ring[n][0] = side[0][i], ring[n++][1] = -SL_B;
    for (int i = ns[1] - 1; i >= 0; i--) /* the side s = +b, back */
        ring[n][0] = side[1][i], ring[n++][1] = SL_B;
    struct build b = {0};
    for (int i = -1; i < n; i++) {
        double t = i < 0 ? 0 : (double)ring[i][0], q = i < 0 ? 0 : (double)ring[i][1];
        double px = cx + t * A[0] + q * B[0], py = cy + t * A[1] + q * B[1];
        b_vert(&b, px - w / 2.0, h / 2.0 - py, 0, 0.02 + 0.96 * (t / a + 1) / 2,
               0.02 + 0.96 * (q / SL_B + 1) / 2);
    }
    for (int i = 0; i < n; i++)
        b_tri(&b, 0, (uint32_t)(1 + i), (uint32_t)(1 + (i + 1) % n));
    mesh_free(&g->m);
    if (b_mesh(&b, &g->m, e))
        return -1;
    g->item = b_item(&g->m, &g->tex, NULL);
    f->cam = g->cam;
    f->items = &g->item;
    f->n_items = 1;
    return 0;
}

static void sliver_measure(void *ctx, const struct fb *fb, const struct render_opts *o, int s,
                           int k, struct sweep_result *r)
{
    (void)o;
    const struct sliver *g = ctx;
    const double *A = sl_axis_a, *B = sl_axis_b, cx = g->cx, cy = g->cy;
    long a = g->a;
    long bad = 0, off = 0;
    for (int py = 0; py < g->h; py++)
        for (int px = 0; px < g->w; px++) {
            /* (t, s) of the centre: exact multiples of 1/5 */
            double dx = px + 0.5 - cx, dy = py + 0.5 - cy;
            double t = (dx * A[0] + dy * A[1]) / 5, q = (dx * B[0] + dy * B[1]) / 5;
            if (fabs(fabs(q) - SL_B) < 1e-9 || fabs(fabs(t) - a) < 1e-9)
                continue; /* on the outline: the tie rule's call, either is right */
            int want = fabs(t) < a && fabs(q) < SL_B;
            size_t i = (size_t)py * g->w + px;
            long got = (long)fb->overdraw[i];
            bad += labs(got - want);
            if (want && got == 1) {
                double tu = (0.02 + 0.96 * (t / a + 1) / 2) * 256 - 0.5;
                double tv = (0.02 + 0.96 * (q / SL_B + 1) / 2) * 256 - 0.5;
                const uint8_t *col = fb->rgb + 3 * i;
                off += fabs(col[0] - tu) > 8 || fabs(col[1] - tv) > 8;
            }
        }
    r->error[s][k] = (double)bad;
    r->extra[s][k] = (double)off;
    r->nan[s][k] = count_nan(fb);
}

static void sliver_release(void *ctx)
{
    struct sliver *g = ctx;
    mesh_free(&g->m);
    texture_free(&g->tex);
}

/* ---- nearplane ---- */

/* box faces crossed by eye + t d with near < t < far: 0, 1 or 2 (NAN: grazes an edge) */
static int box_crossings(vec3 eye, vec3 d, double near, double far)
{
    double t0 = -INFINITY, t1 = INFINITY;
    const double o[3] = {eye.x, eye.y, eye.z}, dd[3] = {d.x, d.y, d.z};
    for (int k = 0; k < 3; k++) {
        if (dd[k] == 0) {
            if (fabs(o[k]) >= 1)
                return 0;
            continue;
        }
        double a = (-1 - o[k]) / dd[k], b = (1 - o[k]) / dd[k];
        if (a > b) {
            double tmp = a;
            a = b, b = tmp;
        }
        t0 = a > t0 ? a : t0;
        t1 = b < t1 ? b : t1;
    }
    if (!(t0 < t1))
        return 0;
    return (t0 > near && t0 < far) + (t1 > near && t1 < far);
}


static const double np_eye_z[] = {3, 2, 1.5, 1.2, 1.1, 1.05, 1.0, 0.95, 0.5, 0, -0.5, -0.9,
                                  -0.95, -1.0, -1.05, -1.5, -3};

struct nearplane {
    int w, h;
    struct mesh m;
    struct draw_item item;
    struct camera cam;  /* this step's */
    struct view_rays v;
};

static int nearplane_init(void *ctx, int w, int h, struct err *e)
{
    struct nearplane *g = ctx;
    g->w = w, g->h = h;
    struct build b = {0};
    const int n = 4;
    for (int face = 0; face < 6; face++) { /* axis, sign; vertices shared along the edges */
        int ax = face / 2;
        double sg = face % 2 ? -1 : 1;
        uint32_t idx[5][5];
        for (int j = 0; j <= n; j++)
            for (int i = 0; i <= n; i++) {
                double p[3], a = -1 + 2.0 * i / n, c = -1 + 2.0 * j / n;
                p[ax] = sg, p[(ax + 1) % 3] = a, p[(ax + 2) % 3] = c * sg;
                /* reuse a vertex already made at this position (edges and corners) */
                uint32_t found = UINT32_MAX;
                for (uint32_t v = 0; v < b.n_pos && found == UINT32_MAX; v++)
                    if (b.pos[3 * v] == (float)p[0] && b.pos[3 * v + 1] == (float)p[1] &&
                        b.pos[3 * v + 2] == (float)p[2])
                        found = v;
                idx[j][i] = found != UINT32_MAX ? found : b_vert(&b, p[0], p[1], p[2], 0, 0);
            }
        for (int j = 0; j < n; j++)
            for (int i = 0; i < n; i++) {
                b_tri(&b, idx[j][i], idx[j][i + 1], idx[j + 1][i + 1]);
                b_tri(&b, idx[j][i], idx[j + 1][i + 1], idx[j + 1][i]);
            }
    }
    if (b_mesh(&b, &g->m, e))
        return -1;
    g->item = b_item(&g->m, NULL, NULL);
    return 0;
}

static int nearplane_step(void *ctx, double *param, struct sweep_frame *f, struct err *e)
{
    (void)e;
    struct nearplane *g = ctx;
    camera_default(&g->cam);
    g->cam.eye = v3(0.3, 0.2, *param);
    g->cam.target = v3_add(g->cam.eye, v3(0.15, 0.1, -1));
    rays_init(&g->v, &g->cam, g->w, g->h);
    f->cam = g->cam;
    f->items = &g->item;
    f->n_items = 1;
    return 0;
}

static void nearplane_measure(void *ctx, const struct fb *fb, const struct render_opts *o,
                              int s, int k, struct sweep_result *r)
{
    const struct nearplane *g = ctx;
    const struct view_rays *v = &g->v;
    const struct camera *cam = &g->cam;
    long bad = 0, nan = 0;
    for (int py = 0; py < g->h; py++)
        for (int px = 0; px < g->w; px++) {
            int want = -1;
            bool clear = true;
            for (int q = 0; q < 5 && clear; q++) { /* the centre and 0.4 px around */
                double ox = q == 1 ? -0.4 : q == 2 ? 0.4 : 0;
                double oy = q == 3 ? -0.4 : q == 4 ? 0.4 : 0;
                int c = box_crossings(v->eye, ray_dir(v, px + 0.5 + ox, py + 0.5 + oy),
                                      cam->near * 1.001, cam->far);
                int c2 = box_crossings(v->eye, ray_dir(v, px + 0.5 + ox, py + 0.5 + oy),
                                       cam->near * 0.999, cam->far);
                clear = c == c2 && (want < 0 || c == want);
                want = c;
            }
            size_t i = (size_t)py * g->w + px;
            if (fb_covered(fb, i)) {
                double d = fb_depth_window(fb, i);
                nan += !isfinite(fb->depth[i]) || !(d >= 0 && d <= 1) ||
                       (o->depth == DEPTH_W && !(fb->depth[i] > 0));
            }
            if (clear)
                bad += labs((long)fb->overdraw[i] - want);
        }
    r->error[s][k] = (double)bad;
    r->nan[s][k] = nan;
}

static void nearplane_release(void *ctx)
{
    struct nearplane *g = ctx;
    mesh_free(&g->m);
}

/* ---- minification ---- */

#define MN_TEX 61 /* a prime period: pixels at large minification do not all see the same texels */

/* F(x, y) from the integer-grid table t (side s = n + 1) for 0 <= x, y <= n: bilinear
 * between grid points, which is exact for a piecewise-constant texture */
static double sat_at(const double *t, int n, double x, double y)
{
    const int s = n + 1;
    int i = (int)floor(x), j = (int)floor(y);
    i = i >= n ? n - 1 : i;
    j = j >= n ? n - 1 : j;
    double fx = x - i, fy = y - j;
    return (1 - fx) * (1 - fy) * t[j * s + i] + fx * (1 - fy) * t[j * s + i + 1] +
           (1 - fx) * fy * t[(j + 1) * s + i] + fx * fy * t[(j + 1) * s + i + 1];
}

/* The integral of texel values (box reconstruction, repeat) over [0,x] x [0,y] in texel
 * units (y from the bottom), channel c, from the summed-area table sat, (MN_TEX+1)^2 per
 * channel: F(x, y) = qx qy F(n,n) + qx F(n, ry) + qy F(rx, n) + F(rx, ry). */
static double box_integral(const double *sat, int c, double x, double y)
{
    const int n = MN_TEX, s = MN_TEX + 1;
    double qx = floor(x / n), qy = floor(y / n);
    double rx = x - qx * n, ry = y - qy * n;
    const double *t = sat + (size_t)c * s * s;
    return qx * qy * sat_at(t, n, n, n) + qx * sat_at(t, n, n, ry) + qy * sat_at(t, n, rx, n) +
           sat_at(t, n, rx, ry);
}

/* Theory, along one axis, for pixel x at k texels a pixel: the weight each texel (mod the
 * period) gets from the method's samples (c) and from the box (a); returns sum c^2, sum c a
 * and sum a^2 in out[3]. method: 0 nearest, 1 bilinear, n >= 2 an n x n grid of nearest
 * samples. */
static void axis_weights(int x, double k, int method, double out[3])
{
    double c[MN_TEX] = {0}, a[MN_TEX] = {0};
    double x0 = x * k, x1 = (x + 1) * k;
    for (int t = (int)floor(x0); t < x1; t++) { /* box: overlap of [t, t+1] with the pixel */
        double o = fmin(t + 1, x1) - fmax(t, x0);
        a[((t % MN_TEX) + MN_TEX) % MN_TEX] += o / k;
    }
    if (method == 1) {
        double sx = (x + 0.5) * k - 0.5, i0 = floor(sx), f = sx - i0;
        int i = ((int)i0 % MN_TEX + MN_TEX) % MN_TEX;
        c[i] += 1 - f;
        c[(i + 1) % MN_TEX] += f;
    } else {
        int n = method == 0 ? 1 : method;
        for (int j = 0; j < n; j++) {
            int t = (int)floor((x + (j + 0.5) / n) * k);
            c[t % MN_TEX] += 1.0 / n;
        }
    }
    out[0] = out[1] = out[2] = 0;
    for (int t = 0; t < MN_TEX; t++)
        out[0] += c[t] * c[t], out[1] += c[t] * a[t], out[2] += a[t] * a[t];
}


static const double mn_k[] = {1, 1.25, 1.5, 2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64};
static const struct sweep_combo mn_methods[] = {
    {"nearest", TEX_NEAREST, SSAA_1},   {"bilinear", TEX_BILINEAR, SSAA_1},
    {"ssaa2", TEX_NEAREST, SSAA_2},     {"ssaa4", TEX_NEAREST, SSAA_4},
    {"ssaa8", TEX_NEAREST, SSAA_8},     {"trilinear", TEX_TRILINEAR, SSAA_1},
};
/* each method's samples for axis_weights; -1: no closed form */
static const int mn_theory[] = {0, 1, 2, 4, 8, -1};
_Static_assert(COUNT(mn_theory) == COUNT(mn_methods), "a theory entry per method");

struct minification {
    int w, h;
    uint8_t *px;               /* the texture: white noise */
    double *sat;               /* its summed-area table, (MN_TEX+1)^2 per channel */
    double (*wx)[3], (*wy)[3]; /* the theory's weights per column and per row */
    double sigma;              /* the noise's deviation, levels */
    struct texture tex;
    struct camera cam;         /* orthographic, one unit a pixel */
    double k;                  /* this step's texels per pixel */
    struct mesh m;             /* this step's plane */
    struct draw_item item;
};

static int minification_init(void *ctx, int w, int h, struct err *e)
{
    struct minification *g = ctx;
    g->w = w, g->h = h;
    /* the texture: white noise from a fixed LCG, and its summed-area table */
    uint8_t *px = g->px = malloc(MN_TEX * MN_TEX * 4);
    double *sat = g->sat = calloc((size_t)3 * (MN_TEX + 1) * (MN_TEX + 1), sizeof *sat);
    g->wx = malloc((size_t)w * sizeof *g->wx), g->wy = malloc((size_t)h * sizeof *g->wy);
    if (!px || !sat || !g->wx || !g->wy)
        return err_set(e, "out of memory");
    uint32_t seed = 12345;
    double sum = 0, sum2 = 0;
    for (int i = 0; i < MN_TEX * MN_TEX; i++)
        for (int c = 0; c < 4; c++) {
            seed = seed * 1664525u + 1013904223u;
            px[4 * i + c] = c == 3 ? 255 : (uint8_t)(seed >> 24);
            if (c < 3)
                sum += px[4 * i + c], sum2 += (double)px[4 * i + c] * px[4 * i + c];
        }
    double nv = 3.0 * MN_TEX * MN_TEX;
    g->sigma = sqrt(sum2 / nv - (sum / nv) * (sum / nv));
    const int s = MN_TEX + 1;
    for (int c = 0; c < 3; c++)
        for (int j = 1; j <= MN_TEX; j++) /* j counts rows from the bottom */
            for (int i = 1; i <= MN_TEX; i++) {
                int row = MN_TEX - j; /* image row of texel row j-1 from the bottom */
                double v = px[4 * (row * MN_TEX + (i - 1)) + c];
                double *t = sat + (size_t)c * s * s;
                t[j * s + i] = v + t[(j - 1) * s + i] + t[j * s + i - 1] - t[(j - 1) * s + i - 1];
            }
    if (texture_from_rgba(MN_TEX, MN_TEX, px, &g->tex, e))
        return -1;
    camera_default(&g->cam);
    g->cam.ortho_height = h; /* one unit = one pixel */
    return 0;
}

static int minification_step(void *ctx, double *param, struct sweep_frame *f, struct err *e)
{
    struct minification *g = ctx;
    int w = g->w, h = g->h;
    double k = g->k = *param;
    struct build b = {0};
    double hw = w / 2.0, hh = h / 2.0, sc = k / MN_TEX;
    b_vert(&b, -hw, -hh, 0, 0, 0);
    b_vert(&b, hw, -hh, 0, w * sc, 0);
    b_vert(&b, hw, hh, 0, w * sc, h * sc);
    b_vert(&b, -hw, hh, 0, 0, h * sc);
    b_tri(&b, 0, 1, 2);
    b_tri(&b, 0, 2, 3);
    mesh_free(&g->m);
    if (b_mesh(&b, &g->m, e))
        return -1;
    g->item = b_item(&g->m, &g->tex, NULL);
    f->cam = g->cam;
    f->items = &g->item;
    f->n_items = 1;
    return 0;
}

static void minification_measure(void *ctx, const struct fb *fb, const struct render_opts *o,
                                 int st, int me, struct sweep_result *r)
{
    (void)o;
    struct minification *g = ctx;
    int w = g->w, h = g->h;
    double k = g->k;
    double se = 0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double x0 = x * k, x1 = (x + 1) * k, y0 = (h - 1 - y) * k, y1 = (h - y) * k;
            for (int c = 0; c < 3; c++) {
                double v = box_integral(g->sat, c, x1, y1) - box_integral(g->sat, c, x0, y1) -
                           box_integral(g->sat, c, x1, y0) + box_integral(g->sat, c, x0, y0);
                double want = floor(v / (k * k) + 0.5);
                double d = fb->rgb[3 * ((size_t)y * w + x) + c] - want;
                se += d * d;
            }
        }
    r->error[st][me] = sqrt(se / (3.0 * w * h));
    r->nan[st][me] = count_nan(fb);
    if (mn_theory[me] < 0) {
        r->extra[st][me] = NAN;
        return;
    }
    /* theory: per pixel sum_t (c_t - a_t)^2 with c and a products of their axes */
    for (int x = 0; x < w; x++)
        axis_weights(x, k, mn_theory[me], g->wx[x]);
    for (int y = 0; y < h; y++) /* rows from the bottom, as texel rows count */
        axis_weights(h - 1 - y, k, mn_theory[me], g->wy[y]);
    double mse = 0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            mse += g->wx[x][0] * g->wy[y][0] - 2 * g->wx[x][1] * g->wy[y][1] +
                   g->wx[x][2] * g->wy[y][2];
    r->extra[st][me] = g->sigma * sqrt(fmax(0, mse / ((double)w * h)));
}

static void minification_predict(void *ctx, struct sweep_result *r)
{
    const struct minification *g = ctx;
    snprintf(r->theory, sizeof r->theory,
             "for white noise of deviation s = %.1f levels, a pixel whose samples weigh texel t "
             "by c_t where the box weighs it by a_t is off by s sqrt(sum (c_t - a_t)^2) RMS; "
             "with m samples in distinct texels that is s sqrt(1/m - 1/k^2). Predicted "
             "failure: nearest at %g, bilinear at %g, ssaa2 at %g, ssaa4 at %g, ssaa8 at %g "
             "texels per pixel. Trilinear (the default) reads mip levels box-filtered from "
             "the texels (no closed form here: the levels of a 61-texel period straddle the "
             "pixels' footprints); it averages about as many texels as the footprint holds, "
             "so its error stays near the levels' own misalignment instead of growing with "
             "the texels skipped.",
             g->sigma, r->predicted[0], r->predicted[1], r->predicted[2], r->predicted[3],
             r->predicted[4]);
}

static void minification_release(void *ctx)
{
    struct minification *g = ctx;
    mesh_free(&g->m);
    texture_free(&g->tex);
    free(g->px);
    free(g->sat);
    free(g->wx);
    free(g->wy);
}

/* ---- the table, and the walker ---- */

#define STEPS(list) .steps = (list), .n_steps = COUNT(list)
#define LOG_STEPS(n, from, per) .n_steps = (n), .log0 = (from), .per_decade = (per)
#define AXIS(names, member) .axis = &(names), .field = offsetof(struct render_opts, member)
#define SCENE(x)                                                                            \
    .ctx_size = sizeof(struct x), .init = x##_init, .step = x##_step, .measure = x##_measure, \
    .release = x##_release

_Static_assert(COUNT(gz_deg) <= SWEEP_MAX_STEPS && COUNT(np_eye_z) <= SWEEP_MAX_STEPS &&
               COUNT(mn_k) <= SWEEP_MAX_STEPS, "steps fit a sweep_result");
_Static_assert(COUNT(mn_methods) <= SWEEP_MAX_METHODS, "methods fit a sweep_result");

static const struct sweep_def sweeps[SWEEP_COUNT] = {
    [SWEEP_GRAZING] = {
        .name = "grazing",
        .what = "a 2x2 textured ground (two triangles) seen from 3 units, camera rolled 30 "
                "degrees; --persp",
        .param_name = "degrees above the ground",
        .error_name = "mean texel error of the uv (256-texel ramp, against a ray cast)",
        .extra_name = "theory: affine's error, uv interpolated linearly between the projected "
                      "corners (double)",
        .extra_is_theory = true,
        .threshold = 0.5,
        .fails = "fails: mean uv error > %.1f texel (the sampled texel is off by half a texel "
                 "on average)",
        .xlog = true, .ylog = true, .reversed = true,
        STEPS(gz_deg),
        AXIS(render_persp_names, persp),
        .bilinear = true,
        SCENE(grazing),
        .predict = grazing_predict,
    },
    [SWEEP_DEPTHRANGE] = {
        .name = "depthrange",
        .what = "two parallel quads 0.01 apart, 20 units away (far plane 100), the farther "
                "drawn first; --depth",
        .param_name = "far/near ratio (near = 100 / ratio)",
        .error_name = "fraction of pixels where the farther quad wins",
        .extra_name = "theory: the expected fraction, mean over the pixels of max(0, 1 - "
                      "gap/step) in each method's stored measure",
        .extra_is_theory = true,
        .threshold = 0.01,
        .fails = "fails: the farther quad wins in more than %.0f%% of the pixels",
        .fails_percent = true,
        .xlog = true,
        LOG_STEPS(25, 1, 4.0), /* 10 .. 1e7 */
        AXIS(render_depth_names, depth),
        SCENE(depthrange),
        .predict = depthrange_predict,
    },
    [SWEEP_MAGNITUDE] = {
        .name = "magnitude",
        .what = "a watertight sphere (radius 1, 32x16) whose float coordinates sit T units "
                "from the origin, camera 3 units away following it; --raster",
        .param_name = "distance from the origin T",
        .error_name = "enclosed background pixels (cracks)",
        .extra_name = "jitter: pixels whose coverage differs from the sphere at the origin",
        .threshold = 0,
        .fails = "fails: any crack (error > 0)",
        .xlog = true, .ylog = true,
        LOG_STEPS(15, 0, 2.0), /* 1 .. 1e7 */
        .reference = true,
        AXIS(render_raster_names, raster),
        SCENE(magnitude),
        .predict = magnitude_predict,
    },
    [SWEEP_SLIVER] = {
        .name = "sliver",
        .what = "a closed fan (centre + ring of 10 to 12) filling a rectangle 8.9 pixels "
                "across, its corners and spokes on pixel centres; --raster",
        .param_name = "aspect ratio (length / width)",
        .error_name = "pixels covered other than once inside / never outside",
        .extra_name = "pixels inside whose uv is more than 8 texels off",
        .threshold = 0,
        .fails = "fails: any hole, overdraw or stray pixel (error > 0)",
        .xlog = true,
        LOG_STEPS(15, 0, 2.0), /* 1 .. 1e7, each the nearest the lattice draws */
        AXIS(render_raster_names, raster),
        .bilinear = true,
        SCENE(sliver),
        .theory = "coverage is decided by exact 64-bit edge functions on snapped vertices with "
                  "the tie rule, so a closed fan covers each pixel centre inside exactly once — "
                  "those on a spoke too — at any aspect ratio (pieces clipped by the guard band "
                  "included): never fails.",
    },
    [SWEEP_NEARPLANE] = {
        .name = "nearplane",
        .what = "the camera flies through a closed 2x2x2 box (4x4 quads a face), looking "
                "ahead and a little aside; --depth",
        .param_name = "eye z (the box spans -1..1)",
        .error_name = "pixels whose fragment count differs from the faces crossed before the "
                      "near plane",
        .threshold = 0,
        .fails = "fails: any hole, triangle drawn twice or pixel from behind the eye (error > "
                 "0); nan also counts stored depths outside the method's range (w <= 0)",
        .reversed = true,
        STEPS(np_eye_z),
        AXIS(render_depth_names, depth),
        SCENE(nearplane),
        .theory = "homogeneous clipping against near (z >= -w) before the divide leaves only "
                  "geometry in front of the eye, and shared clipped edges keep the tie rule, so "
                  "each pixel gets exactly one fragment per face its ray crosses beyond the "
                  "near plane: never fails.",
    },
    [SWEEP_MINIFICATION] = {
        .name = "minification",
        .what = "a plane facing the camera, textured with white noise (61x61 texels, uniform "
                "0..255, repeated; texel grid on the pixel grid at 1); filter and --ssaa",
        .param_name = "texels per pixel",
        .error_name = "RMS error against the exact box filter of each pixel's texels, levels",
        .extra_name = "theory: s sqrt(mean of sum_t (c_t - a_t)^2), c the samples' and a the "
                      "box's weight of each texel",
        .extra_is_theory = true,
        .threshold = 6,
        .fails = "fails: RMS error > %.0f levels (PSNR < %.1f dB) against the box filter",
        .xlog = true,
        STEPS(mn_k),
        .combos = mn_methods, .n_combos = COUNT(mn_methods), .default_combo = 5,
        SCENE(minification),
        .predict = minification_predict,
    },
};

const char *sweep_name(enum sweep_kind k)
{
    return sweeps[k].name;
}

int sweep_parse(const char *name)
{
    for (int k = 0; k < SWEEP_COUNT; k++)
        if (strcmp(name, sweeps[k].name) == 0)
            return k;
    return -1;
}

/* the result's words, steps and methods from the table */
static void describe(const struct sweep_def *d, enum sweep_kind k, struct sweep_result *r)
{
    memset(r, 0, sizeof *r);
    r->kind = k;
    r->name = d->name;
    r->what = d->what;
    r->param_name = d->param_name;
    r->error_name = d->error_name;
    r->extra_name = d->extra_name;
    r->extra_is_theory = d->extra_is_theory;
    r->threshold = d->threshold;
    snprintf(r->threshold_text, sizeof r->threshold_text, d->fails,
             d->fails_percent ? 100 * d->threshold : d->threshold,
             psnr_db(d->threshold * d->threshold));
    r->holds_until = INFINITY;
    r->xlog = d->xlog, r->ylog = d->ylog, r->reversed = d->reversed;
    r->n_steps = d->n_steps;
    for (int s = 0; s < d->n_steps; s++)
        r->param[s] = d->steps ? d->steps[s] : pow(10, d->log0 + s / d->per_decade);
    r->n_methods = d->axis ? d->axis->n : d->n_combos;
    for (int m = 0; m < r->n_methods; m++)
        snprintf(r->method[m], sizeof r->method[m], "%s",
                 d->axis ? d->axis->names[m] : d->combos[m].name);
    r->default_method = d->axis ? 0 : d->default_combo; /* every axis's default is value 0 */
    for (int m = 0; m < SWEEP_MAX_METHODS; m++)
        r->predicted[m] = NAN;
}

/* the options method m draws with */
static void method_opts(const struct sweep_def *d, int m, struct render_opts *o)
{
    render_opts_default(o);
    o->shade = SHADE_UNLIT;
    if (d->bilinear)
        o->filter = TEX_BILINEAR;
    if (d->axis) {
        render_opts_set(o, d->field, m);
    } else {
        o->filter = d->combos[m].filter;
        o->ssaa = d->combos[m].ssaa;
    }
}

int sweep_run(enum sweep_kind k, int w, int h, struct sweep_result *out, struct err *e)
{
    if ((unsigned)k >= SWEEP_COUNT)
        return err_set(e, "no such sweep");
    const struct sweep_def *d = &sweeps[k];
    if ((d->axis ? d->axis->n : d->n_combos) > SWEEP_MAX_METHODS)
        return err_set(e, "sweep %s: too many methods", d->name);
    describe(d, k, out);
    void *ctx = calloc(1, d->ctx_size);
    if (!ctx)
        return err_set(e, "out of memory");
    struct rig rig;
    int rc = -1;
    if (rig_init(&rig, w, h, e) || d->init(ctx, w, h, e))
        goto out;
    for (int s = d->reference ? -1 : 0; s < out->n_steps; s++) {
        double ref_param = 0;
        struct sweep_frame f;
        if (d->step(ctx, s < 0 ? &ref_param : &out->param[s], &f, e))
            goto out;
        for (int m = 0; m < (s < 0 ? 1 : out->n_methods); m++) {
            struct render_opts o;
            method_opts(d, m, &o);
            if (rig_draw(&rig, f.items, f.n_items, &f.cam, &o, e))
                goto out;
            d->measure(ctx, &rig.fb, &o, s, m, out);
        }
    }
    finish(out);
    if (d->extra_is_theory)
        for (int m = 0; m < out->n_methods; m++)
            predict_from_extra(out, m);
    if (d->predict)
        d->predict(ctx, out);
    else
        snprintf(out->theory, sizeof out->theory, "%s", d->theory);
    rc = 0;
out:
    d->release(ctx);
    free(ctx);
    rig_free(&rig);
    return rc;
}

/* ---- output ---- */

static void param_text(const struct sweep_result *r, double v, char *out, size_t n)
{
    if (r->xlog && (v >= 1e4 || v < 1e-2))
        snprintf(out, n, "%.3g", v);
    else
        snprintf(out, n, "%g", v);
}

void sweep_write_table(const struct sweep_result *r, FILE *f)
{
    fprintf(f, "sweep %s: %s\n", r->name, r->what);
    fprintf(f, "error: %s\n%s\n", r->error_name, r->threshold_text);
    fprintf(f, "%-12s", "param");
    for (int m = 0; m < r->n_methods; m++)
        fprintf(f, " %10s", r->method[m]);
    fputc('\n', f);
    for (int s = 0; s < r->n_steps; s++) {
        char p[32];
        param_text(r, r->param[s], p, sizeof p);
        fprintf(f, "%-12s", p);
        for (int m = 0; m < r->n_methods; m++) {
            char v[32];
            double x = r->error[s][m];
            if (isnan(x))
                snprintf(v, sizeof v, "-");
            else
                snprintf(v, sizeof v, x == floor(x) && fabs(x) < 1e9 ? "%.0f"
                                      : x < 0.01                      ? "%.2e"
                                                                      : "%.3f", x);
            bool failed = r->fail_at[m] >= 0 && s >= r->fail_at[m];
            fprintf(f, " %9s%s", v, failed ? (s == r->fail_at[m] ? "!" : "*") : " ");
        }
        fputc('\n', f);
    }
    fprintf(f, "(! failure point, * failed; param in %s)\n", r->param_name);
    if (r->extra_name) {
        fprintf(f, "%s:\n%-12s", r->extra_name, "param");
        for (int m = 0; m < r->n_methods; m++)
            fprintf(f, " %10s", r->method[m]);
        fputc('\n', f);
        for (int s = 0; s < r->n_steps; s++) {
            char p[32];
            param_text(r, r->param[s], p, sizeof p);
            fprintf(f, "%-12s", p);
            for (int m = 0; m < r->n_methods; m++) {
                double x = r->extra[s][m];
                if (isnan(x))
                    fprintf(f, " %10s", "-");
                else
                    fprintf(f, x == floor(x) && fabs(x) < 1e9 ? " %10.0f" : " %10.3f", x);
            }
            fputc('\n', f);
        }
    }
    long nans = 0;
    for (int s = 0; s < r->n_steps; s++)
        for (int m = 0; m < r->n_methods; m++)
            nans += r->nan[s][m];
    fprintf(f, "NaN/inf depths: %ld in the whole sweep\n", nans);
    for (int m = 0; m < r->n_methods; m++) {
        char p[32] = "never", q[48] = "";
        if (r->fail_at[m] >= 0)
            param_text(r, r->param[r->fail_at[m]], p, sizeof p);
        if (!isnan(r->predicted[m])) {
            char t[32];
            param_text(r, r->predicted[m], t, sizeof t);
            snprintf(q, sizeof q, " (theory: %s)", t);
        }
        fprintf(f, "failure point %-9s %s%s%s\n", r->method[m], p, q,
                m == r->default_method ? "   <- default" : "");
    }
    if (isfinite(r->holds_until)) {
        char t[32];
        param_text(r, r->holds_until, t, sizeof t);
        fprintf(f, "theory: the default holds at least until %s\n", t);
    }
    fprintf(f, "theory: %s\n", r->theory);
}

int sweep_write_csv(const struct sweep_result *r, FILE *f)
{
    fputs("sweep,param,method,error,nan,failed\n", f);
    for (int s = 0; s < r->n_steps; s++)
        for (int m = 0; m < r->n_methods; m++)
            fprintf(f, "%s,%.6g,%s,%.6g,%ld,%d\n", r->name, r->param[s], r->method[m],
                    r->error[s][m], r->nan[s][m], r->fail_at[m] >= 0 && s >= r->fail_at[m]);
    return ferror(f) ? -1 : 0;
}

void sweep_draw(const struct sweep_result *r, struct plot *p)
{
    static const uint32_t cols[SWEEP_MAX_METHODS] = {0x000000, 0xd62728, 0x1f77b4, 0x2ca02c,
                                                     0xff7f0e, 0x9467bd, 0x8c564b, 0x17becf};
    static const enum plot_shape shapes[4] = {PLOT_CIRCLE, PLOT_SQUARE, PLOT_TRIANGLE,
                                              PLOT_DIAMOND};
    double cw = p->char_w, ch = p->char_h;
    double x0 = 8 * cw, x1 = p->w - 18 * cw, y0 = 6 * ch, y1 = p->h - 4.5 * ch;
    double plo = INFINITY, phi = -INFINITY, emax = r->threshold, emin = INFINITY;
    for (int s = 0; s < r->n_steps; s++) {
        plo = fmin(plo, r->param[s]), phi = fmax(phi, r->param[s]);
        for (int m = 0; m < r->n_methods; m++) {
            emax = fmax(emax, r->error[s][m]);
            if (r->extra_name && !isnan(r->extra[s][m]))
                emax = fmax(emax, r->extra[s][m]);
            if (r->error[s][m] > 0)
                emin = fmin(emin, r->error[s][m]);
        }
    }
    /* log y: zero sits at the bottom, a third of the smallest error (counts: at 0.5) */
    double floor_v = !r->ylog ? 0 : r->threshold > 0 ? fmax(1e-3, fmin(emin, r->threshold) / 3)
                                                     : 0.5;
    struct plot_axis ax = {r->reversed ? phi : plo, r->reversed ? plo : phi, r->xlog, x0, x1};
    struct plot_axis ay = {floor_v, emax > 0 ? emax * (r->ylog ? 2 : 1.1) : 1, r->ylog, y1, y0};
    const uint32_t ink = p->svg ? 0x303030 : 0xc0c0c0;
    char title[64], ytitle[200];
    snprintf(title, sizeof title, "sweep %s", r->name);
    snprintf(ytitle, sizeof ytitle, "%s%s", r->error_name,
             r->ylog ? " (log; 0 drawn at the bottom)" : "");
    plot_axes(p, &ax, &ay, r->param_name, ytitle, NULL);
    plot_text(p, (x0 + x1) / 2, ch * 1.2, title, ink, PLOT_MIDDLE, 1.15, true);
    plot_text(p, (x0 + x1) / 2, ch * 2.5, r->what, ink, PLOT_MIDDLE, 0.9, false);
    struct plot_clear clear = {.area = {x0, y0, p->w - cw, y1}};
    double ty = plot_map(&ay, r->threshold > floor_v ? r->threshold : floor_v);
    plot_line(p, x0, ty, x1, ty, 0x808080, 1.5, true);
    double mr = p->svg ? 3.5 : 0.5;
    /* measured: solid lines and markers; theory: dotted, no markers */
    double end_y[SWEEP_MAX_METHODS];
    for (int m = 0; m < r->n_methods; m++) {
        uint32_t c = cols[m % SWEEP_MAX_METHODS];
        if (!p->svg && c == 0)
            c = 0xffffff;
        bool second = false; /* a theory or second measure for this method */
        for (int s = 0; s < r->n_steps && r->extra_name; s++)
            second |= !isnan(r->extra[s][m]);
        for (int pass = second ? 0 : 1; pass < 2; pass++) {
            double lx = 0, ly = 0;
            bool have = false;
            for (int s = 0; s < r->n_steps; s++) {
                double raw = pass == 0 ? r->extra[s][m] : r->error[s][m];
                if (isnan(raw))
                    continue;
                double v = fmax(raw, floor_v);
                double px = plot_map(&ax, r->param[s]), py = plot_map(&ay, v);
                if (have)
                    plot_line(p, lx, ly, px, py, c, pass == 0 ? 1 : m == r->default_method ? 2.5
                                                                                         : 1.5,
                              pass == 0);
                if (pass == 1) {
                    plot_marker(p, px, py, shapes[m % 4], mr, c);
                    plot_keep_clear(&clear, px, py, mr);
                }
                lx = px, ly = py;
                have = true;
            }
            end_y[m] = ly;
        }
    }
    /* names at the right end, stacked so they do not overlap */
    int order[SWEEP_MAX_METHODS];
    for (int m = 0; m < r->n_methods; m++)
        order[m] = m;
    for (int i = 1; i < r->n_methods; i++)
        for (int k = i; k > 0 && end_y[order[k]] < end_y[order[k - 1]]; k--) {
            int t = order[k];
            order[k] = order[k - 1], order[k - 1] = t;
        }
    double last = -INFINITY;
    for (int i = 0; i < r->n_methods; i++) {
        int m = order[i];
        double y = fmax(end_y[m], last + ch);
        last = y;
        uint32_t c = cols[m % SWEEP_MAX_METHODS];
        if (!p->svg && c == 0)
            c = 0xffffff;
        char label[48];
        snprintf(label, sizeof label, "%s%s", r->method[m],
                 m == r->default_method ? " (default)" : "");
        plot_text(p, x1 + cw, y, label, c, PLOT_LEFT, 0.95, m == r->default_method);
    }
    /* failure points, circled and labelled; then the threshold's label */
    for (int m = 0; m < r->n_methods; m++) {
        if (r->fail_at[m] < 0)
            continue;
        uint32_t c = cols[m % SWEEP_MAX_METHODS];
        if (!p->svg && c == 0)
            c = 0xffffff;
        int s = r->fail_at[m];
        double px = plot_map(&ax, r->param[s]);
        double py = plot_map(&ay, fmax(r->error[s][m], floor_v));
        char t[128], pv[32], th[48] = "";
        param_text(r, r->param[s], pv, sizeof pv);
        if (!isnan(r->predicted[m])) {
            char tv[32];
            param_text(r, r->predicted[m], tv, sizeof tv);
            snprintf(th, sizeof th, " (theory %s)", tv);
        }
        snprintf(t, sizeof t, "%s fails at %s%s", r->method[m], pv, th);
        if (p->svg)
            fprintf(p->svg, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"8\" fill=\"none\" "
                            "stroke=\"#%06x\" stroke-width=\"2\"/>\n", px, py, (unsigned)c);
        plot_text_clear(p, &clear, px, py, p->svg ? 8 : 1, t, c, 0.85, true, false);
    }
    plot_text_clear(p, &clear, x0 + (x1 - x0) * 0.35, ty, 0, r->threshold_text, 0x606060, 0.85,
                    false, false);
    if (isfinite(r->holds_until) && r->holds_until >= plo && r->holds_until <= phi) {
        double hx = plot_map(&ax, r->holds_until);
        plot_line(p, hx, y0, hx, y1, 0x808080, 1, true);
        plot_text(p, hx - cw * 0.5, y0 + ch * 2, "theory: the input's float precision runs "
                  "out", 0x606060, PLOT_RIGHT, 0.85, false);
    }
    if (r->extra_name) {
        char t[200];
        snprintf(t, sizeof t, "dotted: %s", r->extra_name);
        plot_text(p, x0 + cw, y0 + ch * 0.8, t, ink, PLOT_LEFT, 0.85, false);
    }
}
