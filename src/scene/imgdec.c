/* imgdec.c: image decoding with limits (see imgdec.h). Every decoder hands its rows, top
 * to bottom, to one `shrink` sink that box-filters them to the output size, so downscaling
 * is written once and a 16384-pixel image never needs 16384-pixel storage. */
#include "imgdec.h"

#include <math.h>
#include <setjmp.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <jpeglib.h>
#include <png.h>
#include <stb_image.h>

#define JPEG_MAX_SCANS 200               /* progressive JPEGs: more scans is a CPU bomb */
#define JPEG_MAX_MEMORY (256L << 20)     /* libjpeg's own working memory */
/* A progressive JPEG is decoded from all its coefficients at once (2 bytes per pixel and
 * component at full size, whatever the DCT scaling: a 16384^2 4:2:0 file needs 768 MiB,
 * 4:4:4 1.5 GiB), more than JPEG_MAX_MEMORY: its coefficient buffer gets what it needs when
 * half of MemAvailable holds it. Tests scale both down (MiB): */
#define JPEG_MEMORY_ENV "RASTTY_TEST_JPEG_MEMORY_MIB"  /* for JPEG_MAX_MEMORY */
#define MEMAVAILABLE_ENV "RASTTY_TEST_MEMAVAILABLE_MIB" /* for /proc/meminfo's */
#define PNG_MAX_CHUNK (16L << 20)        /* ancillary chunks (iCCP, zTXt, ...) */

/* ---- the row sink: box filter by an integer factor ------------------------------------ */

struct shrink {
    int w, h;      /* input size */
    int f;         /* factor: output pixel = f x f input block (fewer at the edges) */
    int ow, oh;    /* output size: ceil(w/f), ceil(h/f) */
    int row;       /* input rows received */
    uint32_t *acc; /* ow * 4 sums for the output row being built (f > 1) */
    uint8_t *out;  /* ow * oh * 4 */
};

static int shrink_init(struct shrink *s, int w, int h, int max_side)
{
    memset(s, 0, sizeof *s);
    s->w = w;
    s->h = h;
    s->f = 1;
    while ((w + s->f - 1) / s->f > max_side || (h + s->f - 1) / s->f > max_side)
        s->f *= 2;
    s->ow = (w + s->f - 1) / s->f;
    s->oh = (h + s->f - 1) / s->f;
    s->out = malloc((size_t)s->ow * (size_t)s->oh * 4);
    if (s->f > 1)
        s->acc = calloc((size_t)s->ow * 4, sizeof *s->acc);
    return s->out && (s->f == 1 || s->acc) ? 0 : -1;
}

/* one input row of w RGBA texels */
static void shrink_row(struct shrink *s, const uint8_t *rgba)
{
    if (s->row >= s->h)
        return;
    if (s->f == 1) {
        memcpy(s->out + (size_t)s->row * (size_t)s->w * 4, rgba, (size_t)s->w * 4);
        s->row++;
        return;
    }
    const uint8_t *p = rgba;
    uint32_t *a = s->acc;
    for (int ox = 0; ox < s->ow; ox++, a += 4) {
        int n = ox == s->ow - 1 ? s->w - ox * s->f : s->f;
        uint32_t r = 0, g = 0, b = 0, al = 0;
        for (int k = 0; k < n; k++, p += 4) {
            r += p[0];
            g += p[1];
            b += p[2];
            al += p[3];
        }
        a[0] += r;
        a[1] += g;
        a[2] += b;
        a[3] += al;
    }
    s->row++;
    if (s->row % s->f == 0 || s->row == s->h) {
        int oy = (s->row - 1) / s->f, rows = s->row - oy * s->f;
        uint8_t *o = s->out + (size_t)oy * (size_t)s->ow * 4;
        for (int ox = 0; ox < s->ow; ox++) {
            int cols = ox == s->ow - 1 ? s->w - ox * s->f : s->f;
            uint32_t n = (uint32_t)(rows * cols);
            for (int c = 0; c < 4; c++)
                o[ox * 4 + c] = (uint8_t)((s->acc[ox * 4 + c] + n / 2) / n);
        }
        memset(s->acc, 0, (size_t)s->ow * 4 * sizeof *s->acc);
    }
}

static void shrink_free(struct shrink *s)
{
    free(s->acc);
    free(s->out);
    memset(s, 0, sizeof *s);
}

/* Hand the finished image over (every decoder delivers all h rows before calling this).
 * (file_w, file_h) is the size in the file, for the downscale warning. */
static void shrink_finish(struct shrink *s, struct imgdec_image *out, const char *name,
                          int file_w, int file_h, int max_side, struct warnings *w)
{
    free(s->acc);
    s->acc = NULL;
    out->w = s->ow;
    out->h = s->oh;
    out->rgba = s->out;
    s->out = NULL;
    if (out->w != file_w || out->h != file_h)
        warn_add(w, "%s: %dx%d image downscaled to %dx%d (limit %d per side)", name, file_w,
                 file_h, out->w, out->h, max_side);
}

static int too_big(const char *name, int w, int h, struct err *e)
{
    if (w < 1 || h < 1)
        return err_set(e, "%s: image is %dx%d", name, w, h);
    if (w > IMGDEC_MAX_INPUT || h > IMGDEC_MAX_INPUT)
        return err_set(e, "%s: image is %dx%d (limit %d per side)", name, w, h,
                       IMGDEC_MAX_INPUT);
    return 0;
}

static int oom(const char *name, struct err *e)
{
    return err_set(e, "%s: out of memory", name);
}

/* ---- PNG (libpng) ---------------------------------------------------------------------- */

struct png_ctx {
    const uint8_t *data;
    size_t len, pos;
    char msg[200];
    /* owned while decoding; freed after a longjmp too */
    uint8_t *row;
    uint8_t *whole;
    struct shrink sh;
};

static void png_on_error(png_structp png, png_const_charp msg)
{
    struct png_ctx *c = png_get_error_ptr(png);
    err_quote(msg, strlen(msg), 150, c->msg, sizeof c->msg);
    png_longjmp(png, 1);
}

static void png_on_warning(png_structp png, png_const_charp msg)
{
    (void)png;
    (void)msg; /* libpng's warnings (bad ancillary chunks) are not ours to print */
}

static void png_read_mem(png_structp png, png_bytep out, size_t n)
{
    struct png_ctx *c = png_get_io_ptr(png);
    if (n > c->len - c->pos)
        png_error(png, "file is truncated");
    memcpy(out, c->data + c->pos, n);
    c->pos += n;
}

/* Every chunk's length must fit in the file: libpng allocates what a chunk header claims
 * before reading it (a 65-byte file with a tEXt chunk of 1.9 GB cost 1.9 GB). */
static int png_chunks_fit(const uint8_t *d, size_t len, const char *name, struct err *e)
{
    for (size_t off = 8; off + 8 <= len;) {
        uint32_t n = (uint32_t)d[off] << 24 | (uint32_t)d[off + 1] << 16 |
                     (uint32_t)d[off + 2] << 8 | d[off + 3];
        if (n > len - off - 8 || len - off - 8 - n < 4)
            return err_set(e, "%s: byte %zu: PNG chunk of %u bytes, %zu left in the file: "
                              "truncated",
                           name, off, n, len - off - 8);
        if (memcmp(d + off + 4, "IEND", 4) == 0)
            break;
        off += 12 + (size_t)n;
    }
    return 0;
}

static int decode_png(const uint8_t *data, size_t len, const char *name, int max_side,
                      struct imgdec_image *out, struct warnings *w, struct err *e)
{
    if (png_chunks_fit(data, len, name, e))
        return -1;
    struct png_ctx *c = calloc(1, sizeof *c);
    if (!c)
        return oom(name, e);
    c->data = data;
    c->len = len;
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, c, png_on_error,
                                             png_on_warning);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    if (!info) {
        png_destroy_read_struct(&png, NULL, NULL);
        free(c);
        return oom(name, e);
    }
    int rc = -1;
    if (setjmp(png_jmpbuf(png))) {
        err_set(e, "%s: bad PNG (%s)", name, c->msg);
        goto done;
    }
    png_set_user_limits(png, IMGDEC_MAX_INPUT, IMGDEC_MAX_INPUT);
#ifdef PNG_IGNORE_ADLER32
    /* every IDAT chunk's CRC is still checked (a corrupt file is still refused); zlib's
     * second checksum over the inflated bytes was 9% of loading lost_empire */
    png_set_option(png, PNG_IGNORE_ADLER32, PNG_OPTION_ON);
#endif
    png_set_chunk_malloc_max(png, PNG_MAX_CHUNK);
    png_set_read_fn(png, c, png_read_mem);
    png_read_info(png, info);
    png_uint_32 pw, ph;
    int depth, type, interlace;
    png_get_IHDR(png, info, &pw, &ph, &depth, &type, &interlace, NULL, NULL);
    if (too_big(name, (int)pw, (int)ph, e))
        goto done;
    int iw = (int)pw, ih = (int)ph;
    /* everything to 8-bit RGBA */
    png_set_expand(png); /* palette -> RGB, gray < 8 bits -> 8, tRNS -> alpha */
    png_set_strip_16(png);
    if (type == PNG_COLOR_TYPE_GRAY || type == PNG_COLOR_TYPE_GRAY_ALPHA)
        png_set_gray_to_rgb(png);
    png_set_add_alpha(png, 0xff, PNG_FILLER_AFTER); /* no effect when alpha exists */
    int passes = png_set_interlace_handling(png);
    png_read_update_info(png, info);
    if (png_get_rowbytes(png, info) != (size_t)iw * 4) {
        err_set(e, "%s: bad PNG (unexpected row layout)", name);
        goto done;
    }
    if (passes > 1 && (iw > IMGDEC_MAX_WHOLE || ih > IMGDEC_MAX_WHOLE)) {
        err_set(e, "%s: interlaced PNG of %dx%d (interlaced images are limited to %d per side)",
                name, iw, ih, IMGDEC_MAX_WHOLE);
        goto done;
    }
    if (shrink_init(&c->sh, iw, ih, max_side)) {
        oom(name, e);
        goto done;
    }
    if (passes > 1) { /* the passes fill the whole image in turn */
        c->whole = malloc((size_t)iw * (size_t)ih * 4);
        png_bytep *rows = c->whole ? malloc((size_t)ih * sizeof *rows) : NULL;
        if (!rows) {
            oom(name, e);
            goto done;
        }
        for (int y = 0; y < ih; y++)
            rows[y] = c->whole + (size_t)y * (size_t)iw * 4;
        c->row = (uint8_t *)rows; /* freed with the context even after a longjmp */
        png_read_image(png, rows);
        for (int y = 0; y < ih; y++)
            shrink_row(&c->sh, rows[y]);
    } else {
        c->row = malloc((size_t)iw * 4);
        if (!c->row) {
            oom(name, e);
            goto done;
        }
        for (int y = 0; y < ih; y++) {
            png_read_row(png, c->row, NULL);
            shrink_row(&c->sh, c->row);
        }
    }
    shrink_finish(&c->sh, out, name, iw, ih, max_side, w);
    rc = 0;
done:
    png_destroy_read_struct(&png, &info, NULL);
    free(c->row);
    free(c->whole);
    shrink_free(&c->sh);
    free(c);
    return rc;
}

/* ---- JPEG (libjpeg-turbo) -------------------------------------------------------------- */

struct jpeg_ctx {
    struct jpeg_error_mgr err;
    struct jpeg_progress_mgr progress;
    jmp_buf jb;
    char msg[JMSG_LENGTH_MAX];
    char warning[160]; /* libjpeg's first warning (a corrupt or truncated file), quoted */
    uint8_t *row;
    struct shrink sh;
};

static void jpeg_on_error(j_common_ptr cinfo)
{
    struct jpeg_ctx *c = (struct jpeg_ctx *)cinfo->err;
    char buf[JMSG_LENGTH_MAX];
    cinfo->err->format_message(cinfo, buf);
    err_quote(buf, strlen(buf), 150, c->msg, sizeof c->msg);
    longjmp(c->jb, 1);
}

static void jpeg_on_output(j_common_ptr cinfo)
{
    /* libjpeg would print its warnings to stderr: the first is kept, said as ours */
    struct jpeg_ctx *c = (struct jpeg_ctx *)cinfo->err;
    if (!c->warning[0]) {
        char buf[JMSG_LENGTH_MAX];
        cinfo->err->format_message(cinfo, buf);
        err_quote(buf, strlen(buf), 120, c->warning, sizeof c->warning);
    }
}

static void jpeg_on_progress(j_common_ptr cinfo)
{
    struct jpeg_ctx *c = (struct jpeg_ctx *)cinfo->err;
    j_decompress_ptr d = (j_decompress_ptr)cinfo;
    if (d->input_scan_number > JPEG_MAX_SCANS) {
        snprintf(c->msg, sizeof c->msg, "more than %d progressive scans", JPEG_MAX_SCANS);
        longjmp(c->jb, 1);
    }
}

/* a test's value in MiB from the environment, else dflt (bytes) */
static long long env_mib(const char *var, long long dflt)
{
    const char *v = getenv(var);
    char *end;
    long long n = v && *v ? strtoll(v, &end, 10) : -1;
    return n >= 0 && v && *end == '\0' && n < (1LL << 40) ? n << 20 : dflt;
}

/* MemAvailable in bytes (the kernel's estimate of what can be allocated without swapping);
 * -1 when unknown */
static long long mem_available(void)
{
    long long test = env_mib(MEMAVAILABLE_ENV, -1);
    if (test >= 0)
        return test;
    FILE *f = fopen("/proc/meminfo", "r");
    if (!f)
        return -1;
    char line[128];
    long long kb = -1;
    while (fgets(line, sizeof line, f))
        if (sscanf(line, "MemAvailable: %lld kB", &kb) == 1)
            break;
    fclose(f);
    return kb >= 0 ? kb * 1024 : -1;
}

/* The bytes of a progressive JPEG's coefficient buffer (libjpeg's whole-image virtual
 * arrays: each component's blocks, rounded up to its sampling factors, 128 bytes each) */
static long long jpeg_coef_bytes(const struct jpeg_decompress_struct *d)
{
    int mh = 1, mv = 1;
    for (int i = 0; i < d->num_components; i++) {
        mh = d->comp_info[i].h_samp_factor > mh ? d->comp_info[i].h_samp_factor : mh;
        mv = d->comp_info[i].v_samp_factor > mv ? d->comp_info[i].v_samp_factor : mv;
    }
    long long n = 0;
    for (int i = 0; i < d->num_components; i++) {
        long long h = d->comp_info[i].h_samp_factor, v = d->comp_info[i].v_samp_factor;
        long long bw = ((long long)d->image_width * h + mh * 8 - 1) / (mh * 8);
        long long bh = ((long long)d->image_height * v + mv * 8 - 1) / (mv * 8);
        bw = (bw + h - 1) / h * h;
        bh = (bh + v - 1) / v * v;
        n += bw * bh * (long long)sizeof(JBLOCK);
    }
    return n;
}

static int decode_jpeg(const uint8_t *data, size_t len, const char *name, int max_side,
                       struct imgdec_image *out, struct warnings *w, struct err *e)
{
    struct jpeg_ctx *c = calloc(1, sizeof *c);
    struct jpeg_decompress_struct *d = calloc(1, sizeof *d);
    if (!c || !d) {
        free(c);
        free(d);
        return oom(name, e);
    }
    d->err = jpeg_std_error(&c->err);
    c->err.error_exit = jpeg_on_error;
    c->err.output_message = jpeg_on_output;
    int rc = -1;
    if (setjmp(c->jb)) {
        err_set(e, "%s: bad JPEG (%s)", name, c->msg);
        goto done;
    }
    jpeg_create_decompress(d);
    long long base = env_mib(JPEG_MEMORY_ENV, JPEG_MAX_MEMORY);
    d->mem->max_memory_to_use = (long)base;
    c->progress.progress_monitor = jpeg_on_progress;
    d->progress = &c->progress;
    jpeg_mem_src(d, data, (unsigned long)len);
    jpeg_read_header(d, TRUE);
    int iw = (int)d->image_width, ih = (int)d->image_height;
    if (too_big(name, iw, ih, e))
        goto done;
    /* (a baseline file whose components come in scans of their own needs them all too) */
    if (d->progressive_mode || d->comps_in_scan < d->num_components) {
        long long coef = jpeg_coef_bytes(d);
        if (coef > base / 2) { /* (the rest of the working memory stays as it was) */
            long long avail = mem_available();
            if (avail >= 0 && coef > avail / 2) {
                err_set(e, "%s: %s JPEG of %dx%d needs %lld MiB to decode, more than half of "
                           "the %lld MiB of memory available (save it as a baseline JPEG or "
                           "PNG)",
                        name, d->progressive_mode ? "progressive" : "multi-scan", iw, ih, (coef + (1 << 20) - 1) >> 20, avail >> 20);
                goto done;
            }
            d->mem->max_memory_to_use = (long)(coef + base);
        }
    }
    /* let the decoder scale by 1/2, 1/4, 1/8 (cheap: fewer DCT coefficients); the box
     * filter does the rest */
    unsigned denom = 1, mw = (unsigned)max_side;
    while (denom < 8 && (((unsigned)iw + denom - 1) / denom > mw ||
                         ((unsigned)ih + denom - 1) / denom > mw))
        denom *= 2;
    d->scale_num = 1;
    d->scale_denom = denom;
    bool cmyk = d->jpeg_color_space == JCS_CMYK || d->jpeg_color_space == JCS_YCCK;
    d->out_color_space = cmyk ? JCS_CMYK : JCS_EXT_RGBA;
    jpeg_start_decompress(d);
    int ow = (int)d->output_width, oh = (int)d->output_height;
    if (ow < 1 || oh < 1 || shrink_init(&c->sh, ow, oh, max_side) ||
        !(c->row = malloc((size_t)ow * 4))) {
        oom(name, e);
        goto done;
    }
    bool inverted = cmyk && d->saw_Adobe_marker; /* Adobe stores CMYK inverted */
    while (d->output_scanline < d->output_height) {
        JSAMPROW r = c->row;
        if (jpeg_read_scanlines(d, &r, 1) != 1)
            break;
        if (cmyk)
            for (int x = 0; x < ow; x++) {
                uint8_t *p = c->row + 4 * x;
                int k = inverted ? p[3] : 255 - p[3];
                for (int ch = 0; ch < 3; ch++) {
                    int v = inverted ? p[ch] : 255 - p[ch];
                    p[ch] = (uint8_t)((v * k + 127) / 255);
                }
                p[3] = 255;
            }
        shrink_row(&c->sh, c->row);
    }
    if (c->sh.row != oh) {
        err_set(e, "%s: bad JPEG (scanlines missing)", name);
        goto done;
    }
    jpeg_finish_decompress(d);
    /* a truncated or damaged file decodes with a grey remainder: said, not silent */
    if (c->err.num_warnings > 0)
        warn_add(w, "%s: damaged or truncated JPEG (%s): part of the image is grey", name,
                 c->warning[0] ? c->warning : "libjpeg warned");
    shrink_finish(&c->sh, out, name, iw, ih, max_side, w);
    rc = 0;
done:
    jpeg_destroy_decompress(d);
    free(c->row);
    shrink_free(&c->sh);
    free(c);
    free(d);
    return rc;
}

/* ---- PNM P5/P6 (own) ------------------------------------------------------------------- */

/* header field: skip whitespace and # comments, read a decimal number */
static int pnm_field(const uint8_t *d, size_t len, size_t *pos, long *out)
{
    size_t i = *pos;
    for (;;) {
        while (i < len && (d[i] == ' ' || d[i] == '\t' || d[i] == '\r' || d[i] == '\n' ||
                           d[i] == '\v' || d[i] == '\f'))
            i++;
        if (i < len && d[i] == '#') {
            while (i < len && d[i] != '\n')
                i++;
            continue;
        }
        break;
    }
    if (i >= len || d[i] < '0' || d[i] > '9')
        return -1;
    long v = 0;
    while (i < len && d[i] >= '0' && d[i] <= '9') {
        if (v > 1000000)
            return -1;
        v = v * 10 + (d[i++] - '0');
    }
    *pos = i;
    *out = v;
    return 0;
}

static int decode_pnm(const uint8_t *d, size_t len, const char *name, int max_side,
                      struct imgdec_image *out, struct warnings *w, struct err *e)
{
    if (len < 2 || d[0] != 'P' || (d[1] != '5' && d[1] != '6'))
        return err_set(e, "%s: PNM variant P%c is not supported (only binary P5 and P6)", name,
                       len > 1 && d[1] >= '1' && d[1] <= '7' ? d[1] : '?');
    size_t pos = 2;
    long iw, ih, maxval;
    if (pnm_field(d, len, &pos, &iw) || pnm_field(d, len, &pos, &ih) ||
        pnm_field(d, len, &pos, &maxval))
        return err_set(e, "%s: bad PNM header", name);
    if (pos >= len || !(d[pos] == ' ' || d[pos] == '\t' || d[pos] == '\r' || d[pos] == '\n'))
        return err_set(e, "%s: bad PNM header", name);
    pos++; /* exactly one whitespace byte before the pixels */
    if (maxval < 1 || maxval > 65535)
        return err_set(e, "%s: bad PNM maximum value %ld (1..65535)", name, maxval);
    if (too_big(name, (int)iw, (int)ih, e))
        return -1;
    int ch = d[1] == '6' ? 3 : 1, bytes = maxval > 255 ? 2 : 1;
    size_t need = (size_t)iw * (size_t)ih * (size_t)(ch * bytes);
    if (len - pos < need)
        return err_set(e, "%s: truncated PNM: %zu bytes of pixels, %ldx%ld needs %zu", name,
                       len - pos, iw, ih, need);
    struct shrink sh;
    uint8_t *row = malloc((size_t)iw * 4);
    if (!row || shrink_init(&sh, (int)iw, (int)ih, max_side)) {
        free(row);
        shrink_free(&sh);
        return oom(name, e);
    }
    const uint8_t *p = d + pos;
    for (long y = 0; y < ih; y++) {
        for (long x = 0; x < iw; x++) {
            for (int c = 0; c < ch; c++) {
                unsigned v = bytes == 2 ? (unsigned)p[0] << 8 | p[1] : p[0];
                p += bytes;
                if (v > (unsigned)maxval)
                    v = (unsigned)maxval;
                row[x * 4 + c] = (uint8_t)((v * 255u + (unsigned)maxval / 2) / (unsigned)maxval);
            }
            if (ch == 1)
                row[x * 4 + 1] = row[x * 4 + 2] = row[x * 4];
            row[x * 4 + 3] = 255;
        }
        shrink_row(&sh, row);
    }
    free(row);
    shrink_finish(&sh, out, name, (int)iw, (int)ih, max_side, w);
    return 0;
}

/* ---- Radiance HDR / RGBE (own) --------------------------------------------------------- */

static uint8_t tone_map(float x)
{
    x = x > 0 ? x / (1.0f + x) : 0; /* Reinhard */
    return (uint8_t)(powf(x, 1.0f / 2.2f) * 255.0f + 0.5f);
}

static void rgbe_to_rgba(const uint8_t *rgbe, int n, uint8_t *rgba)
{
    for (int i = 0; i < n; i++) {
        const uint8_t *p = rgbe + 4 * i;
        for (int c = 0; c < 3; c++)
            rgba[4 * i + c] = p[3] ? tone_map(ldexpf((float)p[c], p[3] - (128 + 8))) : 0;
        rgba[4 * i + 3] = 255;
    }
}

/* One scanline of w pixels into rgbe (w*4); returns bytes consumed, or 0 if malformed. */
static size_t hdr_scanline(const uint8_t *d, size_t left, int w, uint8_t *rgbe)
{
    /* new-style RLE: 2 2 hi lo, then each of the 4 components as runs */
    if (w >= 8 && w < 32768 && left >= 4 && d[0] == 2 && d[1] == 2 && !(d[2] & 0x80)) {
        if ((d[2] << 8 | d[3]) != w)
            return 0;
        size_t i = 4;
        for (int c = 0; c < 4; c++) {
            int x = 0;
            while (x < w) {
                if (i >= left)
                    return 0;
                int count = d[i++];
                if (count > 128) { /* a run of one value */
                    count -= 128;
                    if (count > w - x || i >= left)
                        return 0;
                    for (int k = 0; k < count; k++)
                        rgbe[4 * (x + k) + c] = d[i];
                    i++;
                } else { /* count literal values; 0 is invalid (stb loops forever on it) */
                    if (count == 0 || count > w - x || left - i < (size_t)count)
                        return 0;
                    for (int k = 0; k < count; k++)
                        rgbe[4 * (x + k) + c] = d[i + (size_t)k];
                    i += (size_t)count;
                }
                x += count;
            }
        }
        return i;
    }
    /* flat: w pixels of 4 bytes */
    if (left / 4 < (size_t)w)
        return 0;
    memcpy(rgbe, d, (size_t)w * 4);
    return (size_t)w * 4;
}

static int decode_hdr(const uint8_t *d, size_t len, const char *name, int max_side,
                      struct imgdec_image *out, struct warnings *w, struct err *e)
{
    /* header lines until an empty line; FORMAT must be 32-bit_rle_rgbe if given */
    size_t pos = 0;
    bool blank = false;
    while (pos < len && !blank) {
        const uint8_t *nl = memchr(d + pos, '\n', len - pos);
        if (!nl)
            return err_set(e, "%s: truncated HDR header", name);
        size_t n = (size_t)(nl - (d + pos));
        if (n >= 7 && memcmp(d + pos, "FORMAT=", 7) == 0 &&
            !(n >= 22 && memcmp(d + pos + 7, "32-bit_rle_rgbe", 15) == 0))
            return err_set(e, "%s: HDR format is not 32-bit_rle_rgbe (XYZE is not supported)",
                           name);
        blank = n == 0;
        pos += n + 1;
    }
    /* resolution: "-Y H +X W" (the usual orientation; others are refused) */
    const uint8_t *nl = pos < len ? memchr(d + pos, '\n', len - pos) : NULL;
    char line[64];
    size_t n = nl ? (size_t)(nl - (d + pos)) : 0;
    if (!nl || n >= sizeof line)
        return err_set(e, "%s: bad HDR resolution line", name);
    memcpy(line, d + pos, n);
    line[n] = '\0';
    int iw, ih, used = 0;
    if (sscanf(line, "-Y %d +X %d%n", &ih, &iw, &used) != 2 || (size_t)used != n)
        return err_set(e, "%s: unsupported HDR orientation (only -Y H +X W)", name);
    if (too_big(name, iw, ih, e))
        return -1;
    pos += n + 1;
    /* the smallest possible scanline is 4 + 4*2*ceil(w/128) bytes (RLE): a file too short
     * for that many rows is truncated, whatever the encoding */
    size_t min_line = iw >= 8 ? 4 + 8 * (size_t)((iw + 127) / 128) : (size_t)iw * 4;
    if ((len - pos) / (size_t)ih < min_line)
        return err_set(e, "%s: truncated HDR: %zu bytes of pixels cannot hold %dx%d", name,
                       len - pos, iw, ih);
    struct shrink sh;
    uint8_t *rgbe = malloc((size_t)iw * 4), *rgba = malloc((size_t)iw * 4);
    if (!rgbe || !rgba || shrink_init(&sh, iw, ih, max_side)) {
        free(rgbe);
        free(rgba);
        shrink_free(&sh);
        return oom(name, e);
    }
    int rc = 0;
    for (int y = 0; y < ih; y++) {
        size_t used_bytes = hdr_scanline(d + pos, len - pos, iw, rgbe);
        if (!used_bytes) {
            rc = err_set(e, "%s: bad or truncated HDR scanline %d", name, y);
            break;
        }
        pos += used_bytes;
        rgbe_to_rgba(rgbe, iw, rgba);
        shrink_row(&sh, rgba);
    }
    free(rgbe);
    free(rgba);
    if (rc) {
        shrink_free(&sh);
        return -1;
    }
    shrink_finish(&sh, out, name, iw, ih, max_side, w);
    return 0;
}

/* ---- TGA, BMP, PSD, GIF (stb_image, after checks) -------------------------------------- */

/* The fewest bytes a file of px pixels can take: TGA RLE packets hold at most 128 pixels
 * (1 byte + 1 pixel), BMP RLE at most 255 per 2 bytes, PSD PackBits 128 bytes per 2 per
 * channel (at least 1 channel), GIF's LZW at most 4096 pixels per 12-bit code. */
static size_t stb_min_bytes(const uint8_t *d, size_t len, const char *kind, size_t px)
{
    if (strcmp(kind, "TGA") == 0 && len >= 18 && d[2] >= 9) {
        size_t bpp = (size_t)(d[16] + 7) / 8;
        return 18 + (px + 127) / 128 * (1 + bpp);
    }
    if (strcmp(kind, "BMP") == 0)
        return 26 + (px + 254) / 255 * 2;
    if (strcmp(kind, "PSD") == 0)
        return 26 + (px + 127) / 128 * 2;
    if (strcmp(kind, "GIF") == 0)
        return 13 + (px + 4095) / 4096 * 3 / 2;
    return 0;
}

/* The checks of a format decoded whole (stb's, and TGA): its size, and a file long enough
 * for that size even at the format's best compression, so a few hundred bytes cannot ask
 * for 16 million decoded pixels. */
static int whole_image_checks(const uint8_t *d, size_t len, const char *kind, const char *name,
                              int iw, int ih, struct err *e)
{
    if (too_big(name, iw, ih, e))
        return -1;
    if (iw > IMGDEC_MAX_WHOLE || ih > IMGDEC_MAX_WHOLE)
        return err_set(e, "%s: %s of %dx%d (%s images are limited to %d per side; PNG and JPEG "
                          "are downscaled)",
                       name, kind, iw, ih, kind, IMGDEC_MAX_WHOLE);
    size_t need = stb_min_bytes(d, len, kind, (size_t)iw * (size_t)ih);
    if (len < need)
        return err_set(e, "%s: %s of %dx%d cannot fit in %zu bytes (at least %zu): truncated",
                       name, kind, iw, ih, len, need);
    return 0;
}

static int decode_stb(const uint8_t *d, size_t len, const char *kind, const char *name,
                      int max_side, struct imgdec_image *out, struct warnings *w, struct err *e)
{
    if (len > (size_t)INT32_MAX)
        return err_set(e, "%s: file too large", name);
    int iw, ih, n;
    if (!stbi_info_from_memory(d, (int)len, &iw, &ih, &n))
        return err_set(e, "%s: not a readable image (%s)", name, stbi_failure_reason());
    if (ih < 0 && strcmp(kind, "BMP") == 0)
        ih = -ih; /* a top-down BMP (rows stored top first): stb's info gives its height
                     negative, as the file stores it, and decodes it upright */
    if (whole_image_checks(d, len, kind, name, iw, ih, e))
        return -1;
    /* stb "removes the white matte" of PSDs with 4+ channels by dividing by alpha and
     * casting out-of-range floats to bytes (undefined behaviour, found by fuzz_texture) */
    if (strcmp(kind, "PSD") == 0 && len >= 14 && (d[12] << 8 | d[13]) >= 4)
        return err_set(e, "%s: PSD with an alpha channel (%d channels) is not supported", name,
                       d[12] << 8 | d[13]);
    /* stb tries its decoders in turn: make sure it takes the one we checked */
    if (stbi_is_hdr_from_memory(d, (int)len))
        return err_set(e, "%s: not a readable image", name);
    int dw, dh;
    uint8_t *px = stbi_load_from_memory(d, (int)len, &dw, &dh, &n, 4);
    if (!px)
        return err_set(e, "%s: cannot decode %s (%s)", name, kind, stbi_failure_reason());
    int rc = 0;
    struct shrink sh;
    if (dw != iw || dh != ih) {
        rc = err_set(e, "%s: cannot decode %s (size changed)", name, kind);
    } else if (shrink_init(&sh, iw, ih, max_side)) {
        shrink_free(&sh);
        rc = oom(name, e);
    } else {
        for (int y = 0; y < ih; y++)
            shrink_row(&sh, px + (size_t)y * (size_t)iw * 4);
        shrink_finish(&sh, out, name, iw, ih, max_side, w);
    }
    stbi_image_free(px);
    return rc;
}

/* TGA of the common kinds, ours: true colour (24 or 32 bits) or grey (8 bits), raw or RLE,
 * either row order. stb's decoder took 116 instructions a pixel on a 1024x1024 RLE texture
 * (a third of loading the head model) and a second copy of the image; this one writes each
 * pixel once, in its place. The others (colour-mapped, 15/16 bits, right-to-left) go to
 * stb. Bytes: what stb gives (BGR(A) as RGB(A), alpha 255 without one; grey g,g,g,255). */
static int decode_tga(const uint8_t *d, size_t len, const char *name, int max_side,
                      struct imgdec_image *out, struct warnings *w, struct err *e)
{
    const int type = d[2], bits = d[16], desc = d[17];
    const int iw = d[12] | d[13] << 8, ih = d[14] | d[15] << 8;
    const bool grey = type == 3 || type == 11, rle = type >= 9;
    if (d[1] != 0 || !(type == 2 || type == 3 || type == 10 || type == 11) || (desc & 0x10) ||
        (grey ? bits != 8 : bits != 24 && bits != 32))
        return decode_stb(d, len, "TGA", name, max_side, out, w, e);
    /* (a raw TGA's length: tga_plausible) */
    if (whole_image_checks(d, len, "TGA", name, iw, ih, e))
        return -1;
    const size_t bpp = (size_t)bits / 8, npx = (size_t)iw * (size_t)ih;
    uint8_t *img = malloc(npx * 4); /* top row first */
    if (!img)
        return oom(name, e);
    const bool bottom_up = !(desc & 0x20);
    size_t pos = 18 + (size_t)d[0], x = 0, r = 0; /* file order: row r, column x */
    uint8_t *p = img + (bottom_up ? (size_t)(ih - 1) : 0) * (size_t)iw * 4;
    for (size_t i = 0; i < npx;) {
        size_t n = npx - i; /* a raw image is one raw packet */
        bool repeat = false;
        if (rle) {
            if (pos >= len)
                break;
            n = (size_t)(d[pos] & 0x7f) + 1;
            repeat = d[pos++] & 0x80;
            n = n < npx - i ? n : npx - i;
        }
        if (len - pos < (repeat ? 1 : n) * bpp)
            break;
        for (size_t k = 0; k < n; k++) {
            const uint8_t *s = d + pos + (repeat ? 0 : k * bpp);
            if (grey)
                p[0] = p[1] = p[2] = s[0], p[3] = 255;
            else
                p[0] = s[2], p[1] = s[1], p[2] = s[0], p[3] = bpp == 4 ? s[3] : 255;
            p += 4;
            if (++x == (size_t)iw) { /* the next row in the file */
                x = 0;
                if (++r < (size_t)ih)
                    p = img + (bottom_up ? (size_t)ih - 1 - r : r) * (size_t)iw * 4;
            }
        }
        pos += (repeat ? 1 : n) * bpp;
        i += n;
    }
    if (r < (size_t)ih) {
        free(img);
        return err_set(e, "%s: TGA pixel data ends at row %zu of %d: truncated", name, r, ih);
    }
    struct shrink sh;
    if (shrink_init(&sh, iw, ih, max_side)) {
        shrink_free(&sh);
        free(img);
        return oom(name, e);
    }
    if (sh.f == 1) { /* the image as it is: no copy */
        free(sh.out);
        sh.out = img;
        img = NULL;
        sh.row = ih;
    } else {
        for (int y = 0; y < ih; y++)
            shrink_row(&sh, img + (size_t)y * (size_t)iw * 4);
    }
    free(img);
    shrink_finish(&sh, out, name, iw, ih, max_side, w);
    return 0;
}

/* TGA has no magic: a plausible header (image type, colour map, depth) */
static bool tga_plausible(const uint8_t *d, size_t len)
{
    if (len < 18)
        return false;
    int cmap = d[1], type = d[2], bpp = d[16];
    if (cmap > 1)
        return false;
    if (!(type == 1 || type == 2 || type == 3 || type == 9 || type == 10 || type == 11))
        return false;
    if ((type == 1 || type == 9) != (cmap == 1))
        return false;
    if (!(bpp == 8 || bpp == 15 || bpp == 16 || bpp == 24 || bpp == 32))
        return false;
    int w = d[12] | d[13] << 8, h = d[14] | d[15] << 8;
    if (w < 1 || h < 1)
        return false;
    /* uncompressed: the file must hold the pixels */
    if (type <= 3) {
        size_t cmap_bytes = cmap ? (size_t)(d[5] | d[6] << 8) * (size_t)((d[7] + 7) / 8) : 0;
        size_t need = 18 + (size_t)d[0] + cmap_bytes + (size_t)w * (size_t)h * (size_t)((bpp + 7) / 8);
        if (len < need)
            return false;
    }
    return true;
}

/* ---- dispatch -------------------------------------------------------------------------- */

enum kind { K_NONE, K_PNG, K_JPEG, K_PNM, K_PNM_OTHER, K_HDR, K_GIF, K_BMP, K_PSD, K_PIC };

static enum kind sniff(const uint8_t *d, size_t n)
{
#define HAS(s) (n >= sizeof s - 1 && memcmp(d, s, sizeof s - 1) == 0)
    if (HAS("\x89PNG\r\n\x1a\n"))
        return K_PNG;
    if (HAS("\xff\xd8\xff"))
        return K_JPEG;
    if (HAS("GIF87a") || HAS("GIF89a"))
        return K_GIF;
    if (HAS("8BPS"))
        return K_PSD;
    if (HAS("#?RADIANCE\n") || HAS("#?RGBE\n"))
        return K_HDR;
    if (HAS("S\x80\xf6\x34"))
        return K_PIC;
    if (n >= 3 && d[0] == 'P' && (d[1] == '5' || d[1] == '6') &&
        (d[2] == ' ' || d[2] == '\t' || d[2] == '\r' || d[2] == '\n' || d[2] == '#'))
        return K_PNM;
    if (n >= 3 && d[0] == 'P' && ((d[1] >= '1' && d[1] <= '4') || d[1] == '7' || d[1] == 'F' ||
                                  d[1] == 'f') &&
        (d[2] == ' ' || d[2] == '\r' || d[2] == '\n'))
        return K_PNM_OTHER;
    if (n >= 26 && d[0] == 'B' && d[1] == 'M')
        return K_BMP;
#undef HAS
    return K_NONE;
}

static const char *const kind_names[] = {NULL,          "PNG image", "JPEG image", "PNM image",
                                         "PNM image",   "HDR image", "GIF image",  "BMP image",
                                         "PSD image",   "Softimage PIC image"};

const char *imgdec_kind(const uint8_t *data, size_t len)
{
    return kind_names[sniff(data, len)];
}

int imgdec_decode(const uint8_t *data, size_t len, const char *name, int max_side,
                  struct imgdec_image *out, struct warnings *w, struct err *e)
{
    memset(out, 0, sizeof *out);
    if (max_side < 1)
        max_side = 1;
    switch (sniff(data, len)) {
    case K_PNG: return decode_png(data, len, name, max_side, out, w, e);
    case K_JPEG: return decode_jpeg(data, len, name, max_side, out, w, e);
    case K_PNM:
    case K_PNM_OTHER: return decode_pnm(data, len, name, max_side, out, w, e);
    case K_HDR: return decode_hdr(data, len, name, max_side, out, w, e);
    case K_GIF: return decode_stb(data, len, "GIF", name, max_side, out, w, e);
    case K_BMP: return decode_stb(data, len, "BMP", name, max_side, out, w, e);
    case K_PSD: return decode_stb(data, len, "PSD", name, max_side, out, w, e);
    case K_PIC: return err_set(e, "%s: Softimage PIC images are not supported", name);
    case K_NONE: break;
    }
    if (tga_plausible(data, len))
        return decode_tga(data, len, name, max_side, out, w, e);
    return err_set(e, "%s: not a readable image (PNG, JPEG, TGA, BMP, GIF, PSD, PNM or HDR)",
                   name);
}
