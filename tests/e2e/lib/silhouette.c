/* silhouette.c: how well a monochrome picture shows a model, for the end-to-end tests.
 *   silhouette MONO.ppm REF.ppm
 * REF's silhouette: its pixels that are not black (a colour render on a black background).
 * MONO's: pixels whose 4x4 neighbourhood (x-2..x+1, y-2..y+1) has a mean luminance above
 * 43 — the middle between the sky's most ink (2 of 16 pixels of the 8x8 ordered dither, or
 * ramp level 1) and the model's least (4 of 16, ramp level 2); see cellfit.c.
 * Prints "mismatch PCT inner PCT2 area N missed M added A": pixels in one silhouette but
 * not the other (M in REF's only, A in MONO's only) as a percentage of REF's silhouette area
 * N; PCT2 counts only those more than a pixel from REF's outline (its 3x3 neighbourhood all
 * in or all out), as the 4x4 window cannot place an edge closer. Same size pictures only. */
#include <stdbool.h>
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

int main(int argc, char **argv)
{
    int w, h, rw, rh;
    unsigned char *m, *r;
    if (argc != 3 || !(m = load(argv[1], &w, &h)) || !(r = load(argv[2], &rw, &rh)))
        return 2;
    if (w != rw || h != rh)
        return fprintf(stderr, "sizes differ: %dx%d and %dx%d\n", w, h, rw, rh), 2;
    long area = 0, miss = 0, only_ref = 0, inner = 0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            long sum = 0, n = 0;
            for (int j = y - 2; j <= y + 1; j++)
                for (int i = x - 2; i <= x + 1; i++)
                    if (i >= 0 && j >= 0 && i < w && j < h) {
                        const unsigned char *q = m + 3 * ((size_t)j * w + i);
                        sum += (q[0] * 77 + q[1] * 150 + q[2] * 29) >> 8;
                        n++;
                    }
            const unsigned char *q = r + 3 * ((size_t)y * w + x);
            int in_ref = q[0] || q[1] || q[2], in_mono = sum > 43 * n;
            area += in_ref;
            miss += in_ref != in_mono;
            bool edge = false;
            for (int j = y - 1; j <= y + 1; j++)
                for (int i = x - 1; i <= x + 1; i++)
                    if (i >= 0 && j >= 0 && i < w && j < h) {
                        const unsigned char *o = r + 3 * ((size_t)j * w + i);
                        edge |= (o[0] || o[1] || o[2]) != in_ref;
                    }
            inner += in_ref != in_mono && !edge;
            only_ref += in_ref && !in_mono;
        }
    if (!area)
        return fprintf(stderr, "%s: no silhouette\n", argv[2]), 1;
    printf("mismatch %.2f inner %.2f area %ld missed %ld added %ld\n", 100.0 * miss / area,
           100.0 * inner / area, area, only_ref, miss - only_ref);
    return 0;
}
