/* gensphere.c: the scale benchmark's model (tests/bench_scale.sh) — one displaced sphere at
 * any triangle count, written as a binary little-endian PLY, so that the same object can be
 * drawn from 10k to 4M triangles at the same size on screen.
 *
 *   build/bench/gensphere TRIANGLES OUT.ply
 *
 * A latitude/longitude grid of R rows and 2R columns (4 R (R - 1) triangles: R is the
 * smallest that reaches TRIANGLES), its radius 1 + 0.1 sin(5 lat) cos(4 lon) + 0.04
 * sin(13 lat + 1) sin(11 lon): bumps every resolution shows, finer ones only the dense
 * meshes resolve. Positions only (rastty generates the normals); one vertex per grid point
 * and one at each pole, so the surface is closed. Rows run from the north pole down,
 * triangles in the grid's order (as exporters write them). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

static float radius(double lat, double lon)
{
    return (float)(1.0 + 0.1 * sin(5 * lat) * cos(4 * lon) + 0.04 * sin(13 * lat + 1) * sin(11 * lon));
}

static void put_vertex(FILE *f, double lat, double lon)
{
    float r = radius(lat, lon);
    float p[3] = {(float)(r * cos(lat) * cos(lon)), (float)(r * sin(lat)),
                  (float)(-r * cos(lat) * sin(lon))};
    fwrite(p, sizeof p, 1, f);
}

static void put_tri(FILE *f, uint32_t a, uint32_t b, uint32_t c)
{
    unsigned char n = 3;
    uint32_t i[3] = {a, b, c};
    fwrite(&n, 1, 1, f);
    fwrite(i, sizeof i, 1, f);
}

int main(int argc, char **argv)
{
    if (argc != 3 || atol(argv[1]) < 8) {
        fprintf(stderr, "usage: gensphere TRIANGLES OUT.ply (TRIANGLES >= 8)\n");
        return 2;
    }
    const long want = atol(argv[1]);
    long rows = 2; /* latitude bands */
    while (4 * rows * (rows - 1) < want)
        rows++;
    const long cols = 2 * rows, rings = rows - 1; /* rings of vertices between the poles */
    const long n_verts = rings * cols + 2, n_tris = 4 * rows * (rows - 1);
    FILE *f = fopen(argv[2], "wb");
    if (!f) {
        perror(argv[2]);
        return 2;
    }
    fprintf(f, "ply\nformat binary_little_endian 1.0\ncomment rastty tests/bench/gensphere.c\n"
               "element vertex %ld\nproperty float x\nproperty float y\nproperty float z\n"
               "element face %ld\nproperty list uchar uint vertex_indices\nend_header\n",
            n_verts, n_tris);
    const double pi = 3.14159265358979323846;
    put_vertex(f, pi / 2, 0); /* 0: north pole */
    for (long r = 1; r <= rings; r++)
        for (long c = 0; c < cols; c++)
            put_vertex(f, pi / 2 - pi * (double)r / (double)rows, 2 * pi * (double)c / (double)cols);
    put_vertex(f, -pi / 2, 0); /* last: south pole */
    const uint32_t south = (uint32_t)(n_verts - 1);
#define V(r, c) ((uint32_t)(1 + ((r) - 1) * cols + ((c) % cols)))
    for (long c = 0; c < cols; c++) /* counter-clockwise seen from outside */
        put_tri(f, 0, V(1, c), V(1, c + 1));
    for (long r = 1; r < rings; r++)
        for (long c = 0; c < cols; c++) {
            put_tri(f, V(r, c), V(r + 1, c), V(r + 1, c + 1));
            put_tri(f, V(r, c), V(r + 1, c + 1), V(r, c + 1));
        }
    for (long c = 0; c < cols; c++)
        put_tri(f, V(rings, c), south, V(rings, c + 1));
    if (fclose(f)) {
        perror(argv[2]);
        return 2;
    }
    printf("%s: %ld triangles, %ld vertices\n", argv[2], n_tris, n_verts);
    return 0;
}
