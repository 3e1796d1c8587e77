/* ppmstat.c: facts about a P6 PPM for the end-to-end tests:
 * prints "W H AREA CX CY COLOURS" — size, pixels differing from the background colour
 * (argv[2] "r,g,b", default the top-left pixel... no: default 0,0,0), their centroid, and
 * the number of distinct colours. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int main(int argc, char **argv)
{
    if (argc < 2)
        return 2;
    FILE *f = fopen(argv[1], "rb");
    int w, h, max;
    if (!f || fscanf(f, "P6 %d %d %d", &w, &h, &max) != 3 || fgetc(f) == EOF)
        return fprintf(stderr, "%s: not a PPM\n", argv[1]), 2;
    size_t n = (size_t)w * h * 3;
    unsigned char *p = malloc(n);
    if (!p || fread(p, 1, n, f) != n)
        return fprintf(stderr, "%s: short\n", argv[1]), 2;
    int bg[3] = {0, 0, 0};
    if (argc > 2 && sscanf(argv[2], "%d,%d,%d", &bg[0], &bg[1], &bg[2]) != 3)
        return 2;
    long area = 0;
    double sx = 0, sy = 0;
    unsigned char *seen = calloc(1 << 21, 1);
    long colours = 0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            unsigned char *q = p + ((size_t)y * w + x) * 3;
            unsigned key = ((unsigned)q[0] << 16) | ((unsigned)q[1] << 8) | q[2];
            if (!(seen[key >> 3] & (1 << (key & 7)))) {
                seen[key >> 3] |= (unsigned char)(1 << (key & 7));
                colours++;
            }
            if (q[0] != bg[0] || q[1] != bg[1] || q[2] != bg[2]) {
                area++;
                sx += x + 0.5;
                sy += y + 0.5;
            }
        }
    printf("%d %d %ld %.2f %.2f %ld\n", w, h, area, area ? sx / area : -1, area ? sy / area : -1,
           colours);
    return 0;
}
