/* test_sweep.c: every stress sweep at a small size — the default holds where theory says it
 * must, and the naive method fails where theory puts its failure point (the sweeps' exact
 * answers are ray casts, box integrals and counts, computed apart from the renderer). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "render_opts.h"
#include "sweep.h"
#include "test.h"

#define W 64
#define H 48

static struct sweep_result *run_at(struct test *t, enum sweep_kind k, int w, int h)
{
    struct sweep_result *r = malloc(sizeof *r);
    struct err e = {""};
    if (!r || sweep_run(k, w, h, r, &e)) {
        test_fail(t, __FILE__, __LINE__, "sweep %s: %s", sweep_name(k), e.msg);
        free(r);
        return NULL;
    }
    return r;
}

static struct sweep_result *run(struct test *t, enum sweep_kind k)
{
    return run_at(t, k, W, H);
}

/* the index of the first step whose param is at or past v (params increasing) */
static int first_step_at(const struct sweep_result *r, double v)
{
    for (int s = 0; s < r->n_steps; s++)
        if (r->param[s] >= v)
            return s;
    return -1;
}

static long total_nan(const struct sweep_result *r)
{
    long n = 0;
    for (int s = 0; s < r->n_steps; s++)
        for (int m = 0; m < r->n_methods; m++)
            n += r->nan[s][m];
    return n;
}

TEST(grazing_affine_fails_as_theory_says_and_correct_never)
{
    /* a terminal's size: at 1 degree the ground is a few rows of pixels */
    struct sweep_result *r = run_at(t, SWEEP_GRAZING, 160, 96);
    REQUIRE(r);
    CHECK_EQ_INT(r->n_methods, PERSP_COUNT);
    CHECK_EQ_INT(r->default_method, PERSP_CORRECT);
    for (int s = 0; s < r->n_steps; s++) {
        /* the default stays within its threshold over the whole range: ~exact */
        CHECK(r->error[s][PERSP_CORRECT] < 0.05);
        /* affine, measured, is what interpolating uv linearly between the projected
         * corners predicts */
        CHECK_NEAR(r->error[s][PERSP_AFFINE], r->extra[s][PERSP_AFFINE],
                   0.05 + 0.02 * r->extra[s][PERSP_AFFINE]);
        /* affine's error grows monotonically as the angle flattens (90 deg: exact) */
        if (s == 0)
            CHECK(r->error[s][PERSP_AFFINE] < 0.05);
        else
            CHECK(r->error[s][PERSP_AFFINE] > r->error[s - 1][PERSP_AFFINE]);
    }
    CHECK_EQ_INT(r->fail_at[PERSP_CORRECT], -1);
    CHECK(r->fail_at[PERSP_AFFINE] >= 0);
    CHECK(r->param[r->fail_at[PERSP_AFFINE]] == r->predicted[PERSP_AFFINE]);
    /* affine first, then spans, longer spans sooner */
    CHECK(r->fail_at[PERSP_SPAN32] > r->fail_at[PERSP_AFFINE]);
    CHECK(r->fail_at[PERSP_SPAN16] >= r->fail_at[PERSP_SPAN32]);
    CHECK(r->fail_at[PERSP_SPAN8] > r->fail_at[PERSP_SPAN16]);
    CHECK_EQ_INT(total_nan(r), 0);
    free(r);
}

TEST(depthrange_z16_fails_at_the_ratio_16_bits_allow)
{
    /* closed form: a window-depth step q spans q D^2 (ratio - 1) / far at distance D; the
     * quads (gap g) tie in more than 1% of the pixels from ratio = 1 + far g / (0.99 q D^2).
     * D = 20, g = 0.01, far = 100: z16 (q = 1/65535) at 166.5, float z (q = 2^-24) at 42368 */
    const double k = 100 * 0.01 / (0.99 * 20 * 20);
    struct sweep_result *r = run(t, SWEEP_DEPTHRANGE);
    REQUIRE(r);
    int z16 = first_step_at(r, 1 + k * 65535), z = first_step_at(r, 1 + k * 16777216.0);
    REQUIRE(z16 > 0 && z > z16);
    CHECK_EQ_INT(r->fail_at[DEPTH_Z16], z16);
    CHECK(r->error[z16 - 1][DEPTH_Z16] == 0); /* one step before: not a single tie */
    /* z16 rounds every pixel: its tie fraction follows the per-pixel theory step by step */
    for (int s = 0; s < r->n_steps; s++)
        CHECK_NEAR(r->error[s][DEPTH_Z16], r->extra[s][DEPTH_Z16], 0.04);
    /* the default, float z (the order: z16 first, then z; w and rz never in
     * 10..1e7): its plane is evaluated as a float base plus a small part, rounded once
     * (setup.h), so it too ties pixel by pixel as the theory says, and fails where the
     * closed form puts it */
    CHECK_EQ_INT(r->fail_at[DEPTH_Z], z);
    for (int s = 0; s < r->n_steps; s++)
        CHECK_NEAR(r->error[s][DEPTH_Z], r->extra[s][DEPTH_Z], 0.04);
    for (int s = 0; s < r->n_steps; s++) {
        CHECK_EQ_INT(r->error[s][DEPTH_W], 0);
        CHECK_EQ_INT(r->error[s][DEPTH_RZ], 0);
        CHECK_EQ_INT(r->extra[s][DEPTH_W], 0);
        CHECK_EQ_INT(r->extra[s][DEPTH_RZ], 0);
    }
    CHECK_EQ_INT(total_nan(r), 0);
    free(r);
}

TEST(magnitude_no_cracks_at_any_distance)
{
    struct sweep_result *r = run(t, SWEEP_MAGNITUDE);
    REQUIRE(r);
    CHECK(isfinite(r->holds_until) && r->holds_until > 1e4);
    for (int m = 0; m < r->n_methods; m++) {
        CHECK_EQ_INT(r->fail_at[m], -1); /* crack-free over the whole range, 1 .. 1e7 */
        for (int s = 0; s < r->n_steps; s++)
            if (r->param[s] <= 100) /* float steps far below the 1/256-pixel snap */
                CHECK_EQ_INT(r->extra[s][m], 0);
    }
    /* jitter grows once the input's float steps pass a pixel */
    CHECK(r->extra[r->n_steps - 1][0] > 100);
    CHECK_EQ_INT(total_nan(r), 0);
    free(r);
}

TEST(sliver_fans_cover_every_pixel_once_at_any_aspect)
{
    struct sweep_result *r = run(t, SWEEP_SLIVER);
    REQUIRE(r);
    CHECK(r->param[r->n_steps - 1] >= 1e7);
    for (int m = 0; m < r->n_methods; m++) {
        CHECK_EQ_INT(r->fail_at[m], -1);
        for (int s = 0; s < r->n_steps; s++)
            CHECK_EQ_INT(r->extra[s][m], 0); /* no uv off inside */
    }
    CHECK_EQ_INT(total_nan(r), 0);
    free(r);
}

TEST(nearplane_flying_through_a_box_draws_each_face_once)
{
    struct sweep_result *r = run(t, SWEEP_NEARPLANE);
    REQUIRE(r);
    for (int m = 0; m < r->n_methods; m++)
        CHECK_EQ_INT(r->fail_at[m], -1);
    CHECK_EQ_INT(total_nan(r), 0);
    free(r);
}

TEST(minification_follows_the_white_noise_theory)
{
    struct sweep_result *r = run(t, SWEEP_MINIFICATION);
    REQUIRE(r);
    enum { TRI = 5 }; /* trilinear, the default: measured only (no closed form) */
    for (int s = 0; s < r->n_steps; s++)
        for (int m = 0; m < TRI; m++) /* measured RMS = predicted, within noise */
            CHECK_NEAR(r->error[s][m], r->extra[s][m], 0.6 + 0.06 * r->extra[s][m]);
    for (int m = 0; m < TRI; m++)
        CHECK(r->fail_at[m] >= 0 && r->param[r->fail_at[m]] == r->predicted[m]);
    /* nearest is exact at 1 texel a pixel and fails at the first step past it; among the
     * sample-based methods 8x8 samples hold out longest */
    CHECK(r->error[0][0] < 0.5);
    CHECK_EQ_INT(r->fail_at[0], 1);
    for (int m = 1; m < TRI; m++)
        CHECK(r->fail_at[4] >= r->fail_at[m]);
    CHECK(r->fail_at[4] > 1);
    /* trilinear is exact at 1, and once a pixel covers 12 or more texels it stays within the
     * threshold and converges to the box filter as the footprint grows (every sample-based
     * method keeps an error that does not shrink: nearest ~74, ssaa8 ~9 levels) */
    CHECK_EQ_INT(r->default_method, TRI);
    CHECK(r->error[0][TRI] < 0.5);
    for (int s = 0; s < r->n_steps; s++) {
        if (r->param[s] < 12)
            continue;
        CHECK(r->error[s][TRI] < r->threshold);
        CHECK(r->error[s][TRI] < r->error[s][4]);
        if (s + 1 < r->n_steps)
            CHECK(r->error[s + 1][TRI] < r->error[s][TRI]);
    }
    CHECK_EQ_INT(total_nan(r), 0);
    free(r);
}

TEST(sweep_csv_marks_failure_from_the_failure_point_on)
{
    struct sweep_result *r = run(t, SWEEP_DEPTHRANGE);
    REQUIRE(r);
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    REQUIRE(f);
    CHECK(sweep_write_csv(r, f) == 0);
    fclose(f);
    CHECK(strncmp(buf, "sweep,param,method,error,nan,failed\n", 36) == 0);
    int rows = 0, z16_failed = 0;
    for (char *l = strchr(buf, '\n'); l && l[1]; l = strchr(l + 1, '\n')) {
        rows++;
        double param;
        char method[16];
        int failed;
        if (sscanf(l + 1, "depthrange,%lf,%15[^,],%*f,%*d,%d", &param, method, &failed) == 3 &&
            strcmp(method, "z16") == 0) {
            CHECK_EQ_INT(failed, param >= r->param[r->fail_at[DEPTH_Z16]]);
            z16_failed += failed;
        }
    }
    CHECK_EQ_INT(rows, r->n_steps * r->n_methods);
    CHECK_EQ_INT(z16_failed, r->n_steps - r->fail_at[DEPTH_Z16]);
    free(buf);
    free(r);
}
