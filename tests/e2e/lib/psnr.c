/* psnr.c: PSNR in dB of one P6 PPM against another of the same size, over every pixel and
 * channel ("inf" when identical), for the tests and benchmarks.
 *   psnr A.ppm B.ppm
 *   psnr --upscale W H IN.ppm OUT.ppm   IN scaled up to W x H, nearest pixel (the one under
 *                                       each new pixel's centre) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static unsigned char *load(const char *path, int *w, int *h)
{
    FILE *f = fopen(path, "rb");
    int max;
    if (!f || fscanf(f, "P6 %d %d %d", w, h, &max) != 3 || fgetc(f) == EOF || *w <= 0 || *h <= 0)
        return fprintf(stderr, "%s: not a PPM\n", path), NULL;
    size_t n = (size_t)*w * (size_t)*h * 3;
    unsigned char *p = malloc(n);
    if (!p || fread(p, 1, n, f) != n)
        return fprintf(stderr, "%s: short\n", path), NULL;
    fclose(f);
    return p;
}

static int upscale(int W, int H, const char *in, const char *out)
{
    int w, h;
    unsigned char *p = load(in, &w, &h);
    if (!p)
        return 2;
    if (W < w || H < h)
        return fprintf(stderr, "%dx%d is smaller than %dx%d\n", W, H, w, h), 2;
    FILE *f = fopen(out, "wb");
    if (!f)
        return fprintf(stderr, "%s: cannot write\n", out), 2;
    fprintf(f, "P6\n%d %d\n255\n", W, H);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            fwrite(p + 3 * ((size_t)((2 * y + 1) * h / (2 * H)) * w + (size_t)((2 * x + 1) * w / (2 * W))),
                   1, 3, f);
    return fclose(f) ? 2 : 0;
}

int main(int argc, char **argv)
{
    int w, h, bw, bh;
    unsigned char *a, *b;
    if (argc == 6 && argv[1][0] == '-')
        return upscale(atoi(argv[2]), atoi(argv[3]), argv[4], argv[5]);
    if (argc != 3 || !(a = load(argv[1], &w, &h)) || !(b = load(argv[2], &bw, &bh)))
        return 2;
    if (w != bw || h != bh)
        return fprintf(stderr, "sizes differ: %dx%d and %dx%d\n", w, h, bw, bh), 2;
    double sse = 0;
    size_t n = (size_t)w * h * 3;
    for (size_t i = 0; i < n; i++)
        sse += (double)(a[i] - b[i]) * (a[i] - b[i]);
    if (sse == 0)
        printf("inf\n");
    else
        printf("%.2f\n", 10 * log10(255.0 * 255.0 * (double)n / sse));
    return 0;
}
