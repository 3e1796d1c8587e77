/* kernel_ref.c: the reference kernel (kernel.h) — every hot loop of the pipeline as plain
 * scalar C, one pixel (one vertex) at a time, with no lanes, no packs and no special cases
 * for speed: this project's tinyrenderer-sized rasterize. It is what the fast kernels are
 * held to: each of them must write exactly its bytes, depths and counts (the tests draw
 * every method with both). Every formula is the scalar one the vector twins copy lane by
 * lane (simd.h), in the same order of operations, so "the same" means the same bits.
 *
 * Per triangle:  ref_raster tests the centre of every pixel of the triangle's box against
 *                the three edge functions (setup.h) and queues each covered pixel;
 *                ref_span draws the queued pixels: for each, the depth from the plane, the
 *                depth test, the varyings in the perspective method, the colour, the write.
 * Per frame:     ref_vertex_run positions vertices (ref_position_run positions alone),
 *                ref_vertex_shade_many lights them
 *                (vertex.c's vertex_shade), ref_sky_rows draws the sky where nothing was. */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "kernel.h"
#include "kernel_common.h"

/* ---- interpolation setup (setup.h, "Back end"), one corner at a time ---- */

/* a tolerance on barycentrics at the snapped corners (setup.h, "Slivers") */
#define REF_SLIVER_EPS (1.0 / 4)

/* barycentric planes l_k of the triangle (px[k], py[k]) at pixel centre (ox, oy) */
struct ref_bary {
    double l[3], dx[3], dy[3];
};

static int ref_planes(const double px[3], const double py[3], double ox, double oy,
                      struct ref_bary *b)
{
    double area = (px[1] - px[0]) * (py[2] - py[0]) - (py[1] - py[0]) * (px[2] - px[0]);
    if (area == 0)
        return 0;
    double inv = 1.0 / area;
    for (int k = 0; k < 3; k++) { /* edge k runs from corner k+1 to corner k+2 */
        double ax = px[(k + 1) % 3], ay = py[(k + 1) % 3];
        double dx = px[(k + 2) % 3] - ax, dy = py[(k + 2) % 3] - ay;
        b->l[k] = (dx * (oy - ay) - dy * (ox - ax)) * inv;
        b->dx[k] = -dy * inv;
        b->dy[k] = dx * inv;
    }
    return 1;
}

/* do the planes stay within [-eps, 1+eps] at the snapped corners? */
static int ref_planes_bounded(const struct setup_tri *t, const struct ref_bary *b)
{
    bool steep = false;
    for (int k = 0; k < 3; k++)
        steep |= !(fabs(b->dx[k]) + fabs(b->dy[k]) <= 100);
    if (!steep) /* (kernel_setup.h says why that suffices) */
        return 1;
    for (int j = 0; j < 3; j++) {
        double dx = (double)t->v[j]->fx / VIEWPORT_SUBPIX_ONE - (t->x0 + 0.5);
        double dy = (double)t->v[j]->fy / VIEWPORT_SUBPIX_ONE - (t->y0 + 0.5);
        for (int k = 0; k < 3; k++) {
            double l = b->l[k] + dx * b->dx[k] + dy * b->dy[k];
            if (!(l >= -REF_SLIVER_EPS && l <= 1 + REF_SLIVER_EPS))
                return 0;
        }
    }
    return 1;
}

/* the plane of sum_k l_k f_k, rounded to float */
static struct setup_plane ref_combine(const struct ref_bary *b, const double f[3])
{
    return (struct setup_plane){(float)(b->l[0] * f[0] + b->l[1] * f[1] + b->l[2] * f[2]),
                                (float)(b->dx[0] * f[0] + b->dx[1] * f[1] + b->dx[2] * f[2]),
                                (float)(b->dy[0] * f[0] + b->dy[1] * f[1] + b->dy[2] * f[2])};
}

static void ref_setup_interp(const struct setup_tri *t, enum depth_mode depth,
                             const struct fb_depth_proj *proj, int affine, int base, int n_var,
                             struct setup_interp *in)
{
    const struct vertex_out *const *v = t->v;
    const double ox = t->x0 + 0.5, oy = t->y0 + 0.5;
    double ux[3], uy[3], sx[3], sy[3], z[3], w[3], rw[3], d[3], f[3];
    for (int k = 0; k < 3; k++) {
        ux[k] = v[k]->win[0], uy[k] = v[k]->win[1];
        sx[k] = (double)v[k]->fx / VIEWPORT_SUBPIX_ONE;
        sy[k] = (double)v[k]->fy / VIEWPORT_SUBPIX_ONE;
        z[k] = v[k]->clip[2], w[k] = v[k]->clip[3], rw[k] = 1.0 / w[k];
    }
    /* unsnapped planes, unless snapping flipped the orientation, made the triangle
     * non-degenerate, or the planes extrapolate over the covered area */
    double uarea = (ux[1] - ux[0]) * (uy[2] - uy[0]) - (uy[1] - uy[0]) * (ux[2] - ux[0]);
    double sarea = (sx[1] - sx[0]) * (sy[2] - sy[0]) - (sy[1] - sy[0]) * (sx[2] - sx[0]);
    struct ref_bary b = {{0}, {0}, {0}};
    if (!(uarea != 0 && (uarea < 0) == (sarea < 0) && ref_planes(ux, uy, ox, oy, &b) &&
          ref_planes_bounded(t, &b)))
        ref_planes(sx, sy, ox, oy, &b);
    for (int k = 0; k < 3; k++) {
        switch (depth) {
        case DEPTH_RZ: d[k] = (w[k] - z[k]) / (2 * w[k]); break;
        case DEPTH_W:
            d[k] = proj->ortho ? 0.5 * (z[k] / w[k] * (proj->far - proj->near) + proj->far +
                                        proj->near)
                               : w[k];
            break;
        default: d[k] = 0.5 * z[k] * rw[k] + 0.5; break; /* viewport_window's depth */
        }
    }
    double lo = d[0] < d[1] ? d[0] : d[1], hi = d[0] > d[1] ? d[0] : d[1];
    lo = d[2] < lo ? d[2] : lo;
    hi = d[2] > hi ? d[2] : hi;
    in->z_lo = (float)lo, in->z_hi = (float)hi;
    if (depth == DEPTH_W) { /* e = (sum l e / w) / (sum l / w) */
        for (int k = 0; k < 3; k++)
            f[k] = d[k] * rw[k];
        in->z = ref_combine(&b, f);
        in->zq = ref_combine(&b, rw);
        in->z_c_lo = 0;
    } else {
        in->z = ref_combine(&b, d);
        in->z_c_lo = (float)((b.l[0] * d[0] + b.l[1] * d[1] + b.l[2] * d[2]) - (double)in->z.c);
    }
    in->q = affine ? (struct setup_plane){1, 0, 0} : ref_combine(&b, rw);
    for (int j = 0; j < n_var; j++) {
        for (int k = 0; k < 3; k++)
            f[k] = (double)v[k]->all[base + j] * (affine ? 1.0 : rw[k]);
        struct setup_plane p = ref_combine(&b, f);
        in->a_c[j] = p.c, in->a_dx[j] = p.dx, in->a_dy[j] = p.dy;
    }
}

/* ---- coverage: every centre of the box against the three edges ---- */

static void ref_raster(const struct setup_tri *t, struct raster_rect r, struct span_ctx *s)
{
    struct raster_rect b;
    if (!raster_clip_box(t, r, &b))
        return;
    for (int y = b.y0; y <= b.y1; y++)
        for (int x = b.x0; x <= b.x1; x++)
            if (raster_edge_at(t, 0, x, y) >= 0 && raster_edge_at(t, 1, x, y) >= 0 &&
                raster_edge_at(t, 2, x, y) >= 0)
                span_draw(s, y, x, x);
}

/* ---- one pixel ---- */

/* pixel (x, y) of the current triangle, in every method */
static void ref_pixel(struct span_ctx *s, int x, int y)
{
    const struct setup_interp *in = &s->in;
    const struct setup_tri *t = s->tri;
    struct fb *fb = s->fb;
    const size_t i = (size_t)y * (size_t)fb->w + (size_t)x;
    const float X = (float)(x - t->x0), Y = (float)(y - t->y0);
    const float z = kernel_depth_at(s, X, Y); /* the plane, clamped to the corners' range */
    s->tested++;
    if (fb->overdraw)
        fb->overdraw[i]++;
    if (!fb_depth_passes(s->depth, z, fb->depth[i]))
        return;
    fb->depth[i] = z;
    s->shaded++;
    if (s->mode == SHADE_WIRE)
        return;
    /* the varyings in the perspective method */
    const int n_var = kernel_n_var(s, s->mode);
    float var[VARY_MAX] = {0};
    const float rq = kernel_varyings_at(s, x, y, X, Y, n_var, var);
    /* the colour: the texture's level of detail from the planes (trilinear), then shade.h */
    const struct shade_ctx *sc = s->shade;
    float lambda = 0, c[3];
    if (s->st->tex && sc->filter == TEX_TRILINEAR)
        lambda = texture_lod(s->st->tex, (in->a_dx[0] - var[0] * in->q.dx) * rq,
                             (in->a_dx[1] - var[1] * in->q.dx) * rq,
                             (in->a_dy[0] - var[0] * in->q.dy) * rq,
                             (in->a_dy[1] - var[1] * in->q.dy) * rq);
    shade_fragment_lod(sc, s->mode, s->st, var, lambda, c);
    uint8_t *p = fb->rgb + 3 * i;
    p[0] = pixel_quantize(c[0]), p[1] = pixel_quantize(c[1]), p[2] = pixel_quantize(c[2]);
}

/* every queued pixel of the triangle (the same function for every method) */
static void ref_span(struct span_ctx *s)
{
    if (!s->in_ready) {
        ref_setup_interp(s->tri, s->depth, &s->fb->proj, s->persp == PERSP_AFFINE,
                         s->mode == SHADE_WIRE ? VARY_BASE : kernel_vary_base(s),
                         kernel_n_var(s, s->mode), &s->in);
        s->in_ready = true;
        if (s->hit)
            s->hit[s->tri_index] = 1;
    }
    for (int r = 0; r < s->n_runs; r++)
        for (int x = s->runs[r].x0; x <= s->runs[r].x1; x++) {
            if (s->tri->rich)
                kernel_rich_pixel(s, x, s->runs[r].y);
            else
                ref_pixel(s, x, s->runs[r].y);
        }
}

/* ---- vertices ---- */

static void ref_vertex_run(const struct mesh *m, const struct vertex_uniforms *u,
                           struct vertex_out *out, uint32_t i0, uint32_t i1)
{
    for (uint32_t i = i0; i < i1; i++) {
        const float *p = m->verts[i].pos;
        const double x = p[0], y = p[1], z = p[2];
        struct vertex_out *o = &out[i];
        for (int r = 0; r < 4; r++) /* m4_mul_v4's sums, in its order */
            o->clip[r] = u->mvp.m[r][0] * x + u->mvp.m[r][1] * y + u->mvp.m[r][2] * z +
                         u->mvp.m[r][3] * 1.0;
        o->outcode = vertex_outcode(o->clip, u->guard_x, u->guard_y);
        o->projected = 0;
        o->shaded = VERTEX_UNSHADED;
        if (!(o->outcode & VERTEX_NEEDS_CLIP))
            vertex_project(o, u->fb_w, u->fb_h);
    }
}

static void ref_position_run(const float *xyz, size_t stride, const struct vertex_uniforms *u,
                             struct vertex_pos *out, uint32_t p0, uint32_t p1)
{
    for (uint32_t i = p0; i < p1; i++) {
        const float *q = (const float *)((const char *)xyz + (size_t)i * stride);
        const double x = q[0], y = q[1], z = q[2];
        double clip[4];
        for (int r = 0; r < 4; r++) /* m4_mul_v4's sums, in its order */
            clip[r] = u->mvp.m[r][0] * x + u->mvp.m[r][1] * y + u->mvp.m[r][2] * z +
                      u->mvp.m[r][3] * 1.0;
        struct vertex_pos *o = &out[i];
        o->outcode = vertex_outcode(clip, u->guard_x, u->guard_y);
        o->fx = o->fy = 0;
        o->z = 0;
        if (!(o->outcode & VERTEX_NEEDS_CLIP)) {
            double win[3];
            viewport_window(clip, u->fb_w, u->fb_h, win);
            o->fx = (int32_t)viewport_snap(win[0]);
            o->fy = (int32_t)viewport_snap(win[1]);
            o->z = (float)win[2];
        }
    }
}

static void ref_vertex_shade_many(const struct mesh *m, const struct vertex_uniforms *u,
                                  const uint32_t *idx, struct vertex_out *const *out, uint32_t n)
{
    for (uint32_t k = 0; k < n; k++)
        vertex_shade(m, u, idx[k], out[k]);
}

/* ---- the sky ---- */

/* bilinear sample of face `face` of level l at face coordinates (u, v) in [-1, 1], in float */
static void ref_sky_sample(const struct skybox_level *l, int face, float u, float v,
                           float rgb_out[3])
{
    const float half = 0.5f * l->n;
    float x = (u + 1) * half - 0.5f, y = (v + 1) * half - 0.5f;
    int i0 = (int)x, j0 = (int)y; /* floor: x, y >= -0.5 here, and finite */
    i0 -= (float)i0 > x, j0 -= (float)j0 > y;
    i0 = i0 < -1 ? -1 : i0 > l->n - 1 ? l->n - 1 : i0;
    j0 = j0 < -1 ? -1 : j0 > l->n - 1 ? l->n - 1 : j0;
    float ax = x - (float)i0, ay = y - (float)j0;
    ax = ax < 0 ? 0 : ax > 1 ? 1 : ax;
    ay = ay < 0 ? 0 : ay > 1 ? 1 : ay;
    const int row = l->n + 2; /* texels r g b 0, the faces one after another */
    const uint8_t *p00 = l->rgb[0] + 4 * ((size_t)face * row * row + (size_t)(j0 + 1) * row +
                                          (size_t)(i0 + 1));
    const uint8_t *p10 = p00 + 4, *p01 = p00 + 4 * row, *p11 = p01 + 4;
    for (int c = 0; c < 3; c++) {
        float a = (float)p00[c] + ax * ((float)p10[c] - (float)p00[c]);
        float b = (float)p01[c] + ax * ((float)p11[c] - (float)p01[c]);
        rgb_out[c] = (a + ay * (b - a)) * (1.0f / 255.0f);
    }
}

static void ref_sky_rows(const struct skybox *s, const struct camera *cam, struct fb *fb, int y0,
                         int y1)
{
    if (s->n_levels == 0)
        return;
    vec3 f = v3_norm(v3_sub(cam->target, cam->eye));
    vec3 r = v3_norm(v3_cross(f, cam->up));
    vec3 u = v3_cross(r, f);
    double fov = cam->fov_deg > 0 ? cam->fov_deg : 50;
    double ty = tan(fov * (M_PI / 360.0)), tx = ty * fb_aspect(fb);
    /* the level whose texel matches a pixel: a face spans 2 (in tan units) over n texels */
    double texels_per_px = (2 * ty / fb->h) / (2.0 / s->level[0].n);
    double lod = texels_per_px > 1 ? log2(texels_per_px) : 0;
    int level = (int)floor(lod);
    float frac = (float)(lod - level);
    if (level >= s->n_levels - 1) {
        level = s->n_levels - 1;
        frac = 0;
    }
    const struct skybox_level *l0 = &s->level[level], *l1 = &s->level[level + (frac > 0)];
    y0 = y0 < 0 ? 0 : y0;
    y1 = y1 > fb->h ? fb->h : y1;
    const float rx = (float)(r.x * tx), ry = (float)(r.y * tx), rz = (float)(r.z * tx);
    const float sx = 2.0f / fb->w;
    for (int y = y0; y < y1; y++) {
        double ny = 1 - 2 * (y + 0.5) / fb->h;
        vec3 row = v3_add(f, v3_scale(u, ny * ty));
        const float ox = (float)row.x, oy = (float)row.y, oz = (float)row.z;
        for (int x = 0; x < fb->w; x++) {
            size_t i = (size_t)y * fb->w + x;
            if (fb_covered(fb, i))
                continue;
            /* the direction, then the GL cube-map table: the face of the major axis */
            float nx = ((float)x + 0.5f) * sx - 1;
            float d0 = ox + nx * rx, d1 = oy + nx * ry, d2 = oz + nx * rz;
            float ax = fabsf(d0), ay = fabsf(d1), az = fabsf(d2);
            bool isx = ax >= ay && ax >= az, isy = !isx && ay >= az;
            float ma = isx ? ax : isy ? ay : az;
            float sc = isx ? (d0 > 0 ? -d2 : d2) : isy ? d0 : (d2 > 0 ? d0 : -d0);
            float tc = isy ? (d1 > 0 ? d2 : -d2) : -d1;
            int face = isx ? (d0 > 0 ? 0 : 1) : isy ? (d1 > 0 ? 2 : 3) : (d2 > 0 ? 4 : 5);
            bool seen = ma > 0; /* else black */
            float im = 1.0f / (seen ? ma : 1);
            float fu = seen ? sc * im : 0, fv = seen ? tc * im : 0;
            float c[3];
            ref_sky_sample(l0, face, fu, fv, c);
            if (frac > 0) { /* trilinear: blend with the next coarser level */
                float c2[3];
                ref_sky_sample(l1, face, fu, fv, c2);
                for (int k = 0; k < 3; k++)
                    c[k] += frac * (c2[k] - c[k]);
            }
            uint8_t *p = fb->rgb + 3 * i;
            for (int k = 0; k < 3; k++)
                p[k] = pixel_quantize(seen ? c[k] : 0);
        }
    }
}

const struct kernel kernel_ref = {
    .name = "ref",
    .lanes = 1,
    .span_one_pixel = {ref_span, ref_span, ref_span, ref_span, ref_span},
    .span_packs_z = {{ref_span, ref_span, ref_span}, {ref_span, ref_span, ref_span},
                     {ref_span, ref_span, ref_span}, {ref_span, ref_span, ref_span},
                     {ref_span, ref_span, ref_span}},
    .span_packs = {ref_span, ref_span, ref_span, ref_span, ref_span},
    .span_runs = {ref_span, ref_span, ref_span, ref_span, ref_span},
    .span_rich = {ref_span, ref_span, ref_span, ref_span, ref_span},
    .raster = {ref_raster, ref_raster, ref_raster},
    .vertex_run = ref_vertex_run,
    .position_run = ref_position_run,
    .vertex_shade_many = ref_vertex_shade_many,
    .sky_rows = ref_sky_rows,
};
_Static_assert(SHADE_COUNT == 5 && TEX_FILTER_COUNT == 3 && RASTER_COUNT == 3,
               "every method has its entry in the table above");
