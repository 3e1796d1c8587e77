/* encode_screen.h: the encoder's model of the terminal — the cells it shows, what the next
 * frame should show, and the options a frame is encoded with. Both passes of the encoder
 * read it: cellfit.c fills the target cells, encode.c emits the bytes (encode.h). */
#ifndef RASTTY_ENCODE_SCREEN_H
#define RASTTY_ENCODE_SCREEN_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "cell.h"
#include "err.h"
#include "fb.h"
#include "palette.h"

#define ENCODE_MAX_COLS 8192 /* = FB_MAX_DIM: CUP column has at most 4 digits */
#define ENCODE_MAX_ROWS 4096 /* = FB_MAX_DIM / 2 */

/* A body this large (~110 truecolor cells whose fg and bg both change; a full 80x24 frame of
 * a photo is ~67 KB) may reach the terminal in several reads, so it gets wrapped in
 * synchronized output; 16 bytes are < 0.4% of it. Smaller frames almost always arrive in one
 * read and are left bare. */
#define ENCODE_SYNC_MIN_BYTES 4096

/* Worst case per cell: a cursor move (<= CUP "ESC[rrrr;ccccH" = 12 bytes; every cheaper move
 * we choose costs less, rewrites included) + fg and bg in one truecolor SGR
 * ("ESC[38;2;255;255;255;48;2;255;255;255m" = 36) + a glyph of up to 4 bytes (sextants) = 52.
 * Per frame:
 * ESC[H (3) + ESC[?2026h (8) + ESC[0m (4) + ESC[?2026l (8) = 23. Plus 8 bytes of slack
 * because digits are stored 4 bytes at a time. */
#define ENCODE_CELL_MAX_BYTES 52
#define ENCODE_FRAME_MAX_BYTES 23
#define ENCODE_BOUND(cols, rows)                                                          \
    ((size_t)(cols) * (size_t)(rows) * ENCODE_CELL_MAX_BYTES + ENCODE_FRAME_MAX_BYTES + 8)

/* 2^15 entries x 8 bytes = 256 KB per screen: holds the distinct colours of a typical
 * 160x96 frame, so a diff frame in 256/16 colours rarely searches the palette. */
#define ENCODE_QCACHE_BITS 16

struct encode_opts {
    enum palette_mode mode;
    bool diff;           /* emit only changed cells (a full frame when the screen is unknown) */
    int tolerance;       /* 0..255 per channel; diff frames only */
    bool dither;         /* 4x4 ordered dither before quantising (256/16 only; off = exact
                          * nearest colour; on adds up to PALETTE_DITHER_AMP of error) */
    bool mark_frames;    /* every frame starts with ESC[H, even an empty diff */
    bool lf_newline;     /* rows advance with LF alone (files played on a tty, which adds
                          * the CR); else CR LF, as a raw-mode terminal needs */
    uint8_t pad_rgb[3];  /* bottom half of the last row when the height is odd */
    size_t budget;       /* bytes the frame may take, 0 = no limit (see "Budget" above) */
    int hold_col, hold_row, hold_cols, hold_rows; /* cells never drawn (an overlay's) */
    enum cell_glyphs glyphs; /* how cells show pixels (cell.h); 0 = half blocks */
    const struct fb *cover;  /* none mode: which pixels something covers (fb_covered); the rest
                              * (sky, background) is dimmed. NULL = all. encode_fb sets it */
};

/* A cell as the terminal displays it: pixel i shows `top` where bit i of mask is set, else
 * `bot` (cell.h numbers the pixels; half blocks: top and bottom pixel, mask 1). Colours are
 * packed 0xIIRRGGBB where RRGGBB is the colour really shown (after quantisation) and II the
 * palette index (256/16), the ramp level (none with ascii) or 0 (truecolor); the terminal's
 * own colours (braille's background, none's ink) have II 0xFD/0xFE (cellfit.h).
 * Canonical, so that equal pictures are equal cells: one colour is mask 0 and top == bot;
 * two colours have bit 0 set (braille keeps its background in bot). */
struct encode_cell {
    uint32_t top, bot;
    uint32_t mask;
};

struct encode_glyph {
    char utf8[4];
    uint8_t len;
};
#define ENCODE_CELL_UNKNOWN 0xFFFFFFFFu /* never a real colour: forces a redraw */

struct encode_screen {
    int cols, rows;
    struct encode_cell *cells;  /* cols*rows, row-major: what the terminal shows */
    struct encode_cell *target; /* cols*rows scratch: this frame after quantisation */
    bool valid;                 /* false: the terminal is unknown, the next frame is full */
    enum palette_mode mode;     /* mode the cells were drawn in (a change forces a full frame) */
    char *out;                  /* output buffer, out_cap = ENCODE_BOUND(cols, rows) bytes */
    size_t out_cap;
    /* palette-mode speed-ups (pure caches: they never change the output) */
    struct encode_cell *memo;   /* cols*rows: input pixels (packed RGB) behind `target` */
    uint32_t memo_tag;          /* mode/dither/pad that `target` was made with; 0 = none */
    uint32_t *qcache;           /* RGB -> cell colour, 2 << ENCODE_QCACHE_BITS words */
    /* budgeted frames */
    struct encode_cell *saved;  /* cols*rows: the screen model before the frame, for retries */
    double lambda;              /* the last budgeted frame's lambda: the next one's first guess */
    /* the glyph set the cells were drawn with (a change forces a full frame) */
    enum cell_glyphs glyphs;
    struct cell_geom geom;
    struct encode_glyph glyph[256]; /* UTF-8 of each pattern */
};

/* 1 <= cols <= ENCODE_MAX_COLS, 1 <= rows <= ENCODE_MAX_ROWS. Screen starts unknown. */
int encode_screen_init(struct encode_screen *s, int cols, int rows, struct err *e);
void encode_screen_free(struct encode_screen *s);
/* The terminal was cleared, resized or scribbled on: the next frame is a full frame. */
void encode_screen_invalidate(struct encode_screen *s);
/* Cells in the rectangle were overwritten by someone else (a HUD): redraw them next frame. */
void encode_screen_damage(struct encode_screen *s, int col, int row, int ncols, int nrows);

/* A frame tried and taken back (its bytes never written; the viewer's quality floor,
 * view_frames.h): encode_screen_keep copies what the model says the terminal shows into keep
 * (s->cols * s->rows cells the caller owns) and the rest of the model's state (whether it
 * is known, its colour mode, the last budgeted frame's price) into *kept;
 * encode_screen_restore puts them back. The glyph set must be the same in between (the
 * next encode_frame with the same options). */
struct encode_kept {
    bool valid;
    enum palette_mode mode;
    double lambda;
};
void encode_screen_keep(const struct encode_screen *s, struct encode_cell *keep,
                        struct encode_kept *kept);
void encode_screen_restore(struct encode_screen *s, const struct encode_cell *keep,
                           const struct encode_kept *kept);

/* The glyph set's UTF-8 for every pattern, kept in s (encode_frame calls it when the set
 * changes). */
void encode_screen_glyphs(struct encode_screen *s, enum cell_glyphs g);

#endif
