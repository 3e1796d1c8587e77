/* fuzz_decode.c: libFuzzer target for the ANSI decoder, plus an encode -> decode property.
 *
 * 1. Arbitrary bytes through decode_apply / decode_frame / decode_measure: no crash, no
 *    sanitizer report, errors are one line starting with the name.
 * 2. The input also seeds a tiny frame pair (size, mode, tolerance, glyph set from the first
 *    bytes, pixels from the rest): the encoder's output for a full frame then a diff must
 *    decode on the glyph set's grid; with half blocks in truecolor within the tolerance.
 *
 * Build and run (clang):
 *   clang -g -O1 -fsanitize=fuzzer,address,undefined -Iinclude tests/fuzz/fuzz_decode.c \
 *         src/decode.c src/encode.c src/cellfit.c src/cell.c src/palette.c src/err.c \
 *         -o build/fuzz_decode
 *   build/fuzz_decode -max_total_time=60
 * Without libFuzzer (gcc): add -DFUZZ_STANDALONE; the binary runs each file argument once,
 * or a fixed number of pseudo-random inputs when given none. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "decode.h"
#include "encode.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void decode_anything(const uint8_t *data, size_t size)
{
    struct decode_state d;
    struct err e;
    if (decode_init(&d, 16, 8, cell_geom((enum cell_glyphs)(size % CELL_GLYPHS_COUNT)), NULL) != 0)
        abort();
    d.name = "fuzz";
    d.text = size > 1 && (data[1] & 1); /* ansi2ppm's text cells half the time */
    e.msg[0] = 0;
    if (decode_apply(&d, (const char *)data, size, &e) != 0 &&
        (strncmp(e.msg, "fuzz: byte ", 11) != 0 || strchr(e.msg, '\n')))
        abort();
    if (d.row < 0 || d.row > d.rows || d.col < 0 || d.col >= d.cols)
        abort();
    decode_frame(&d, (const char *)data, size, size ? data[0] % 4 : 0, &e);
    int cols, rows, frames;
    struct cell_geom grid;
    decode_measure((const char *)data, size, "fuzz", d.text, &cols, &rows, &frames, &grid, &e);
    decode_free(&d);
}

static void roundtrip(const uint8_t *data, size_t size)
{
    if (size < 5)
        return;
    struct cell_geom g = cell_geom((enum cell_glyphs)(data[3] / 6 % CELL_GLYPHS_COUNT));
    int cols = 1 + data[0] % 12, rows = 1 + data[1] % 6;
    int w = cols * g.px_w, h = rows * g.px_h - (data[2] & 1) * (g.px_h > 1);
    enum palette_mode mode = (enum palette_mode)(data[2] >> 1 & 3);
    int tol = data[3] % 6;
    const uint8_t *src = data + 4;
    size_t nsrc = size - 4, npx = (size_t)w * (size_t)h * 3;
    uint8_t *a = malloc(npx), *b = malloc(npx);
    for (size_t i = 0; i < npx; i++) {
        a[i] = src[i % nsrc];
        b[i] = (uint8_t)(src[(i * 7 + 3) % nsrc] ^ (i % 5 == 0 ? 0 : a[i]));
    }
    struct encode_screen s;
    struct decode_state d;
    struct err e;
    if (encode_screen_init(&s, cols, rows, &e) || decode_init(&d, cols, rows, g, &e))
        abort();
    struct encode_opts o = {.mode = mode, .diff = true, .tolerance = tol,
                            .mark_frames = data[4] & 1, .dither = data[4] & 2,
                            .pad_rgb = {data[4], 0, 255}, .glyphs = g.glyphs};
    for (int f = 0; f < 2; f++) {
        const uint8_t *px = f ? b : a;
        size_t n;
        const char *out = encode_frame(&s, px, w, h, &o, &n, NULL);
        if (n > ENCODE_BOUND(cols, rows) || decode_apply(&d, out, n, &e) != 0)
            abort();
        if (mode == PALETTE_TRUECOLOR && g.glyphs == CELL_HALF) {
            for (int y = 0; y < h; y++)
                for (int i = 0; i < w * 3; i++) {
                    int diff = abs((int)d.rgb[(size_t)y * w * 3 + i] - px[(size_t)y * w * 3 + i]);
                    if (diff > tol)
                        abort();
                }
        }
    }
    encode_screen_free(&s);
    decode_free(&d);
    free(a);
    free(b);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    decode_anything(data, size);
    roundtrip(data, size);
    return 0;
}

#ifdef FUZZ_STANDALONE
int main(int argc, char **argv)
{
    static uint8_t buf[1 << 16];
    if (argc > 1) {
        for (int i = 1; i < argc; i++) {
            FILE *f = fopen(argv[i], "rb");
            if (!f)
                continue;
            size_t n = fread(buf, 1, sizeof buf, f);
            fclose(f);
            LLVMFuzzerTestOneInput(buf, n);
        }
        return 0;
    }
    /* Random inputs biased towards our alphabet so the parser gets past the first byte. */
    static const char *const atoms[] = {"\x1b[", "38;2;", "48;5;", ";", "m", "H", "C", "G",
                                        "\xe2\x96\x80", "\xe2\x96\x84", " ", "\r\n", "?2026h",
                                        "1", "255", "\x1b[0m", "\x1b[H", "@", "J", "2"};
    uint32_t s = 1;
    for (int it = 0; it < 200000; it++) {
        size_t n = 0;
        int atoms_n = (int)(s % 40);
        for (int k = 0; k < atoms_n; k++) {
            s ^= s << 13;
            s ^= s >> 17;
            s ^= s << 5;
            const char *a = atoms[s % (sizeof atoms / sizeof atoms[0])];
            size_t l = strlen(a);
            if (s & 0x100000) {
                buf[n++] = (uint8_t)(s >> 8);
            } else if (n + l < sizeof buf) {
                memcpy(buf + n, a, l);
                n += l;
            }
        }
        LLVMFuzzerTestOneInput(buf, n);
    }
    puts("fuzz_decode: 200000 inputs, no failure");
    return 0;
}
#endif
