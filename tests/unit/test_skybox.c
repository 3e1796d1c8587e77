/* test_skybox.c: cube-map orientation, seams and the sky behind the geometry. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "kernel.h"
#include "skybox.h"
#include "test.h"

/* a sky whose colour encodes the direction: faces are flat colours, so the face a direction
 * lands on is visible in the sample */
static int face_colour_sky(struct skybox *s, char paths[6][64])
{
    static const uint8_t col[6][3] = {{255, 0, 0}, {0, 255, 0},   {0, 0, 255},
                                      {255, 255, 0}, {0, 255, 255}, {255, 0, 255}};
    const char *pp[6];
    for (int f = 0; f < 6; f++) {
        snprintf(paths[f], 64, "build/tests/sky_face%d.ppm", f);
        FILE *out = fopen(paths[f], "wb");
        if (!out)
            return -1;
        fprintf(out, "P6\n8 8\n255\n");
        for (int i = 0; i < 64; i++)
            fwrite(col[f], 1, 3, out);
        fclose(out);
        pp[f] = paths[f];
    }
    return skybox_load(s, pp, NULL, NULL);
}

TEST(skybox_direction_picks_gl_face)
{
    struct skybox s;
    char paths[6][64];
    REQUIRE(face_colour_sky(&s, paths) == 0);
    const vec3 dirs[6] = {{1, 0.1, 0.2}, {-1, 0.2, -0.1}, {0.1, 1, 0.3},
                          {-0.2, -1, 0.1}, {0.3, -0.1, 1}, {0.2, 0.1, -1}};
    const float want[6][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {0, 1, 1}, {1, 0, 1}};
    for (int f = 0; f < 6; f++) {
        float c[3];
        skybox_sample(&s, 0, dirs[f], c);
        for (int k = 0; k < 3; k++)
            CHECK_NEAR(c[k], want[f][k], 1e-6);
    }
    skybox_free(&s);
}

TEST(skybox_no_seams_across_shared_cubemap_edges)
{
    /* the shared cube map: sample pairs of directions a hair apart on either side of each of
     * the 12 cube edges; bilinear through the borders must make them nearly equal (a
     * clamped sampler shows jumps of tens of levels there on this image) */
    const char *dir = test_models_dir();
    if (!dir) {
        test_skip(t, "no ../shared/models");
        return;
    }
    static const char *names[6] = {"posx", "negx", "posy", "negy", "posz", "negz"};
    char paths[6][512];
    const char *pp[6];
    for (int f = 0; f < 6; f++) {
        snprintf(paths[f], sizeof paths[f], "%s/skybox/%s.jpg", dir, names[f]);
        pp[f] = paths[f];
    }
    struct skybox s;
    REQUIRE(skybox_load(&s, pp, NULL, NULL) == 0);
    double worst = 0;
    for (int a = 0; a < 3; a++)          /* the axis the edge runs along */
        for (int sgn = 0; sgn < 4; sgn++) /* which of its 4 edges */
            for (int k = 1; k < 40; k++) {
                double along = -1 + 2.0 * k / 40, e = 1e-6;
                double u = sgn & 1 ? 1 : -1, w = sgn & 2 ? 1 : -1;
                double c1[3], c2[3];
                /* points near the edge where components (a+1) and (a+2) are u and w */
                c1[a] = along, c1[(a + 1) % 3] = u * (1 + e), c1[(a + 2) % 3] = w;
                c2[a] = along, c2[(a + 1) % 3] = u, c2[(a + 2) % 3] = w * (1 + e);
                for (int lvl = 0; lvl < s.n_levels && s.level[lvl].n >= 64; lvl++) {
                    float x[3], y[3];
                    skybox_sample(&s, lvl, v3(c1[0], c1[1], c1[2]), x);
                    skybox_sample(&s, lvl, v3(c2[0], c2[1], c2[2]), y);
                    for (int ch = 0; ch < 3; ch++)
                        worst = fmax(worst, fabs(x[ch] - y[ch]) * 255);
                }
            }
    /* the faces' own edge texels differ by up to ~10 levels (readme.txt); blending through
     * the borders makes the two sides meet: measured 0.0 on 512..128 faces, 2.4 at 64 near
     * the corners (faces of 8 texels and less, only used for framebuffers a few pixels
     * tall, drift up to 17 there) */
    if (worst > 3)
        fprintf(stderr, "    worst seam difference %.1f levels\n", worst);
    CHECK(worst <= 3);
    skybox_free(&s);
}

/* the sky over every row of fb, drawn by kernel set isa's kernel for whole stages */
static void sky_draw(enum kernel_isa isa, const struct skybox *s, const struct camera *c,
                     struct fb *fb)
{
    kernel_set(isa)->by_size[SPAN_SIZE_LARGE]->sky_rows(s, c, fb, 0, fb->h);
}

TEST(skybox_fills_only_empty_pixels)
{
    struct skybox s;
    char paths[6][64];
    REQUIRE(face_colour_sky(&s, paths) == 0);
    struct fb fb;
    REQUIRE(fb_init(&fb, 8, 4, false, NULL) == 0);
    const uint8_t grey[3] = {7, 7, 7};
    fb_clear(&fb, grey);
    fb.depth[0] = 0.5f; /* something drawn at pixel 0 */
    struct camera c;
    camera_default(&c); /* looks down -Z: the negz face (magenta) */
    sky_draw(KERNEL_AUTO, &s, &c, &fb);
    CHECK_EQ_INT(fb.rgb[0], 7);
    CHECK_EQ_INT(fb.rgb[3 * 5 + 0], 255);
    CHECK_EQ_INT(fb.rgb[3 * 5 + 1], 0);
    CHECK_EQ_INT(fb.rgb[3 * 5 + 2], 255);
    fb_free(&fb);
    skybox_free(&s);
}

TEST(sky_draw_matches_the_double_reference)
{
    /* every drawn pixel against skybox_sample (double precision) along the pixel centre's
     * ray, on a procedural sky, a framebuffer whose width is no multiple of four or eight
     * (the last group of lanes is partial), some pixels covered, cameras that see every
     * face, every kernel (kernel.h: the reference, the baseline, AVX2 with eight and four
     * lanes and gathers): within one level (float against double); a lane that took
     * another lane's face or texel would be tens of levels off. And every fast kernel
     * writes exactly the reference kernel's bytes. */
    struct skybox s;
    REQUIRE(skybox_procedural(&s, v3(0.3, 0.5, -1), NULL) == 0);
    struct fb fb;
    const int w = 37, h = 23;
    REQUIRE(fb_init(&fb, w, h, false, NULL) == 0);
    const vec3 eyes[4] = {{0, 0, 3}, {0.1, 3, 0.2}, {-2, -1, -2}, {3, 0.5, -0.4}};
    int worst = 0, drawn = 0, kept = 0, copies = 0, unlike_ref = 0;
    static const enum kernel_isa isas[] = {KERNEL_REF, KERNEL_SSE2, KERNEL_AVX2_8, KERNEL_AVX2_4};
    uint8_t *ref = malloc(4 * 3 * (size_t)w * h);
    REQUIRE(ref);
    for (int ki = 0; ki < 4; ki++) {
        if (!kernel_set(isas[ki]))
            continue;
        copies++;
        for (int e = 0; e < 4; e++) {
            const uint8_t grey[3] = {7, 7, 7};
            fb_clear(&fb, grey);
            for (int i = 0; i < w * h; i += 5)
                fb.depth[i] = 0.5f; /* covered: the sky must leave these */
            struct camera c;
            camera_default(&c);
            c.eye = eyes[e];
            c.fov_deg = 120;
            sky_draw(isas[ki], &s, &c, &fb);
            uint8_t *want_rgb = ref + (size_t)e * 3 * w * h;
            if (ki == 0)
                memcpy(want_rgb, fb.rgb, 3 * (size_t)w * h);
            else
                unlike_ref += memcmp(want_rgb, fb.rgb, 3 * (size_t)w * h) != 0;
            vec3 f = v3_norm(v3_sub(c.target, c.eye)), r = v3_norm(v3_cross(f, c.up));
            vec3 u = v3_cross(r, f);
            double ty = tan(c.fov_deg * M_PI / 360), tx = ty * fb_aspect(&fb);
            double tpp = (2 * ty / h) / (2.0 / s.level[0].n), lod = tpp > 1 ? log2(tpp) : 0;
            int lvl = (int)floor(lod);
            double frac = lod - lvl;
            for (int y = 0; y < h; y++)
                for (int x = 0; x < w; x++) {
                    int i = y * w + x;
                    if (i % 5 == 0) {
                        kept += fb.rgb[3 * i] == 7 && fb.rgb[3 * i + 1] == 7 &&
                                fb.rgb[3 * i + 2] == 7;
                        continue;
                    }
                    double nx = 2 * (x + 0.5) / w - 1, ny = 1 - 2 * (y + 0.5) / h;
                    vec3 d = v3_add(f, v3_add(v3_scale(r, nx * tx), v3_scale(u, ny * ty)));
                    float a[3], b[3];
                    skybox_sample(&s, lvl, d, a);
                    skybox_sample(&s, lvl + (frac > 0), d, b);
                    for (int k = 0; k < 3; k++) {
                        int want = pixel_quantize((float)(a[k] + frac * (b[k] - a[k])));
                        int diff = abs(want - fb.rgb[3 * i + k]);
                        worst = diff > worst ? diff : worst;
                    }
                    drawn++;
                }
        }
    }
    free(ref);
    CHECK_EQ_INT(unlike_ref, 0);
    CHECK(copies >= 2);
    CHECK_EQ_INT(drawn, copies * 4 * (w * h - (w * h + 4) / 5));
    CHECK_EQ_INT(kept, copies * 4 * ((w * h + 4) / 5));
    if (worst > 1)
        fprintf(stderr, "    worst difference %d levels\n", worst);
    CHECK(worst <= 1);
    fb_free(&fb);
    skybox_free(&s);
}
