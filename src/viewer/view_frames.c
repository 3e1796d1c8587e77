/* view_frames.c: the decoded screen, the quality floor and the frame log (view_frames.h). */
#include "view_frames.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "image.h"
#include "psnr.h"

void view_frames_init(struct view_frames *f, bool floor, double t0)
{
    *f = (struct view_frames){0};
    f->t0 = t0;
    f->db = INFINITY;
    const char *log = getenv("RASTTY_FRAME_LOG");
    const char *dir = getenv("RASTTY_FRAME_PPM");
    if (log && *log)
        f->log = fopen(log, "a");
    if (f->log) { /* the viewer's start on CLOCK_MONOTONIC: for tests/bench_first_frame.sh */
        fprintf(f->log, "start clock %.6f\n", t0);
        fflush(f->log);
    }
    if (dir && *dir)
        f->ppm_dir = dir;
    const char *off = getenv("RASTTY_FRAME_FLOOR");
    f->floor = floor && !(off && strcmp(off, "off") == 0);
    f->on = floor || f->log || f->ppm_dir;
}

static void drop(struct view_frames *f)
{
    if (f->dec.rgb)
        decode_free(&f->dec);
    free(f->keep);
    free(f->keep_rgb);
    f->keep = NULL;
    f->keep_rgb = NULL;
    f->dec_ok = false;
}

void view_frames_resize(struct view_frames *f, int cols, int rows, struct cell_geom g)
{
    drop(f);
    if (!f->on)
        return;
    struct err e;
    if (decode_init(&f->dec, cols, rows, g, &e))
        return;
    size_t px = (size_t)cols * (size_t)rows * (size_t)(g.px_w * g.px_h) * 3;
    f->keep = malloc((size_t)cols * (size_t)rows * sizeof *f->keep);
    f->keep_rgb = malloc(px);
    f->dec_ok = f->keep && f->keep_rgb;
}

void view_frames_free(struct view_frames *f)
{
    drop(f);
    if (f->log)
        fclose(f->log);
    f->log = NULL;
}

/* Decode the frame's bytes on top of the screen; its PSNR against fb (-1: not decoded). */
static double decode_frame_db(struct view_frames *f, const struct fb *fb, const char *bytes,
                              size_t n)
{
    struct err e;
    if (!f->dec_ok)
        return -1;
    if (decode_apply(&f->dec, bytes, n, &e)) {
        f->dec_ok = false; /* not what we emit: stop measuring rather than guess */
        return -1;
    }
    size_t npx = (size_t)fb->w * (size_t)fb->h * 3; /* an odd last pixel row: not shown */
    return psnr_db(psnr_sse(f->dec.rgb, fb->rgb, npx) / (double)npx);
}

const char *view_frames_encode(struct view_frames *f, struct encode_screen *s,
                               const struct fb *fb, struct encode_opts *o, bool floor,
                               size_t *len_out, struct encode_stats *st, int *tries_out)
{
    floor = floor && f->floor && f->dec_ok && o->budget > 0 && s->glyphs == o->glyphs &&
            o->mode != PALETTE_NONE && o->glyphs != CELL_BRAILLE;
    size_t px = 0;
    struct encode_kept kept = {0};
    if (floor) {
        px = (size_t)f->dec.cols * (size_t)f->dec.rows * (size_t)(f->dec.px_w * f->dec.px_h) * 3;
        encode_screen_keep(s, f->keep, &kept);
        memcpy(f->keep_rgb, f->dec.rgb, px);
        f->keep_dec = f->dec;
    }
    size_t budget = o->budget;
    const char *bytes = NULL;
    int tries = 0;
    for (;;) {
        tries++;
        bytes = encode_fb(s, fb, o, len_out, st);
        f->db = f->on ? decode_frame_db(f, fb, bytes, *len_out) : -1;
        /* met, nothing more to send, or the last try (the whole demand) */
        if (!floor || f->db < 0 || f->db >= VIEW_MIN_DB || o->budget == 0 ||
            *len_out >= st->demand || tries >= VIEW_FLOOR_TRIES)
            break;
        /* take it back: the screen model and the decoded screen as before the frame */
        encode_screen_restore(s, f->keep, &kept);
        uint8_t *rgb = f->dec.rgb;
        f->dec = f->keep_dec;
        f->dec.rgb = rgb;
        memcpy(f->dec.rgb, f->keep_rgb, px);
        /* twice the budget, and at least an eighth of the whole demand: a frame far over
         * its budget gets there in a few tries, near the bar rather than exact */
        size_t next = o->budget * 2 > st->demand / 8 ? o->budget * 2 : st->demand / 8;
        o->budget = tries + 1 >= VIEW_FLOOR_TRIES || next >= st->demand ? 0 : next;
    }
    o->budget = budget;
    *tries_out = tries;
    return bytes;
}

static void write_ppm(const struct view_frames *f, const char *what, const uint8_t *rgb, int w,
                      int h)
{
    char path[4200];
    snprintf(path, sizeof path, "%s/%s-%05lu.ppm", f->ppm_dir, what, f->n);
    struct fb pic = {.w = w, .h = h, .rgb = (uint8_t *)rgb};
    struct err e;
    image_write_ppm(path, &pic, &e); /* a debugging aid: a failure only loses the picture */
}

void view_frames_written(struct view_frames *f, const struct fb *fb, const struct encode_opts *o,
                         size_t bytes, size_t budget, int tries, bool full, const char *lod,
                         double t)
{
    if (!f->log && !f->ppm_dir)
        return;
    f->n++;
    if (f->log) {
        char db[32];
        if (f->db < 0)
            snprintf(db, sizeof db, "?");
        else if (isinf(f->db))
            snprintf(db, sizeof db, "inf");
        else
            snprintf(db, sizeof db, "%.2f", f->db);
        fprintf(f->log,
                "frame %lu t %.4f bytes %zu budget %zu tries %d psnr %s mode %s full %d lod %s\n",
                f->n, t - f->t0, bytes, budget, tries, db, palette_mode_name(o->mode), full, lod);
        fflush(f->log);
    }
    if (f->ppm_dir) {
        write_ppm(f, "fb", fb->rgb, fb->w, fb->h);
        if (f->dec_ok)
            write_ppm(f, "screen", f->dec.rgb, fb->w, fb->h);
    }
}

void view_frames_note(struct view_frames *f, const char *what, size_t bytes, double t)
{
    if (!f->log)
        return;
    if (bytes)
        fprintf(f->log, "%s t %.4f bytes %zu\n", what, t - f->t0, bytes);
    else
        fprintf(f->log, "%s t %.4f\n", what, t - f->t0);
    fflush(f->log);
}
