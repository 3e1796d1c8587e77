/* cellfit.c: pixels -> cells (see cellfit.h). */
#include "cellfit.h"

/* cellfit_pack() with one 4-byte load; reads one byte past the pixel, so only where one
 * exists. */
static inline uint32_t pack_load4(const uint8_t *px)
{
    uint32_t v;
    memcpy(&v, px, 4);
#if __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    return __builtin_bswap32(v) >> 8;
#else
    return v >> 8;
#endif
}

/* One pixel as the terminal will show it in a palette mode. The nearest-colour search costs
 * ~30 ns, so results are memoised in the screen's direct-mapped cache (key = RGB | mode << 24;
 * a pure function of the key, so entries never go stale). Dithered pixels bypass it. */
uint32_t cellfit_quant(struct encode_screen *s, enum palette_mode mode, const uint8_t *px,
                             int x, int y, bool dither)
{
    uint8_t q[3];
    uint32_t *slot = NULL, key = 0;
    if (dither) {
        int d = palette_dither(x, y);
        for (int k = 0; k < 3; k++) {
            int v = px[k] + d;
            q[k] = (uint8_t)(v < 0 ? 0 : v > 255 ? 255 : v);
        }
    } else {
        key = cellfit_pack(px) | (uint32_t)mode << 24;
        slot = s->qcache + 2 * ((key * 2654435761u) >> (32 - ENCODE_QCACHE_BITS));
        if (slot[0] == key)
            return slot[1];
        memcpy(q, px, 3);
    }
    int idx = mode == PALETTE_256 ? palette_nearest_256(q) : palette_nearest_16(q);
    uint8_t shown[3];
    palette_rgb(idx, shown);
    uint32_t out = (uint32_t)idx << 24 | cellfit_pack(shown);
    if (slot) {
        slot[0] = key;
        slot[1] = out;
    }
    return out;
}

void cellfit_frame(struct encode_screen *s, const uint8_t *rgb, int w, int h,
                     const struct encode_opts *o)
{
    bool palette = o->mode == PALETTE_256 || o->mode == PALETTE_16;
    /* In palette modes a pixel equal to last frame's input at the same place keeps last
     * frame's target (still in s->target): static regions cost a compare, not a search. */
    uint32_t tag = palette ? 1u << 27 | (uint32_t)o->dither << 26 | (uint32_t)o->mode << 24 |
                                 cellfit_pack(o->pad_rgb)
                           : 0;
    bool memo_ok = palette && s->memo_tag == tag;
    s->memo_tag = tag;
    for (int r = 0; r < s->rows; r++) {
        const uint8_t *top = rgb + (size_t)(2 * r) * (size_t)w * 3;
        const uint8_t *bot = 2 * r + 1 < h ? top + (size_t)w * 3 : NULL;
        struct encode_cell *t = s->target + (size_t)r * (size_t)s->cols;
        struct encode_cell *m = s->memo + (size_t)r * (size_t)s->cols;
        switch (o->mode) {
        case PALETTE_TRUECOLOR:
            if (bot && 2 * r + 2 < h) { /* a row follows: 4-byte loads stay in the buffer */
                for (int c = 0; c < w; c++) {
                    t[c].top = pack_load4(top + 3 * c);
                    t[c].bot = pack_load4(bot + 3 * c);
                }
                break;
            }
            for (int c = 0; c < w; c++) {
                t[c].top = cellfit_pack(top + 3 * c);
                t[c].bot = cellfit_pack(bot ? bot + 3 * c : o->pad_rgb);
            }
            break;
        case PALETTE_256:
        case PALETTE_16:
            for (int c = 0; c < w; c++) {
                const uint8_t *pb = bot ? bot + 3 * c : o->pad_rgb;
                uint32_t in_top = cellfit_pack(top + 3 * c), in_bot = cellfit_pack(pb);
                if (!memo_ok || m[c].top != in_top)
                    t[c].top = cellfit_quant(s, o->mode, top + 3 * c, c, 2 * r, o->dither);
                if (!memo_ok || m[c].bot != in_bot)
                    t[c].bot = cellfit_quant(s, o->mode, pb, c, 2 * r + 1, o->dither);
                m[c].top = in_top;
                m[c].bot = in_bot;
            }
            break;
        case PALETTE_NONE:
        case PALETTE_MODE_COUNT:
            for (int c = 0; c < w; c++) {
                int luma = palette_luma(top + 3 * c) + palette_luma(bot ? bot + 3 * c : o->pad_rgb);
                int level = palette_ramp_level((luma + 1) / 2);
                uint32_t grey = palette_ramp_grey(level);
                t[c].top = t[c].bot = (uint32_t)level << 24 | grey * 0x010101u;
            }
            break;
        }
    }
}

