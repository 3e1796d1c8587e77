/* decode.h: terminal bytes (ours, or tmux `capture-pane -e -N -p`) back to pixels.
 *
 * A tiny terminal emulator for exactly what rastty emits (and chafa, given the same glyph
 * sets), so tests and `ansi2ppm` can prove that what reaches the screen is the framebuffer.
 * Owns a pixel grid of px_w x px_h pixels per cell (cell.h; half blocks: cols x 2*rows, cell
 * (c, r) = pixels (c, 2r) and (c, 2r+1)), row 0 on top, that persists across calls, so diff
 * frames apply on top of the previous frame. A glyph lands on the grid by area: each pixel
 * shows the mix of fg and bg over the part of the glyph it covers (cell.h's master grid), so
 * every glyph set decodes exactly on its own grid (or a finer one). Callers: ansi2ppm, unit
 * tests, bench, the fuzzer.
 *
 * Understood, anything else is an error naming its byte offset ("NAME: byte N: ..."):
 *   SGR ESC[...m: 0 or empty (reset), 38;2;r;g;b, 48;2;r;g;b, 38;5;n, 48;5;n, 30-37, 40-47,
 *       90-97, 100-107, 39, 49, 7 and 27 (reverse video on, off) (several per sequence; no
 *       ':' sub-parameters)
 *   CUP ESC[r;cH (either may be omitted), CUF ESC[nC, HPA/CHA ESC[nG (clamped to the grid),
 *   ESC[2J (clears with the current bg), ESC[?25h/l, ESC[?2026h/l (no effect on pixels),
 *   ESC[?1049h (the alternate screen starts cleared to the default bg), ESC[?1049l (pixels kept:
 *   we do not keep the main screen), CR, LF (= CR LF, as a tty with ONLCR and tmux's capture
 *   lines mean it), the glyphs ' ' (all bg), U+2580 (top fg, bottom bg), U+2584 (top bg,
 *   bottom fg), U+2588 (all fg), the quadrants and U+258C/U+2590, the sextants U+1FB00..
 *   U+1FB3B, braille U+2800..U+28FF (a dot fills its eighth of the cell), and the none-mode
 *   ramp characters of PALETTE_RAMP except ' ' (the ramp's grey). Colours 0..15 are
 *   palette.h's xterm defaults.
 * Writing in the last column leaves a pending wrap (the next glyph wraps, like xterm); we do
 * not scroll: LF on the last row parks the cursor below the grid, and drawing there is an
 * error. A default fg/bg is shown as default_fg / default_bg (229,229,229 / 0,0,0).
 * Text cells (.text set; ansi2ppm sets it): a tmux capture of the viewer holds its status
 * line and, while open, its help box. A cell whose character is no glyph — a printable ASCII
 * character other than the ramp's, a ramp character drawn with colours set (rastty's ramp
 * is drawn in the terminal's own colours), any other character (the box's frame) — is
 * drawn as a cell of its background colour (after reverse video), what a cell of text
 * mostly shows, and counted in text_cells; SGR's text attributes (1-5, 8, 9, 21-25, 28,
 * 29) are then accepted and change no colour. The picture's glyph cells around decode as
 * ever. Without .text such bytes are errors, as before (the tests' and the fuzzer's check
 * that rastty's own output holds nothing else).
 * Frames: every bare ESC[H (no parameters) starts a frame; frame k = the screen just before
 * the (k+2)-th ESC[H, or at the end. Bytes before the first ESC[H belong to frame 0; input
 * without any ESC[H (a tmux capture) is one frame. See encode.h's mark_frames. */
#ifndef RASTTY_DECODE_H
#define RASTTY_DECODE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "cell.h"
#include "err.h"

struct decode_state {
    int cols, rows;
    int px_w, px_h;           /* pixels per cell */
    uint32_t region[CELL_MASTER_PX]; /* pixel i of a cell: its master-grid cells (cell.h) */
    uint8_t *rgb;             /* cols*px_w x rows*px_h x 3, row 0 top; NULL while measuring */
    const char *name;         /* message prefix (a file name); "input" when NULL */
    bool text;                /* text cells allowed (below); false: they are errors */
    uint8_t default_fg[3], default_bg[3];
    /* terminal state */
    int row, col;             /* cursor cell; row == rows means below the grid */
    bool wrap_pending;
    bool fg_default, bg_default;
    bool reverse;             /* SGR 7 (chafa draws solid cells so) */
    uint8_t fg[3], bg[3];
    /* what was seen */
    int frames;               /* bare ESC[H seen since the last reset */
    int used_cols, used_rows; /* extent of the cells drawn since the last reset */
    int need_w, need_h;       /* the grid the glyphs drawn need (cell_shape_grid) */
    int text_cells;           /* text cells drawn since the last reset (with .text) */
};

/* 1..8192 x 1..4096 cells on g's grid (its px_w x px_h; the glyph set does not matter). The
 * grid starts cleared to default_bg. */
int decode_init(struct decode_state *d, int cols, int rows, struct cell_geom g, struct err *e);
void decode_free(struct decode_state *d);
/* Grid to default_bg, cursor home, colours default, counters zero. */
void decode_reset(struct decode_state *d);

/* Feed bytes (offsets in messages count from buf). */
int decode_apply(struct decode_state *d, const char *buf, size_t len, struct err *e);

/* Reset, then decode frame k (0-based) of buf. -1 if a byte before the end of frame k is not
 * understood or there is no frame k. */
int decode_frame(struct decode_state *d, const char *buf, size_t len, int k, struct err *e);

/* Grid size the input needs (extent of the cells it draws, auto-wrap ignored), its number
 * of frames and the pixels per cell its glyphs need (the finest of them: columns the most,
 * rows the least common multiple; at least half blocks' 1x2; grid_out->glyphs is the glyph
 * set with that grid, or CELL_GLYPHS_COUNT for a mix), parsing it all; name and text as in
 * decode_state. */
int decode_measure(const char *buf, size_t len, const char *name, bool text, int *cols_out,
                   int *rows_out, int *frames_out, struct cell_geom *grid_out, struct err *e);

#endif
