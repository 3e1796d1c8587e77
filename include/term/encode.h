/* encode.h: framebuffer -> terminal bytes (ANSI: half blocks, or the other glyph sets of
 * cell.h), diffed against the model of the screen (encode_screen.h).
 *
 * Pure: no terminal I/O. The caller owns a struct encode_screen (encode_screen_init/free) that
 * remembers what the terminal shows and holds the output buffer; encode_frame fills that
 * buffer and the tty layer writes it with one write(). Callers: the viewer, `dump`, `bench`.
 *
 * Picture: the framebuffer is cols x rows cells of the glyph set's pixels (cell.h), row 0 on
 * top; cellfit.c decides what each cell shows (for quadrants, sextants, braille and ascii:
 * the two colours and the glyph that fit its pixels best). Half blocks, the default: cell
 * (c, r) shows pixel (c, 2r) in its top half and (c, 2r+1) in its bottom half. An odd height
 * pads the last cell row's bottom half with opts.pad_rgb.
 * Glyphs (half blocks): U+2580 upper half (fg = top, bg = bottom), or U+2584 lower half
 * (fg = bottom, bg = top) when that needs fewer SGR changes given the current colours. A cell
 * whose halves are equal is always a space on that background, never U+2588: xterm and st draw
 * block elements from the font, and common fonts leave uncovered strips (a visible grid).
 * Colour modes (palette.h): truecolor 38;2/48;2, 256 38;5/48;5 (16..255), 16 30-37/90-97 and
 * 40-47/100-107, none (one ramp character per cell from the mean luma of its two pixels;
 * no SGR, no synchronized output: only cursor positioning).
 * SGR: only when fg or bg changes, both in one sequence when both change; digits come from a
 * table. Each frame that set a colour ends with ESC[0m, so the terminal is never left
 * coloured between frames (and the next frame starts from "colours unknown").
 * Cursor: moves by the shortest of CUP (ESC[r;cH), CUF (ESC[nC), HPA (ESC[nG, strictly CHA),
 * CR, CR LF (LF with opts.lf_newline), or rewriting the skipped cells (with what they show,
 * or this frame's colours) when that needs no SGR and is shorter. Never relies on
 * auto-wrap: after the last column the column counts as unknown.
 * LF is only ever sent right after CR (safe whether or not the tty translates LF), unless
 * opts.lf_newline says the reader adds the CR (a file `cat` to a terminal).
 *
 * Frames. Full frame: ESC[H, then every cell, rows joined by CR LF (or LF). Diff frame: only cells
 * whose displayed colours change; a frame equal to the screen is 0 bytes. opts.mark_frames
 * makes every frame, even an empty diff, start with ESC[H (3 bytes): the frame boundary that
 * decode_frame counts, for `dump --diff` files. A frame whose body exceeds
 * ENCODE_SYNC_MIN_BYTES is wrapped in ESC[?2026h .. ESC[?2026l (synchronized output).
 * Tolerance N (diff frames only): a cell stays as it is when the terminal already shows
 * exactly the cell this frame would draw, or when every channel of both halves of what it
 * REALLY shows (the screen model, never the previous frame) is within N of the true pixel.
 * A cell that is redrawn may show the current fg/bg (or one colour for both halves) instead
 * of its exact colours when those are within N of its true pixels: no SGR needed. So in
 * truecolor a decoded screen is never more than N per channel from the true frame, and in
 * 256/16 colours never more than max(N, that palette's quantisation error). On the skybox
 * photo panned by half a pixel per frame, N = 2/3/4 gives 148/112/86 KB per frame at
 * 49.5/45.8/43.2 dB PSNR, against 264 KB exact (160x48 cells; `rastty bench` prints such
 * tables for any scene, make bench for the shared photo sky).
 *
 * Budget (opts.budget > 0 bytes, diff frames, not in none mode): a rate-distortion choice, as
 * video coders make. If the frame above fits, it is the frame. Otherwise every changed cell
 * (beyond the tolerance) is left as it is, drawn exactly, or drawn approximately — one colour
 * for both halves (a space on their mean), or the current fg/bg for one or both halves (no
 * SGR) — whichever minimises  error + lambda * bytes,  error being the squared channel
 * differences of its two pixels from the true ones and bytes the exact cost given the current
 * colours; a cell the screen may not show at all counts as four times the worst error. lambda
 * is searched (from the last frame's) for the largest frame within the budget. What is left
 * is counted in encode_stats (cells_pending, max_err): drawing the same picture again fixes
 * it, most error per byte first, so a still picture converges to the exact frame.
 * Held cells (opts.hold_*: an overlay someone else drew) are never written, not even to save
 * a cursor move; the screen model keeps what it had for them.
 *
 * Cost: ~15 us for an unchanged 160x48 truecolor frame, ~80 us for a full one (267 KB of a
 * photo). 256/16 colours search the palette (~30 ns a pixel), memoised per pixel position and
 * by colour, so static regions stay cheap; a frame of all-new colours costs ~0.3-0.5 ms. */
#ifndef RASTTY_ENCODE_H
#define RASTTY_ENCODE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "encode_screen.h"
#include "err.h"
#include "fb.h"

struct encode_stats {
    int cells_drawn;   /* changed cells (all cells in a full frame) */
    int cells_rewritten; /* unchanged cells rewritten because that beat a cursor move */
    int sgr;           /* SGR sequences emitted */
    int moves;         /* cursor moves emitted (CUP, CUF, HPA, CR, CR LF runs) */
    size_t bytes;
    bool full, synced;
    /* budgeted frames (see "Budget"); without a budget demand = bytes, the rest 0 */
    size_t demand;     /* bytes the frame needs without a budget */
    double lambda;     /* the error-per-byte price paid: 0 = every change was drawn */
    int cells_pending; /* cells left further from the truth than their target (and beyond
                        * the tolerance): later frames of a still picture fix them */
    int max_err;       /* largest channel error left in a changed cell this frame */
};

/* Encode a w x h RGB image (row 0 top, 3 bytes/pixel) with w == s->cols and
 * (h + 1) / 2 == s->rows (asserted). Returns the bytes (inside s->out, valid until the next
 * call) and their count in *len_out; updates the screen model. stats_out may be NULL. */
const char *encode_frame(struct encode_screen *s, const uint8_t *rgb, int w, int h,
                         const struct encode_opts *o, size_t *len_out,
                         struct encode_stats *stats_out);

static inline const char *encode_fb(struct encode_screen *s, const struct fb *fb,
                                    const struct encode_opts *o, size_t *len_out,
                                    struct encode_stats *stats_out)
{
    struct encode_opts with_cover = *o;
    with_cover.cover = fb->depth ? fb : NULL;
    return encode_frame(s, fb->rgb, fb->w, fb->h, &with_cover, len_out, stats_out);
}

#endif
