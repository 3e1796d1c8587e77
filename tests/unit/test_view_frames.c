/* test_view_frames.c: the viewer's quality floor (view_frames.h): a budgeted pan whose
 * budget alone leaves ghosts is held to VIEW_MIN_DB, frame by frame, as an independent
 * decoder of the bytes sees it. */
#include <math.h>
#include <string.h>

#include "decode.h"
#include "encode.h"
#include "psnr.h"
#include "test.h"
#include "view_frames.h"

enum { C = 40, R = 12, B = 600 };

/* A smooth picture with detail, panned by `shift` pixels. */
static void picture(uint8_t *rgb, int shift)
{
    for (int y = 0; y < 2 * R; y++)
        for (int x = 0; x < C; x++) {
            int u = x + shift;
            uint8_t *p = rgb + ((size_t)y * C + x) * 3;
            p[0] = (uint8_t)((u * 6) & 255);
            p[1] = (uint8_t)(y * 10);
            p[2] = (uint8_t)(((u / 4 + y / 3) % 2) * 200);
        }
}

/* The pan through view_frames_encode with a budget of B bytes; the worst frame's PSNR as a
 * second decoder sees the bytes, and the largest number of tries. */
static double worst_pan(struct test *t, bool floor, int *max_tries, size_t *max_bytes)
{
    static uint8_t rgb[C * 2 * R * 3];
    struct fb fb = {.w = C, .h = 2 * R, .rgb = rgb, .pixel_aspect = 1};
    struct view_frames f;
    struct encode_screen s;
    struct decode_state d;
    double worst = INFINITY;
    view_frames_init(&f, true, 0);
    view_frames_resize(&f, C, R, cell_geom(CELL_HALF));
    if (encode_screen_init(&s, C, R, NULL) || decode_init(&d, C, R, cell_geom(CELL_HALF), NULL)) {
        CHECK(!"init");
        return 0;
    }
    CHECK(f.dec_ok);
    *max_tries = 0;
    *max_bytes = 0;
    for (int k = 0; k < 20; k++) {
        picture(rgb, 3 * k);
        struct encode_opts o = {.mode = PALETTE_TRUECOLOR, .diff = true, .budget = B};
        struct encode_stats st;
        size_t n;
        int tries;
        const char *out = view_frames_encode(&f, &s, &fb, &o, floor, &n, &st, &tries);
        CHECK_EQ_INT(o.budget, B); /* the caller's options are left as they were */
        struct err e;
        if (decode_apply(&d, out, n, &e)) {
            CHECK(!"decodes");
            break;
        }
        size_t npx = sizeof rgb;
        double db = psnr_db(psnr_sse(d.rgb, rgb, npx) / (double)npx);
        /* the viewer's own decoded screen is the same as ours (a frame taken back left no
         * trace in it) */
        CHECK(memcmp(d.rgb, f.dec.rgb, npx) == 0);
        CHECK(isinf(db) ? isinf(f.db) : fabs(db - f.db) < 1e-9);
        worst = db < worst ? db : worst;
        *max_tries = tries > *max_tries ? tries : *max_tries;
        *max_bytes = n > *max_bytes ? n : *max_bytes;
    }
    decode_free(&d);
    encode_screen_free(&s);
    view_frames_free(&f);
    return worst;
}

TEST(quality_floor_holds_every_budgeted_frame_above_its_bar)
{
    int tries;
    size_t bytes;
    double off = worst_pan(t, false, &tries, &bytes);
    CHECK(off < 30);         /* the budget alone smears the pan */
    CHECK_EQ_INT(tries, 1);
    CHECK(bytes <= B);
    double on = worst_pan(t, true, &tries, &bytes);
    CHECK(on >= VIEW_MIN_DB); /* every frame on the screen is within the bar */
    CHECK(tries > 1);         /* by spending more than the budget on some */
    CHECK(bytes > B);
    printf("    worst frame: %.2f dB with the budget alone, %.2f dB with the floor\n", off, on);
}
