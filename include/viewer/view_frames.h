/* view_frames.h: what reaches the screen, frame by frame, and the quality floor over a slow
 * link (issue 25 item 3).
 *
 * The viewer decodes every frame it writes (decode.h: the bytes themselves, not the encoder's
 * model of the screen) on top of the frames before, so it knows the picture the terminal
 * shows after each frame and its PSNR against the framebuffer the frame was encoded from.
 *
 * Quality floor. A frame with a byte budget (pace.h: a link, not a local terminal) that would
 * leave the screen below VIEW_MIN_DB is taken back (encode_screen_restore) and encoded again
 * with a larger budget: twice as large and at least an eighth of the frame's demand (its
 * bytes without a budget), at most VIEW_FLOOR_TRIES times, the last try the whole demand
 * (every change exact). Over a link too slow for the motion frames
 * therefore come fewer but whole (one frame in flight: a larger frame delays the next),
 * never as ghosts of two pictures. The floor is off where the decoded screen cannot be
 * compared with the framebuffer: no colours (PALETTE_NONE), braille (the terminal's own
 * background), or with the help box over the picture. VIEW_MIN_DB is the bar
 * (30 dB) with a margin: the terminal shows exactly the decoded bytes.
 *
 * Measuring (debugging and tests/bench_link.sh, e2e slow_link.sh), from the environment:
 *   RASTTY_FRAME_LOG=FILE  one line per frame written, appended:
 *     frame N t SECONDS bytes B budget B0 tries K psnr DB mode truecolor|256|16 full 0|1
 *           lod none|pending|building|ready
 *   SECONDS from the viewer's start (view_run entered, before the models are loaded), B the
 *   frame's bytes (status line and query not counted), B0 the pacing's budget (0 = none), K
 *   encodes tried (1 = the floor was met at once), DB the decoded screen against the
 *   framebuffer ("inf" = identical); lod: the levels of detail of the current scene are
 *   not wanted yet (none: --lod off before the first L), wanted but not started (pending:
 *   they start after the first frame), being built (building), or in (ready); the status
 *   line's "lod auto..." is pending or building. First a line "start clock C": the start
 *   on CLOCK_MONOTONIC, in seconds.
 *   RASTTY_FRAME_PPM=DIR   each frame's framebuffer DIR/fb-NNNNN.ppm and the decoded screen
 *   DIR/screen-NNNNN.ppm (the picture's rows, as the terminal shows them).
 *   The log has key and status-line lines too (view_frames_note), and the start's phases:
 *   "loaded t" (the models are in), "terminal t" (its probes answered), "levels t" (every
 *   scene's levels of detail started building) and "levels-ready t" (the current scene's
 *   are in).
 *   RASTTY_FRAME_FLOOR=off the floor off, and the demo's spin never paused for the link:
 *   the viewer as it was before them, for make bench's before/after. */
#ifndef RASTTY_VIEW_FRAMES_H
#define RASTTY_VIEW_FRAMES_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "decode.h"
#include "encode.h"
#include "fb.h"

#define VIEW_MIN_DB 32.0     /* a frame on the screen is at least this close to its picture */
#define VIEW_FLOOR_TRIES 5   /* encodes of one frame at most (the last: its whole demand) */

struct view_frames {
    bool on;                  /* decoding (the floor or a log wants it) */
    bool floor;               /* the quality floor is on (a link; RASTTY_FRAME_FLOOR) */
    struct decode_state dec;  /* what the terminal shows */
    bool dec_ok;              /* dec matches the terminal (false after an error, a resize) */
    struct encode_cell *keep; /* the screen model before the frame being tried */
    uint8_t *keep_rgb;        /* the decoded screen before it */
    struct decode_state keep_dec;
    FILE *log;
    const char *ppm_dir;
    unsigned long n;          /* frames logged */
    double db;                /* the last frame's PSNR as decoded (INFINITY: identical) */
    double t0;
};

/* From the environment (RASTTY_FRAME_LOG, RASTTY_FRAME_PPM); floor: the viewer may need the
 * quality floor (not a local terminal). t0: the viewer's start. */
void view_frames_init(struct view_frames *f, bool floor, double t0);
/* A new screen of cols x rows cells with geometry g (after a resize or a new glyph set); the
 * next frame written is a full one. Errors leave the decoding off (the floor with it). */
void view_frames_resize(struct view_frames *f, int cols, int rows, struct cell_geom g);
void view_frames_free(struct view_frames *f);

/* Encode fb as encode_fb does, holding the frame to the floor when o->budget > 0 and floor
 * is true (see above); *tries_out: encodes made. */
const char *view_frames_encode(struct view_frames *f, struct encode_screen *s,
                               const struct fb *fb, struct encode_opts *o, bool floor,
                               size_t *len_out, struct encode_stats *st, int *tries_out);
/* For RASTTY_FRAME_LOG, where a key's time goes: "key t SECONDS" when a key is read, "hud t
 * SECONDS bytes B" when a changed status line is written (bytes 0: with the next frame,
 * ahead of it in the same write). */
void view_frames_note(struct view_frames *f, const char *what, size_t bytes, double t);
/* The frame's bytes were written (t: now): log it (when asked); lod: "none", "pending",
 * "building" or "ready" (see above). */
void view_frames_written(struct view_frames *f, const struct fb *fb, const struct encode_opts *o,
                         size_t bytes, size_t budget, int tries, bool full, const char *lod,
                         double t);

#endif
