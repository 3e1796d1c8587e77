/* test_texture.c: texel conventions (v = 1 is the top row, centres at half texels, repeat),
 * both filters, and loading (LDR formats, HDR tone mapping, corrupt files). */
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>

#include <stdlib.h>
#include <time.h>
#include <unistd.h>

#include <fcntl.h>
#include <sys/stat.h>

#include <stb_image.h>
#include <stb_image_write.h>

#include "file.h"
#include "imgdec.h"
#include "test.h"
#include "texture.h"

/* 2x2: top row red, green; bottom row blue, white (as a file stores it: row 0 = top) */
static int tex2(struct texture *t)
{
    static const uint8_t px[16] = {255, 0, 0, 255, 0, 255, 0, 255,
                                   0, 0, 255, 255, 255, 255, 255, 255};
    return texture_from_rgba(2, 2, px, t, NULL);
}

static void expect(struct test *t, const struct texture *tx, enum tex_filter f, float u, float v,
                   float r, float g, float b, int line)
{
    float c[3];
    texture_sample(tx, f, u, v, 0, c);
    if (fabsf(c[0] - r) > 1e-5f || fabsf(c[1] - g) > 1e-5f || fabsf(c[2] - b) > 1e-5f)
        test_fail(t, __FILE__, line, "sample(%g, %g) = (%g %g %g), want (%g %g %g)", u, v, c[0],
                  c[1], c[2], r, g, b);
}

TEST(texture_v1_is_top_row_and_nearest_picks_floor)
{
    struct texture tx;
    REQUIRE(tex2(&tx) == 0);
    expect(t, &tx, TEX_NEAREST, 0.25f, 0.75f, 1, 0, 0, __LINE__); /* top-left: red */
    expect(t, &tx, TEX_NEAREST, 0.75f, 0.75f, 0, 1, 0, __LINE__); /* top-right: green */
    expect(t, &tx, TEX_NEAREST, 0.25f, 0.25f, 0, 0, 1, __LINE__); /* bottom-left: blue */
    expect(t, &tx, TEX_NEAREST, 0.5f, 0.5f, 0, 1, 0, __LINE__);   /* floor(1): texel 1, row 1 */
    expect(t, &tx, TEX_NEAREST, 1.25f, -0.25f, 1, 0, 0, __LINE__); /* repeat: -0.25 = 0.75 */
    expect(t, &tx, TEX_NEAREST, -0.75f, 2.75f, 1, 0, 0, __LINE__);
    texture_free(&tx);
}

TEST(texture_bilinear_centres_and_wrap)
{
    struct texture tx;
    REQUIRE(tex2(&tx) == 0);
    /* at a texel centre: exactly that texel */
    expect(t, &tx, TEX_BILINEAR, 0.25f, 0.75f, 1, 0, 0, __LINE__);
    /* halfway between the two top texels */
    expect(t, &tx, TEX_BILINEAR, 0.5f, 0.75f, 0.5f, 0.5f, 0, __LINE__);
    /* at u = 0 (an edge) repeat blends the left and right columns equally */
    expect(t, &tx, TEX_BILINEAR, 0.0f, 0.75f, 0.5f, 0.5f, 0, __LINE__);
    /* centre of the texture: the mean of all four */
    expect(t, &tx, TEX_BILINEAR, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, __LINE__);
    texture_free(&tx);
}

/* NaN cannot come from a file (the parser rejects it), but a finite 1e38 times the width
 * overflows to inf, and inf - floor(inf) is NaN: samples must stay in [0,1] regardless */
TEST(texture_huge_and_nonfinite_coordinates_stay_in_range)
{
    struct texture tx;
    REQUIRE(tex2(&tx) == 0);
    float c[3];
    const float bad[] = {1e30f, -1e30f, INFINITY, -INFINITY, NAN};
    for (unsigned i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        texture_sample(&tx, TEX_NEAREST, bad[i], bad[i], 0, c);
        CHECK(c[0] >= 0 && c[0] <= 1);
        texture_sample(&tx, TEX_BILINEAR, bad[i], 0.3f, 0, c);
        CHECK(c[1] >= 0 && c[1] <= 1);
    }
    texture_free(&tx);
}

TEST(texture_load_formats_and_errors)
{
    struct texture tx;
    struct err e;
    REQUIRE(texture_load("tests/data/obj/checker2x2.png", TEXTURE_MAX_SIDE, &tx, NULL, &e) == 0);
    CHECK_EQ_INT(tx.w, 2);
    CHECK_EQ_INT(tx.h, 2);
    texture_free(&tx);
    CHECK(texture_load("tests/data/obj/corrupt.png", TEXTURE_MAX_SIDE, &tx, NULL, &e) == -1);
    CHECK_STR_CONTAINS(e.msg, "corrupt.png");
    CHECK(texture_load("tests/data/obj/no-such-file.png", TEXTURE_MAX_SIDE, &tx, NULL, &e) == -1);
    CHECK_STR_CONTAINS(e.msg, "no-such-file.png");
    /* special files are refused before any read: /dev/zero would never end */
    CHECK(texture_load("/dev/zero", TEXTURE_MAX_SIDE, &tx, NULL, &e) == -1);
    CHECK(strcmp(e.msg, "/dev/zero: cannot open texture: a device, not a regular file") == 0);
}

TEST(texture_hdr_is_tone_mapped_not_clipped)
{
    const char *dir = test_models_dir();
    if (!dir) {
        test_skip(t, "no ../shared/models");
        return;
    }
    char path[512];
    snprintf(path, sizeof path, "%s/sky_hdr/venice_sunset_1k.hdr", dir);
    struct texture tx;
    struct err e;
    REQUIRE(texture_load(path, TEXTURE_MAX_SIDE, &tx, NULL, &e) == 0);
    CHECK_EQ_INT(tx.w, 1024);
    CHECK_EQ_INT(tx.h, 512);
    /* radiance up to 6496 (the sun): Reinhard keeps everything below white except the
     * brightest texels, and the picture is neither black nor blown out */
    long sum = 0, white = 0, n = (long)tx.w * tx.h;
    for (long i = 0; i < n; i++) {
        const uint8_t *p = tx.rgba + 4 * i;
        sum += p[0] + p[1] + p[2];
        white += p[0] == 255 && p[1] == 255 && p[2] == 255;
    }
    double mean = sum / (3.0 * n);
    CHECK(mean > 60 && mean < 200);
    CHECK(white < n / 1000);
    texture_free(&tx);
}

/* ---- decoders: every format through imgdec, byte-exact on small images ---- */

static int decode(const void *data, size_t len, struct texture *tx, struct warnings *w,
                  struct err *e)
{
    if (w)
        memset(w, 0, sizeof *w);
    struct imgdec_image img;
    memset(tx, 0, sizeof *tx);
    if (imgdec_decode(data, len, "t", TEXTURE_MAX_SIDE, &img, w, e))
        return -1;
    tx->w = img.w, tx->h = img.h, tx->rgba = img.rgba;
    return 0;
}

/* issue 12, defect 1: 16-bit PGM/PPM crashed stb_image (reads past its buffer) */
TEST(pnm_16_bit_is_decoded_not_a_crash)
{
    struct texture tx;
    struct err e;
    /* 2x1 P5, maxval 65535: 0xffff, 0x8000 */
    static const uint8_t pgm[] = "P5 2 1 65535\n\xff\xff\x80\x00";
    REQUIRE(decode(pgm, sizeof pgm - 1, &tx, NULL, &e) == 0);
    CHECK_EQ_INT(tx.w, 2);
    CHECK_EQ_INT(tx.rgba[0], 255);
    CHECK_EQ_INT(tx.rgba[2], 255);
    CHECK_EQ_INT(tx.rgba[4], 128); /* 32768 * 255 / 65535, rounded */
    CHECK_EQ_INT(tx.rgba[7], 255);
    texture_free(&tx);
    /* P6, maxval 1000 (16-bit samples), with a comment in the header */
    static const uint8_t ppm[] = "P6\n# c\n1 1\n1000\n\x03\xe8\x01\xf4\x00\x00";
    REQUIRE(decode(ppm, sizeof ppm - 1, &tx, NULL, &e) == 0);
    CHECK_EQ_INT(tx.rgba[0], 255);
    CHECK_EQ_INT(tx.rgba[1], 128);
    CHECK_EQ_INT(tx.rgba[2], 0);
    texture_free(&tx);
    /* the 15-byte file of the report: a header promising more than the file holds */
    static const uint8_t short16[] = "P5 9 9 65535\n\x01\x02";
    CHECK_EQ_INT(decode(short16, sizeof short16 - 1, &tx, NULL, &e), -1);
    CHECK(strcmp(e.msg, "t: truncated PNM: 2 bytes of pixels, 9x9 needs 162") == 0);
    CHECK(tx.rgba == NULL);
    /* the size that made stb_image crash (SIGSEGV) outright: 1024x1024 16-bit */
    static const char hdr[] = "P5 1024 1024 65535\n";
    const size_t hn = sizeof hdr - 1, big_n = hn + (size_t)1024 * 1024 * 2;
    uint8_t *big = malloc(big_n);
    REQUIRE(big);
    memcpy(big, hdr, hn);
    for (size_t i = hn; i < big_n; i++)
        big[i] = (uint8_t)i;
    REQUIRE(decode(big, big_n, &tx, NULL, &e) == 0);
    CHECK_EQ_INT(tx.w, 1024);
    uint8_t want = (uint8_t)((((unsigned)big[hn] << 8 | big[hn + 1]) * 255u + 32767) / 65535);
    CHECK_EQ_INT(tx.rgba[0], want);
    texture_free(&tx);
    free(big);
    static const uint8_t ascii[] = "P3 1 1 255\n1 2 3\n";
    CHECK_EQ_INT(decode(ascii, sizeof ascii - 1, &tx, NULL, &e), -1);
    CHECK_STR_CONTAINS(e.msg, "P3 is not supported");
}

/* issue 12, defect 2: truncated Radiance HDR made stb_image loop forever */
TEST(hdr_truncated_or_malformed_fails_at_once)
{
    struct texture tx;
    struct err e;
    /* a 135-byte file claiming 9994x9999 (stb accepted it as a 1.5 GB image) */
    char big[136];
    int n = snprintf(big, sizeof big, "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 9999 +X 9994\n");
    memset(big + n, 0x02, sizeof big - 1 - (size_t)n);
    clock_t t0 = clock();
    CHECK_EQ_INT(decode(big, 135, &tx, NULL, &e), -1);
    CHECK_STR_CONTAINS(e.msg, "truncated HDR");
    /* an RLE run of length 0 (what a file cut short reads as in stb): stb's loop never
     * advances */
    uint8_t zero[200];
    n = snprintf((char *)zero, sizeof zero,
                 "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 16\n");
    const uint8_t line[] = {2, 2, 0, 16, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    memcpy(zero + n, line, sizeof line);
    CHECK_EQ_INT(decode(zero, (size_t)n + sizeof line, &tx, NULL, &e), -1);
    CHECK_STR_CONTAINS(e.msg, "bad or truncated HDR scanline 0");
    /* a valid 8x1 RLE image: runs of 8 (value 128, exponent 129 = 1.0 -> Reinhard 0.5) */
    const uint8_t good[] = {2, 2, 0, 8, 128 + 8, 128, 128 + 8, 128, 128 + 8, 128, 128 + 8, 129};
    n = snprintf((char *)zero, sizeof zero, "#?RGBE\n\n-Y 1 +X 8\n");
    memcpy(zero + n, good, sizeof good);
    REQUIRE(decode(zero, (size_t)n + sizeof good, &tx, NULL, &e) == 0);
    CHECK_EQ_INT(tx.w, 8);
    CHECK_EQ_INT(tx.rgba[0], 186); /* pow(0.5, 1/2.2) * 255 */
    CHECK_EQ_INT(tx.rgba[4 * 7 + 2], 186);
    texture_free(&tx);
    /* the shared HDR cut at the sizes of the report: errors, each at once */
    const char *dir = test_models_dir();
    if (dir) {
        char path[512];
        snprintf(path, sizeof path, "%s/sky_hdr/venice_sunset_1k.hdr", dir);
        char *data;
        size_t len;
        REQUIRE(file_read(path, FILE_MAX_IMAGE, &data, &len) == 0);
        static const size_t cuts[] = {200, 1000, 10000, 100000, 500000};
        for (size_t i = 0; i < sizeof cuts / sizeof cuts[0]; i++) {
            CHECK_EQ_INT(decode(data, cuts[i], &tx, NULL, &e), -1);
            CHECK_STR_CONTAINS(e.msg, "HDR");
        }
        free(data);
    }
    CHECK((double)(clock() - t0) / CLOCKS_PER_SEC < 10); /* not a time bar: a hang guard */
}

/* issue 12, defect 6: JPEG goes to libjpeg-turbo, never to stb_image */
TEST(jpeg_and_png_use_their_libraries)
{
    const char *dir = test_models_dir();
    struct texture tx;
    struct err e;
    /* a JPEG cut short: libjpeg's words, not stb's */
    static const uint8_t notjpeg[] = "\xff\xd8\xff\xe0\x00\x10JFIF\x00";
    CHECK_EQ_INT(decode(notjpeg, sizeof notjpeg - 1, &tx, NULL, &e), -1);
    CHECK_STR_CONTAINS(e.msg, "t: bad JPEG (");
    /* the input a fuzzer found to make stb_image write one past its 257-byte Huffman size
     * table (UBSan: index 257 out of bounds): libjpeg refuses it cleanly */
    struct texture tx2;
    CHECK_EQ_INT(texture_load("tests/data/tex/stb_jpeg_ub.jpg", TEXTURE_MAX_SIDE, &tx2, NULL, &e),
                 -1);
    CHECK(strcmp(e.msg, "tests/data/tex/stb_jpeg_ub.jpg: bad JPEG (Bogus Huffman table "
                        "definition)") == 0);
    /* a complete IHDR chunk with a wrong checksum: libpng's words */
    static const uint8_t notpng[] = "\x89PNG\r\n\x1a\n\x00\x00\x00\x0dIHDR\x00\x00\x00\x01"
                                    "\x00\x00\x00\x01\x08\x02\x00\x00\x00\x00\x00\x00\x00";
    CHECK_EQ_INT(decode(notpng, sizeof notpng - 1, &tx, NULL, &e), -1);
    CHECK_STR_CONTAINS(e.msg, "t: bad PNG (");
    if (!dir) {
        test_skip(t, "no shared models for the JPEG cube map");
        return;
    }
    char path[512];
    snprintf(path, sizeof path, "%s/skybox/posx.jpg", dir);
    REQUIRE(texture_load(path, TEXTURE_MAX_SIDE, &tx, NULL, &e) == 0);
    CHECK_EQ_INT(tx.w, 512);
    CHECK_EQ_INT(tx.h, 512);
    texture_free(&tx);
    /* 1/2 scaling inside libjpeg: 256x256 */
    struct warnings w = {0};
    REQUIRE(texture_load(path, 256, &tx, &w, &e) == 0);
    CHECK_EQ_INT(tx.w, 256);
    CHECK_EQ_INT(w.n, 1);
    texture_free(&tx);
}

/* issue 12, defect 4: a 261 KB 16384^2 PNG cost 2 GB; the same path 64 times 16 GB */
TEST(huge_texture_downscaled_and_loaded_once)
{
    const char *huge = "tests/data/tex/huge16384.png";
    struct texture_cache c = {0};
    struct warnings w = {0};
    struct err e;
    const struct texture *first = NULL, *tx;
    for (int i = 0; i < 64; i++) {
        REQUIRE(texture_cache_load(&c, huge, &tx, &w, &e) == 0);
        if (i == 0)
            first = tx;
        CHECK(tx == first);
    }
    CHECK_EQ_INT(c.n, 1);
    CHECK_EQ_INT(first->w, TEXTURE_MAX_SIDE);
    CHECK_EQ_INT(first->h, TEXTURE_MAX_SIDE);
    size_t want = 0; /* level 0 and its mip chain count against the budget */
    for (size_t side = TEXTURE_MAX_SIDE; side >= 1; side /= 2)
        want += side * side * 4;
    CHECK_EQ_INT(c.bytes, want);
    /* left half white, right half black, box-filtered */
    CHECK_EQ_INT(first->rgba[0], 255);
    CHECK_EQ_INT(first->rgba[(size_t)(TEXTURE_MAX_SIDE - 1) * 4], 0);
    CHECK_EQ_INT(w.n, 1);
    CHECK(strcmp(w.msg[0], "tests/data/tex/huge16384.png: 16384x16384 image downscaled to "
                           "4096x4096 (limit 4096 per side)") == 0);
    /* a second spelling of the same file is the same texture */
    REQUIRE(texture_cache_load(&c, "tests/data/tex/../tex/huge16384.png", &tx, &w, &e) == 0);
    CHECK(tx == first);
    texture_cache_free(&c);
    /* over the budget: refused, named. A 512x512 file of its own (1 MiB of texels and its
     * mips): the huge one again would be decoded again, half this test's time. */
    char path[64], want_msg[160];
    snprintf(path, sizeof path, "/tmp/rastty-budget-%d.png", (int)getpid());
    static uint8_t grey[512 * 512];
    REQUIRE(stbi_write_png(path, 512, 512, 1, grey, 512) != 0);
    struct texture_cache small = {.budget = 1 << 20};
    CHECK_EQ_INT(texture_cache_load(&small, path, &tx, &w, &e), -1);
    snprintf(want_msg, sizeof want_msg,
             "%s: texture would pass the 1 MiB texture budget (0 MiB in use)", path);
    CHECK(strcmp(e.msg, want_msg) == 0);
    CHECK_EQ_INT(small.bytes, 0);
    texture_cache_free(&small);
    remove(path);
}

TEST(not_an_image_is_named)
{
    struct texture tx;
    struct err e;
    static const uint8_t text[] = "this is not an image\n";
    CHECK_EQ_INT(decode(text, sizeof text - 1, &tx, NULL, &e), -1);
    CHECK_STR_CONTAINS(e.msg, "t: not a readable image");
    CHECK(strcmp(imgdec_kind((const uint8_t *)"\xff\xd8\xff\xe0", 4), "JPEG image") == 0);
    CHECK(imgdec_kind(text, sizeof text - 1) == NULL);
}

/* a 65-byte TGA whose RLE header asks for 3855x3855: stb would decode 15 million pixels
 * from it (25 s under the sanitizers, found by fuzz_texture); refused by its size */
TEST(stb_formats_checked_against_file_size)
{
    static const uint8_t tga[] = {0, 0, 10, 0, 0, 15, 15, 15, 15, 15, 90, 15, 15, 15, 15, 15,
                                  15, 15, 15, 58, 15, 52, 53, 56, 0, 0, 0, 5, 0, 4, 0, 24};
    uint8_t d[65] = {0};
    memcpy(d, tga, sizeof tga);
    d[12] = 0x0f, d[13] = 0x0f, d[14] = 0x0f, d[15] = 0x0f, d[16] = 24, d[17] = 0;
    struct texture tx;
    struct err e;
    CHECK_EQ_INT(decode(d, sizeof d, &tx, NULL, &e), -1);
    CHECK(strcmp(e.msg, "t: TGA of 3855x3855 cannot fit in 65 bytes (at least 464426): "
                        "truncated") == 0);
    CHECK(tx.rgba == NULL);
}

/* A TGA of w x h (type 2, 3, 10 or 11; bits 8, 24 or 32; rows top-first when top) from a
 * pseudo-random image with runs: RLE packets of both kinds, some of them crossing rows. */
static size_t make_tga(uint8_t *f, int type, int bits, bool top, int w, int h, unsigned seed)
{
    const int bpp = bits / 8, n = w * h;
    memset(f, 0, 18);
    f[0] = 3, f[2] = (uint8_t)type, f[12] = (uint8_t)w, f[14] = (uint8_t)h, f[16] = (uint8_t)bits;
    f[17] = top ? 0x20 : 0;
    size_t pos = 21; /* after a 3-byte image id */
    uint8_t px[64 * 64 * 4];
    for (int i = 0; i < n; i++) {
        seed = seed * 1103515245u + 12345u;
        if (i > 0 && (seed >> 28) < 9) /* a run: the pixel before again */
            memcpy(px + i * bpp, px + (i - 1) * bpp, (size_t)bpp);
        else
            for (int c = 0; c < bpp; c++)
                px[i * bpp + c] = (uint8_t)((seed = seed * 1103515245u + 12345u) >> 20);
    }
    if (type < 9) {
        memcpy(f + pos, px, (size_t)(n * bpp));
        return pos + (size_t)(n * bpp);
    }
    for (int i = 0; i < n;) {
        int k = 1; /* the run at i, up to 128 */
        while (i + k < n && k < 128 && !memcmp(px + (i + k) * bpp, px + i * bpp, (size_t)bpp))
            k++;
        if (k > 1) {
            f[pos++] = (uint8_t)(0x80 | (k - 1));
            memcpy(f + pos, px + i * bpp, (size_t)bpp);
            pos += (size_t)bpp;
        } else { /* raw: up to the next run */
            while (i + k < n && k < 128 &&
                   memcmp(px + (i + k) * bpp, px + (i + k - 1) * bpp, (size_t)bpp))
                k++;
            f[pos++] = (uint8_t)(k - 1);
            memcpy(f + pos, px + i * bpp, (size_t)(k * bpp));
            pos += (size_t)(k * bpp);
        }
        i += k;
    }
    return pos;
}

/* rastty's TGA decoder against stb's, byte for byte, on every kind it takes */
TEST(tga_decodes_as_stb_does)
{
    static uint8_t f[18 + 3 + 64 * 64 * 5];
    static const int kinds[][2] = {{2, 24}, {2, 32}, {3, 8}, {10, 24}, {10, 32}, {11, 8}};
    int compared = 0;
    for (size_t k = 0; k < sizeof kinds / sizeof kinds[0]; k++)
        for (int top = 0; top < 2; top++) {
            int w = 37 + (int)k, h = 23 + top;
            size_t len = make_tga(f, kinds[k][0], kinds[k][1], top, w, h, (unsigned)(k * 7 + top));
            struct texture tx;
            struct err e;
            REQUIRE(decode(f, len, &tx, NULL, &e) == 0);
            int sw, sh, n;
            uint8_t *ref = stbi_load_from_memory(f, (int)len, &sw, &sh, &n, 4);
            REQUIRE(ref != NULL);
            CHECK_EQ_INT(tx.w, sw);
            CHECK_EQ_INT(tx.h, sh);
            if (tx.w == sw && tx.h == sh && memcmp(tx.rgba, ref, (size_t)(sw * sh * 4)) != 0)
                test_fail(t, __FILE__, __LINE__, "type %d, %d bits, %s: bytes differ from stb",
                          kinds[k][0], kinds[k][1], top ? "top-first" : "bottom-first");
            compared++;
            stbi_image_free(ref);
            texture_free(&tx);
        }
    CHECK_EQ_INT(compared, 12);
    /* pixel data that stops short: named, not decoded from nothing */
    size_t len = make_tga(f, 10, 24, false, 40, 20, 1);
    struct texture tx;
    struct err e;
    CHECK_EQ_INT(decode(f, len - 40, &tx, NULL, &e), -1);
    CHECK_STR_CONTAINS(e.msg, "t: TGA pixel data ends at row");
    CHECK(tx.rgba == NULL);
    /* the shared textures too */
    const char *dir = test_models_dir();
    if (!dir) {
        test_skip(t, "no ../shared/models: the shared TGA textures not compared");
        return;
    }
    static const char *const files[] = {"african_head/african_head_diffuse.tga",
                                        "african_head/african_head_nm.tga",
                                        "african_head/african_head_spec.tga",
                                        "diablo3_pose/diablo3_pose_diffuse.tga"};
    for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) {
        char path[1024];
        snprintf(path, sizeof path, "%s/%s", dir, files[i]);
        char *data;
        size_t n;
        REQUIRE(file_read(path, FILE_MAX_IMAGE, &data, &n) == 0);
        REQUIRE(decode(data, n, &tx, NULL, &e) == 0);
        int sw, sh, c;
        uint8_t *ref = stbi_load_from_memory((const uint8_t *)data, (int)n, &sw, &sh, &c, 4);
        REQUIRE(ref != NULL);
        if (tx.w != sw || tx.h != sh || memcmp(tx.rgba, ref, (size_t)sw * (size_t)sh * 4))
            test_fail(t, __FILE__, __LINE__, "%s: differs from stb", files[i]);
        stbi_image_free(ref);
        texture_free(&tx);
        free(data);
    }
}

struct membuf {
    uint8_t d[4096];
    size_t n;
};

static void to_membuf(void *ctx, void *data, int size)
{
    struct membuf *m = ctx;
    if (size > 0 && m->n + (size_t)size <= sizeof m->d)
        memcpy(m->d + m->n, data, (size_t)size), m->n += (size_t)size;
}

static uint32_t crc32_of(const uint8_t *p, size_t n)
{
    uint32_t c = 0xffffffffu;
    for (size_t i = 0; i < n; i++) {
        c ^= p[i];
        for (int k = 0; k < 8; k++)
            c = c >> 1 ^ (0xedb88320u & (0u - (c & 1)));
    }
    return ~c;
}

/* PNG: zlib's Adler-32 over the inflated bytes is not checked (the chunk CRCs are): a
 * changed IDAT byte is still refused, a wrong Adler-32 under a right CRC decodes */
TEST(png_idat_crc_checked_adler32_not)
{
    uint8_t px[8 * 8 * 3];
    for (size_t i = 0; i < sizeof px; i++)
        px[i] = (uint8_t)(i * 7);
    struct membuf m = {.n = 0};
    REQUIRE(stbi_write_png_to_func(to_membuf, &m, 8, 8, 3, px, 8 * 3) != 0);
    size_t at = 8, idat = 0, idat_len = 0; /* the IDAT chunk's data */
    while (at + 12 <= m.n) {
        size_t len = (size_t)m.d[at] << 24 | (size_t)m.d[at + 1] << 16 |
                     (size_t)m.d[at + 2] << 8 | m.d[at + 3];
        if (!memcmp(m.d + at + 4, "IDAT", 4))
            idat = at + 8, idat_len = len;
        at += 12 + len;
    }
    REQUIRE(idat > 0 && idat_len > 6);
    struct texture tx;
    struct err e;
    REQUIRE(decode(m.d, m.n, &tx, NULL, &e) == 0);
    int same = tx.w == 8 && tx.h == 8;
    for (int i = 0; same && i < 64; i++)
        same = !memcmp(tx.rgba + 4 * i, px + 3 * i, 3);
    CHECK(same);
    texture_free(&tx);
    /* one byte of the compressed data changed: the CRC no longer matches */
    struct membuf bad = m;
    bad.d[idat + 3] ^= 0x40;
    CHECK_EQ_INT(decode(bad.d, bad.n, &tx, NULL, &e), -1);
    CHECK_STR_CONTAINS(e.msg, "t: bad PNG (");
    /* the Adler-32 (the stream's last 4 bytes) changed and the CRC made right again */
    bad = m;
    bad.d[idat + idat_len - 1] ^= 0x01;
    uint32_t crc = crc32_of(bad.d + idat - 4, idat_len + 4);
    for (int k = 0; k < 4; k++)
        bad.d[idat + idat_len + (size_t)k] = (uint8_t)(crc >> (24 - 8 * k));
    CHECK_EQ_INT(decode(bad.d, bad.n, &tx, NULL, &e), 0);
    if (tx.rgba) {
        same = tx.w == 8 && tx.h == 8;
        for (int i = 0; same && i < 64; i++)
            same = !memcmp(tx.rgba + 4 * i, px + 3 * i, 3);
        CHECK(same);
        texture_free(&tx);
    }
}

/* a 151-byte PSD with 4 channels: stb's matte removal casts -12750 to a byte (UBSan, found by
 * fuzz_texture with stb compiled in); refused before stb sees it */
TEST(psd_with_alpha_is_refused)
{
    static const uint8_t psd[] = {'8', 'B', 'P', 'S', 0, 1, 'B', '/', 10, 24, 0, 0, 0, 7, 0, 0,
                                  0, 4, 0, 0, 0, 4, 0, 16, 0, 3, 0, 0, 0, 0, 0, 0, 0, 0};
    struct texture tx;
    struct err e;
    CHECK_EQ_INT(decode(psd, sizeof psd, &tx, NULL, &e), -1);
    CHECK(strcmp(e.msg, "t: PSD with an alpha channel (7 channels) is not supported") == 0);
}

/* a 65-byte PNG whose tEXt chunk claims 1.9 GB: libpng allocated it (found by fuzz_texture:
 * out of memory); every chunk must now fit in the file */
TEST(png_chunk_lengths_checked_against_the_file)
{
    static const uint8_t png[] = {
        0x89, 'P', 'N', 'G', 0x0d, 0x0a, 0x1a, 0x0a, 0, 0, 0, 0x0d, 'I', 'H', 'D', 'R',
        0, 0, 0, 9, 0, 0, 0, 7, 8, 3, 0, 0, 1, 0x9a, 0x42, 0xa7, 0xc4,
        0, 0, 0, 4, 'g', 'A', 'M', 'A', 0x2c, 0xe8, 0x94, 0x34, 0x42, 0x3e, 0, 0x25,
        0x74, 0x3e, 0, 0x25, 't', 'E', 'X', 't', 'd', 'a', 't', '2', '0', '0', ':', 0x82};
    struct texture tx;
    struct err e;
    CHECK_EQ_INT(decode(png, sizeof png, &tx, NULL, &e), -1);
    CHECK(strcmp(e.msg, "t: byte 49: PNG chunk of 1950220325 bytes, 8 left in the file: "
                        "truncated") == 0);
}

/* issue 25, item 17: a valid top-down BMP (negative height: rows stored top first) was
 * refused as "image is 2x-2" */
TEST(top_down_bmp_is_decoded_upright)
{
    /* 2x2, 24-bit, height -2: the first stored row (red, green) is the top row */
    uint8_t bmp[54 + 16] = {'B', 'M'};
    uint32_t fsize = sizeof bmp;
    memcpy(bmp + 2, &fsize, 4);
    bmp[10] = 54;
    bmp[14] = 40;
    int32_t wd = 2, ht = -2;
    memcpy(bmp + 18, &wd, 4);
    memcpy(bmp + 22, &ht, 4);
    bmp[26] = 1;
    bmp[28] = 24;
    static const uint8_t rows[16] = {0, 0, 255, 0, 255, 0, 0, 0, /* BGR red, green, pad */
                                     255, 0, 0, 255, 255, 255, 0, 0}; /* blue, white, pad */
    memcpy(bmp + 54, rows, sizeof rows);
    struct texture tx;
    struct err e;
    if (decode(bmp, sizeof bmp, &tx, NULL, &e)) {
        test_fail(t, __FILE__, __LINE__, "%s", e.msg);
        return;
    }
    CHECK(tx.w == 2 && tx.h == 2);
    CHECK(tx.rgba[0] == 255 && tx.rgba[1] == 0 && tx.rgba[2] == 0);        /* top left red */
    CHECK(tx.rgba[8] == 0 && tx.rgba[9] == 0 && tx.rgba[10] == 255);       /* bottom left blue */
    free(tx.rgba);
}

#include <jpeglib.h>

/* issue 25, item 16: a truncated JPEG drew a grey remainder with no word */
TEST(truncated_jpeg_is_a_warning)
{
    /* a 64x64 baseline JPEG written here, cut at half its length */
    struct jpeg_compress_struct c;
    struct jpeg_error_mgr jerr;
    c.err = jpeg_std_error(&jerr);
    jpeg_create_compress(&c);
    unsigned char *buf = NULL;
    unsigned long n = 0;
    jpeg_mem_dest(&c, &buf, &n);
    c.image_width = 64, c.image_height = 64, c.input_components = 3, c.in_color_space = JCS_RGB;
    jpeg_set_defaults(&c);
    jpeg_start_compress(&c, TRUE);
    uint8_t row[64 * 3];
    for (int y = 0; y < 64; y++) {
        for (int x = 0; x < 64 * 3; x++)
            row[x] = (uint8_t)(x * 7 + y * 13);
        JSAMPROW r = row;
        jpeg_write_scanlines(&c, &r, 1);
    }
    jpeg_finish_compress(&c);
    jpeg_destroy_compress(&c);
    struct texture tx;
    struct err e;
    struct warnings w;
    REQUIRE(decode(buf, n, &tx, &w, &e) == 0); /* whole: no warning */
    CHECK_EQ_INT(w.n, 0);
    free(tx.rgba);
    REQUIRE(decode(buf, n / 2, &tx, &w, &e) == 0); /* cut: drawn, and said */
    CHECK(w.n == 1 && strstr(w.msg[0], "t: damaged or truncated JPEG (Premature end of JPEG"));
    free(tx.rgba);
    free(buf);
}

/* issue 25, item 18: the budget was per cache (per scene), so six scenes naming the same six
 * 4096^2 textures held 3.1 GB; now one budget for the process, and a file another cache
 * decoded is shared with it, counted once, not decoded again */
TEST(texture_budget_is_per_process_and_files_are_shared_across_caches)
{
    char a[64], b[64], want_msg[200];
    snprintf(a, sizeof a, "/tmp/rastty-share-a-%d.png", (int)getpid());
    snprintf(b, sizeof b, "/tmp/rastty-share-b-%d.png", (int)getpid());
    static uint8_t grey[256 * 256];
    memset(grey, 200, sizeof grey);
    REQUIRE(stbi_write_png(a, 256, 256, 1, grey, 256) != 0);
    memset(grey, 100, sizeof grey);
    REQUIRE(stbi_write_png(b, 256, 256, 1, grey, 256) != 0);
    size_t one = 0; /* a 256x256 texture and its mips */
    for (size_t side = 256; side >= 1; side /= 2)
        one += side * side * 4;
    size_t before = texture_process_bytes();
    /* room for one and a half textures: two scenes may not hold one each */
    struct texture_cache s1 = {.budget = before + one + one / 2};
    struct texture_cache s2 = {.budget = s1.budget}, s3 = {.budget = s1.budget};
    const struct texture *t1, *t2, *t3;
    struct err e;
    REQUIRE(texture_cache_load(&s1, a, &t1, NULL, &e) == 0);
    CHECK_EQ_INT(texture_process_bytes() - before, one);
    CHECK_EQ_INT(texture_cache_load(&s2, b, &t2, NULL, &e), -1);
    snprintf(want_msg, sizeof want_msg, "%s: texture would pass the %zu MiB texture budget",
             b, s1.budget >> 20);
    CHECK_STR_CONTAINS(e.msg, want_msg);
    /* the same file in another scene: the first scene's texels, counted once */
    REQUIRE(texture_cache_load(&s2, a, &t2, NULL, &e) == 0);
    CHECK(t2->rgba == t1->rgba);
    CHECK_EQ_INT(t2->rgba[0], 200);
    CHECK_EQ_INT(s2.bytes, one);
    CHECK_EQ_INT(texture_process_bytes() - before, one);
    /* the scene that decoded it goes: the texels stay for the other */
    texture_cache_free(&s1);
    CHECK_EQ_INT(texture_process_bytes() - before, one);
    CHECK_EQ_INT(t2->rgba[0], 200);
    REQUIRE(texture_cache_load(&s3, a, &t3, NULL, &e) == 0);
    CHECK(t3->rgba == t2->rgba);
    texture_cache_free(&s2);
    texture_cache_free(&s3);
    CHECK_EQ_INT(texture_process_bytes(), before);
    /* a file rewritten since is decoded again (same inode, new size and time) */
    struct texture_cache s4 = {0}, s5 = {0};
    REQUIRE(texture_cache_load(&s4, a, &t1, NULL, &e) == 0);
    FILE *f = fopen(a, "r+b");
    REQUIRE(f);
    REQUIRE(fseek(f, 0, SEEK_END) == 0 && fputc(0, f) == 0);
    fclose(f);
    struct timespec ts[2] = {{0, UTIME_NOW}, {1, 0}};
    REQUIRE(utimensat(AT_FDCWD, a, ts, 0) == 0);
    REQUIRE(texture_cache_load(&s5, a, &t2, NULL, &e) == 0);
    CHECK(t2->rgba != t1->rgba);
    CHECK_EQ_INT(texture_process_bytes() - before, 2 * one);
    texture_cache_free(&s4);
    texture_cache_free(&s5);
    CHECK_EQ_INT(texture_process_bytes(), before);
    remove(a);
    remove(b);
}

/* a w x h JPEG (a gradient with a checker in blue) in memory; progressive or baseline */
static unsigned char *jpeg_make(int w, int h, bool progressive, unsigned long *n)
{
    struct jpeg_compress_struct c;
    struct jpeg_error_mgr jerr;
    c.err = jpeg_std_error(&jerr);
    jpeg_create_compress(&c);
    unsigned char *buf = NULL;
    *n = 0;
    jpeg_mem_dest(&c, &buf, n);
    c.image_width = (JDIMENSION)w, c.image_height = (JDIMENSION)h;
    c.input_components = 3, c.in_color_space = JCS_RGB;
    jpeg_set_defaults(&c);
    if (progressive)
        jpeg_simple_progression(&c);
    jpeg_start_compress(&c, TRUE);
    uint8_t *row = malloc((size_t)w * 3);
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            row[3 * x] = (uint8_t)(x * 255 / w);
            row[3 * x + 1] = (uint8_t)(y * 255 / h);
            row[3 * x + 2] = ((x / 64 + y / 64) & 1) ? 200 : 0;
        }
        JSAMPROW r = row;
        jpeg_write_scanlines(&c, &r, 1);
    }
    free(row);
    jpeg_finish_compress(&c);
    jpeg_destroy_compress(&c);
    return buf;
}

/* issue 25, item 17: a 16384^2 progressive JPEG was refused ('Backing store not supported':
 * libjpeg keeps all its coefficients, 768 MiB, past the 256 MiB cap) although the README
 * says such images are downscaled. Scaled down here: a 1 MiB cap, a 1024^2 file whose
 * coefficients take 3 MiB */
TEST(progressive_jpeg_gets_the_memory_its_coefficients_need)
{
    unsigned long n, nb;
    unsigned char *prog = jpeg_make(1024, 1024, true, &n);
    unsigned char *base = jpeg_make(1024, 1024, false, &nb);
    struct texture tp, tb;
    struct err e;
    struct warnings w;
    setenv("RASTTY_TEST_JPEG_MEMORY_MIB", "1", 1);
    /* decoded, the same picture as the baseline file's within JPEG's loss */
    if (decode(prog, n, &tp, &w, &e) != 0) {
        test_fail(t, __FILE__, __LINE__, "%s", e.msg);
    } else {
        CHECK_EQ_INT(w.n, 0);
        CHECK(tp.w == 1024 && tp.h == 1024);
        REQUIRE(decode(base, nb, &tb, &w, &e) == 0);
        long worst = 0;
        for (size_t i = 0; i < (size_t)1024 * 1024 * 4; i++) {
            long dv = labs((long)tp.rgba[i] - (long)tb.rgba[i]);
            worst = dv > worst ? dv : worst;
        }
        CHECK(worst < 48);
        CHECK(tp.rgba[((size_t)30 * 1024 + 100) * 4 + 2] > 150); /* the checker's blue */
        free(tb.rgba);
        free(tp.rgba);
    }
    /* more than half of the memory available: one line, the size and the need */
    setenv("RASTTY_TEST_MEMAVAILABLE_MIB", "4", 1);
    CHECK_EQ_INT(decode(prog, n, &tp, &w, &e), -1);
    CHECK(strcmp(e.msg, "t: progressive JPEG of 1024x1024 needs 3 MiB to decode, more than "
                        "half of the 4 MiB of memory available (save it as a baseline JPEG or "
                        "PNG)") == 0);
    setenv("RASTTY_TEST_MEMAVAILABLE_MIB", "8", 1);
    REQUIRE(decode(prog, n, &tp, &w, &e) == 0);
    free(tp.rgba);
    /* a baseline file needs no more than its rows */
    setenv("RASTTY_TEST_MEMAVAILABLE_MIB", "0", 1);
    REQUIRE(decode(base, nb, &tb, &w, &e) == 0);
    free(tb.rgba);
    unsetenv("RASTTY_TEST_MEMAVAILABLE_MIB");
    unsetenv("RASTTY_TEST_JPEG_MEMORY_MIB");
    free(prog);
    free(base);
}
