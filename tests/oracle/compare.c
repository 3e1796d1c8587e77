/* compare.c: the oracle's image comparison — one tested render against one reference render.
 *
 *   compare [--name NAME] [--magenta] [--exact] [--diff OUT.png] [--list N] [--reduce K]
 *           [--psnr-bar DB] [--diff8-bar F] TEST.ppm TEST.pfm REF.ppm REF.pfm
 *
 * Colour images are PPM or PNG (anything stb_image reads), depth is PFM ("Pf", rows
 * bottom-to-top, 1.0 where nothing was drawn). Prints ONE line:
 *   NAME WxH cov=N/BAR diff8=N/BAR maxdiff=N psnr=DB [enclosed=N ref=N] PASS|FAIL(...)
 *   cov      pixels covered (depth < 1) in exactly one of the two renders
 *   diff8    pixels whose colour differs by more than 8 levels in some channel
 *   maxdiff  largest per-channel difference over the image
 *   psnr     over all pixels and channels, 255 peak ("inf" when identical)
 *   enclosed (--magenta) background-magenta pixels of TEST not 4-connected to the image
 *            border through magenta: holes inside the silhouette (cracks); ref = the same
 *            count for REF (a sanity check of the scene, not judged)
 * Bars: cov <= min(10, 0.02% of the pixels), diff8 <= 0.05% of the pixels, psnr >= 45 dB,
 * enclosed == 0. --exact: no pixel may differ at all (tie-rule scenes).
 * --reduce K: REF was drawn K times larger on each side (the ideal image's check: Mesa at 8x
 * against rastty --ssaa 8); it is box-filtered down first, as rastty's ssaa.h resolves:
 * colour = (sum of the K*K values + K*K/2) / (K*K), depth = the nearest sample's (so a pixel
 * is covered when any sample is). Written from ssaa.h's description, not from its code.
 * --psnr-bar DB: judge PSNR against DB instead of 45 (the ideal's bar is 40).
 * --diff8-bar F: allow a fraction F of the pixels off by more than 8 instead of 0.0005.
 * --diff writes a picture of the differences when the scene fails (always with --diff-always):
 *   red = covered only in TEST, cyan = covered only in REF, yellow = colour differs > 8,
 *   blue = differs 1..8, grey = identical (TEST's luminance, darkened).
 * --list N prints up to N mismatching pixels (x,y from the top-left) to stderr.
 * Exit status: 0 pass, 1 fail, 2 usage or file error. */
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stb_image.h>
#include <stb_image_write.h>

struct pic {
    int w, h;
    unsigned char *rgb; /* row 0 = top */
    float *depth;       /* row 0 = top */
};

static int load_rgb(const char *path, struct pic *p)
{
    int n;
    p->rgb = stbi_load(path, &p->w, &p->h, &n, 3);
    if (!p->rgb) {
        fprintf(stderr, "compare: %s: %s\n", path, stbi_failure_reason());
        return -1;
    }
    return 0;
}

static int load_pfm(const char *path, const struct pic *p, float **out)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        fprintf(stderr, "compare: %s: %s\n", path, strerror(errno));
        return -1;
    }
    char magic[3] = {0};
    int w, h;
    double scale;
    if (fscanf(f, "%2s %d %d %lf", magic, &w, &h, &scale) != 4 || strcmp(magic, "Pf") ||
        fgetc(f) == EOF || w != p->w || h != p->h || scale >= 0) {
        fprintf(stderr, "compare: %s: not a little-endian %dx%d Pf depth image\n", path, p->w,
                p->h);
        fclose(f);
        return -1;
    }
    size_t n = (size_t)w * h;
    float *d = malloc(n * sizeof *d);
    unsigned char *raw = malloc(n * 4);
    if (!d || !raw || fread(raw, 4, n, f) != n) {
        fprintf(stderr, "compare: %s: short file\n", path);
        free(d), free(raw), fclose(f);
        return -1;
    }
    fclose(f);
    for (int y = 0; y < h; y++) /* file rows are bottom-to-top */
        for (int x = 0; x < w; x++) {
            const unsigned char *b = raw + 4 * ((size_t)(h - 1 - y) * w + x);
            uint32_t u = b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24;
            memcpy(&d[(size_t)y * w + x], &u, 4);
        }
    free(raw);
    *out = d;
    return 0;
}

/* --reduce: p (k*w x k*h) -> w x h in place, colour and depth */
static int reduce(struct pic *p, int k)
{
    int w = p->w / k, h = p->h / k;
    unsigned char *rgb = malloc((size_t)w * h * 3);
    float *depth = malloc((size_t)w * h * sizeof *depth);
    if (!rgb || !depth) {
        free(rgb), free(depth);
        return -1;
    }
    unsigned n = (unsigned)(k * k);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            unsigned sum[3] = {0, 0, 0};
            float d = INFINITY;
            for (int j = 0; j < k; j++)
                for (int i = 0; i < k; i++) {
                    size_t s = (size_t)(y * k + j) * p->w + (size_t)(x * k + i);
                    for (int c = 0; c < 3; c++)
                        sum[c] += p->rgb[3 * s + c];
                    d = p->depth[s] < d ? p->depth[s] : d;
                }
            size_t o = (size_t)y * w + x;
            for (int c = 0; c < 3; c++)
                rgb[3 * o + c] = (unsigned char)((sum[c] + n / 2) / n);
            depth[o] = d;
        }
    stbi_image_free(p->rgb);
    free(p->depth);
    p->rgb = rgb; /* stbi_image_free is free() */
    p->depth = depth;
    p->w = w, p->h = h;
    return 0;
}

/* Magenta pixels not 4-connected to the border through magenta. */
static long enclosed_magenta(const struct pic *p)
{
    size_t n = (size_t)p->w * p->h;
    unsigned char *seen = calloc(n, 1);
    size_t *stack = malloc(n * sizeof *stack);
    if (!seen || !stack) {
        free(seen), free(stack);
        return -1;
    }
#define IS_MAGENTA(i)                                                                      \
    (p->rgb[3 * (i)] == 255 && p->rgb[3 * (i) + 1] == 0 && p->rgb[3 * (i) + 2] == 255)
    size_t top = 0;
    for (int y = 0; y < p->h; y++)
        for (int x = 0; x < p->w; x++) {
            if (x != 0 && y != 0 && x != p->w - 1 && y != p->h - 1)
                continue;
            size_t i = (size_t)y * p->w + x;
            if (IS_MAGENTA(i) && !seen[i]) {
                seen[i] = 1;
                stack[top++] = i;
            }
        }
    while (top) {
        size_t i = stack[--top];
        int x = (int)(i % p->w), y = (int)(i / p->w);
        const int nb[4][2] = {{x - 1, y}, {x + 1, y}, {x, y - 1}, {x, y + 1}};
        for (int k = 0; k < 4; k++) {
            if (nb[k][0] < 0 || nb[k][1] < 0 || nb[k][0] >= p->w || nb[k][1] >= p->h)
                continue;
            size_t j = (size_t)nb[k][1] * p->w + nb[k][0];
            if (!seen[j] && IS_MAGENTA(j)) {
                seen[j] = 1;
                stack[top++] = j;
            }
        }
    }
    long count = 0;
    for (size_t i = 0; i < n; i++)
        count += IS_MAGENTA(i) && !seen[i];
#undef IS_MAGENTA
    free(seen);
    free(stack);
    return count;
}

int main(int argc, char **argv)
{
    const char *name = "scene", *diff_path = NULL, *files[4];
    int magenta = 0, exact = 0, list = 0, diff_always = 0, nfiles = 0, factor = 1;
    double psnr_bar = 45.0, diff8_frac = 0.0005;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--magenta") == 0)
            magenta = 1;
        else if (strcmp(argv[i], "--exact") == 0)
            exact = 1;
        else if (strcmp(argv[i], "--diff-always") == 0)
            diff_always = 1;
        else if (strcmp(argv[i], "--name") == 0 && i + 1 < argc)
            name = argv[++i];
        else if (strcmp(argv[i], "--diff") == 0 && i + 1 < argc)
            diff_path = argv[++i];
        else if (strcmp(argv[i], "--list") == 0 && i + 1 < argc)
            list = atoi(argv[++i]);
        else if (strcmp(argv[i], "--reduce") == 0 && i + 1 < argc)
            factor = atoi(argv[++i]);
        else if (strcmp(argv[i], "--psnr-bar") == 0 && i + 1 < argc)
            psnr_bar = atof(argv[++i]);
        else if (strcmp(argv[i], "--diff8-bar") == 0 && i + 1 < argc)
            diff8_frac = atof(argv[++i]);
        else if (argv[i][0] != '-' && nfiles < 4)
            files[nfiles++] = argv[i];
        else
            nfiles = 99;
    }
    if (nfiles != 4 || factor < 1 || factor > 64) {
        fprintf(stderr, "usage: compare [--name NAME] [--magenta] [--exact] [--diff OUT.png] "
                        "[--diff-always] [--list N] [--reduce K] [--psnr-bar DB] [--diff8-bar F] "
                        "TEST.ppm TEST.pfm REF.ppm REF.pfm\n");
        return 2;
    }
    struct pic t = {0}, r = {0};
    int bad = load_rgb(files[0], &t) || load_rgb(files[2], &r);
    if (!bad && (t.w * factor != r.w || t.h * factor != r.h)) {
        fprintf(stderr, "compare: %s is %dx%d but %s is %dx%d (expected %d times that)\n",
                files[0], t.w, t.h, files[2], r.w, r.h, factor);
        bad = 1;
    }
    bad = bad || load_pfm(files[1], &t, &t.depth) || load_pfm(files[3], &r, &r.depth);
    if (!bad && factor > 1 && reduce(&r, factor)) {
        fprintf(stderr, "compare: out of memory\n");
        bad = 1;
    }
    if (bad) {
        stbi_image_free(t.rgb);
        stbi_image_free(r.rgb);
        free(t.depth);
        return 2;
    }

    size_t n = (size_t)t.w * t.h;
    long cov = 0, diff8 = 0, diffany = 0;
    int maxdiff = 0;
    double sse = 0;
    unsigned char *img = diff_path ? malloc(n * 3) : NULL;
    for (size_t i = 0; i < n; i++) {
        int ct = t.depth[i] < 1.0f, cr = r.depth[i] < 1.0f, md = 0;
        for (int k = 0; k < 3; k++) {
            int dlt = abs((int)t.rgb[3 * i + k] - (int)r.rgb[3 * i + k]);
            md = dlt > md ? dlt : md;
            sse += (double)dlt * dlt;
        }
        maxdiff = md > maxdiff ? md : maxdiff;
        cov += ct != cr;
        diff8 += md > 8;
        diffany += md > 0;
        if (img) {
            unsigned char *o = img + 3 * i;
            int lum = (t.rgb[3 * i] * 3 + t.rgb[3 * i + 1] * 6 + t.rgb[3 * i + 2]) / 40;
            if (ct && !cr)
                o[0] = 255, o[1] = 0, o[2] = 0;
            else if (cr && !ct)
                o[0] = 0, o[1] = 255, o[2] = 255;
            else if (md > 8)
                o[0] = 255, o[1] = 255, o[2] = 0;
            else if (md > 0)
                o[0] = 0, o[1] = 0, o[2] = (unsigned char)(96 + md * 19);
            else
                o[0] = o[1] = o[2] = (unsigned char)lum;
        }
    }
    double mse = sse / (3.0 * n);
    double psnr = mse > 0 ? 10.0 * log10(255.0 * 255.0 / mse) : INFINITY;
    long cov_bar = (long)floor(fmin(10.0, 0.0002 * n)), diff8_bar = (long)floor(diff8_frac * n);
    long enc = 0, enc_ref = 0;
    if (magenta) {
        enc = enclosed_magenta(&t);
        enc_ref = enclosed_magenta(&r);
    }

    char why[128] = "";
    if (exact) {
        if (cov)
            strcat(why, " coverage");
        if (diffany)
            strcat(why, " colour");
    } else {
        if (cov > cov_bar)
            strcat(why, " coverage");
        if (diff8 > diff8_bar)
            strcat(why, " diff8");
        if (!(psnr >= psnr_bar))
            strcat(why, " psnr");
    }
    if (magenta && enc != 0)
        strcat(why, " cracks");
    int pass = why[0] == 0;

    printf("%-28s %dx%d cov=%ld/%ld diff8=%ld/%ld maxdiff=%d psnr=", name, t.w, t.h, cov,
           exact ? 0 : cov_bar, diff8, exact ? 0 : diff8_bar, maxdiff);
    if (isinf(psnr))
        printf("inf");
    else
        printf("%.2f", psnr);
    if (exact)
        printf(" differing=%ld/0", diffany);
    if (magenta)
        printf(" enclosed=%ld ref=%ld", enc, enc_ref);
    if (pass)
        printf(" PASS\n");
    else
        printf(" FAIL(%s)\n", why + 1);

    fflush(stdout);
    for (size_t i = 0, listed = 0; i < n && listed < (size_t)list; i++) {
        int ct = t.depth[i] < 1.0f, cr = r.depth[i] < 1.0f, md = 0;
        for (int k = 0; k < 3; k++) {
            int dlt = abs((int)t.rgb[3 * i + k] - (int)r.rgb[3 * i + k]);
            md = dlt > md ? dlt : md;
        }
        if (ct == cr && md <= (exact ? 0 : 8))
            continue;
        listed++;
        fprintf(stderr, "  %s (%zu,%zu): test %s rgb %d,%d,%d depth %.7g | ref %s rgb %d,%d,%d "
                        "depth %.7g\n",
                name, i % t.w, i / t.w, ct ? "covered" : "empty", t.rgb[3 * i], t.rgb[3 * i + 1],
                t.rgb[3 * i + 2], t.depth[i], cr ? "covered" : "empty", r.rgb[3 * i],
                r.rgb[3 * i + 1], r.rgb[3 * i + 2], r.depth[i]);
    }
    int rc = pass ? 0 : 1;
    if (img && (!pass || diff_always)) {
        if (!stbi_write_png(diff_path, t.w, t.h, 3, img, t.w * 3)) {
            fprintf(stderr, "compare: %s: cannot write\n", diff_path);
            rc = 2;
        }
    }
    free(img);
    stbi_image_free(t.rgb);
    stbi_image_free(r.rgb);
    free(t.depth);
    free(r.depth);
    return rc;
}
