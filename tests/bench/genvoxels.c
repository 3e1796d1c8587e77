/* genvoxels.c: the scale benchmark's block world (tests/bench_scale.sh) — what voxel
 * exporters write (lost_empire): an N x N heightmap of unit columns in plateaus of 8 x 8
 * blocks (heights 1 to 3), closed, every exposed face of every block a quad of its own
 * corners mapping one whole tile of a 32 x 32 atlas (tops, sides and bottoms each their
 * tile), so that every vertex is a uv seam; one material with a cut-out map (all opaque),
 * which puts it on the features path as lost_empire's. The hierarchy (scene/dag.h) welds
 * each plateau's faces of one tile; nothing else simplifies it.
 *
 *   build/bench/genvoxels N DIR     (DIR/blocks.obj, .mtl, atlas.ppm, white.ppm)
 *
 * N = 160: 121,152 triangles. */
#include <stdio.h>
#include <stdlib.h>

static int n;

static int ht(int x, int z)
{
    return x < 0 || z < 0 || x >= n || z >= n ? 0 : 1 + (x / 8 + 2 * (z / 8)) % 3;
}

enum { H = 4 };

static long pi(int x, int y, int z)
{
    return ((long)x * (H + 1) + y) * (n + 1) + z + 1;
}

/* a quad a b d e (counter-clockwise seen from outside), normal k, tile */
static void quad(FILE *f, long a, long b, long d, long e, int k, int tile)
{
    const long q[4] = {a, b, d, e};
    fputc('f', f);
    for (int i = 0; i < 4; i++)
        fprintf(f, " %ld/%d/%d", q[i], 4 * tile + i + 1, k + 1);
    fputc('\n', f);
}

static FILE *open_in(const char *dir, const char *name)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "wb");
    if (!f)
        perror(path);
    return f;
}

int main(int argc, char **argv)
{
    if (argc != 3 || atoi(argv[1]) < 8 || atoi(argv[1]) > 4096) {
        fprintf(stderr, "usage: genvoxels N DIR (8 <= N <= 4096)\n");
        return 2;
    }
    n = atoi(argv[1]);
    FILE *f = open_in(argv[2], "blocks.obj");
    if (!f)
        return 2;
    fprintf(f, "# rastty tests/bench/genvoxels.c\nmtllib blocks.mtl\n");
    for (int x = 0; x <= n; x++)
        for (int y = 0; y <= H; y++)
            for (int z = 0; z <= n; z++)
                fprintf(f, "v %d %d %d\n", x - n / 2, y, z - n / 2);
    for (int tile = 0; tile < 3; tile++) /* tile t: the quarter (t % 2, t / 2) of the atlas */
        for (int k = 0; k < 4; k++)
            fprintf(f, "vt %g %g\n", (tile % 2) * 0.5 + (k == 1 || k == 2 ? 0.5 : 0),
                    (tile / 2) * 0.5 + (k >= 2 ? 0.5 : 0));
    fprintf(f, "vn 0 1 0\nvn 0 -1 0\nvn 1 0 0\nvn -1 0 0\nvn 0 0 1\nvn 0 0 -1\nusemtl blocks\n");
    for (int x = 0; x < n; x++)
        for (int z = 0; z < n; z++) {
            const int h = ht(x, z);
            quad(f, pi(x, h, z + 1), pi(x + 1, h, z + 1), pi(x + 1, h, z), pi(x, h, z), 0, 0);
            quad(f, pi(x, 0, z), pi(x + 1, 0, z), pi(x + 1, 0, z + 1), pi(x, 0, z + 1), 1, 2);
            for (int y = ht(x + 1, z); y < h; y++)
                quad(f, pi(x + 1, y, z + 1), pi(x + 1, y, z), pi(x + 1, y + 1, z),
                     pi(x + 1, y + 1, z + 1), 2, 1);
            for (int y = ht(x - 1, z); y < h; y++)
                quad(f, pi(x, y, z), pi(x, y, z + 1), pi(x, y + 1, z + 1), pi(x, y + 1, z), 3, 1);
            for (int y = ht(x, z + 1); y < h; y++)
                quad(f, pi(x, y, z + 1), pi(x + 1, y, z + 1), pi(x + 1, y + 1, z + 1),
                     pi(x, y + 1, z + 1), 4, 1);
            for (int y = ht(x, z - 1); y < h; y++)
                quad(f, pi(x + 1, y, z), pi(x, y, z), pi(x, y + 1, z), pi(x + 1, y + 1, z), 5, 1);
        }
    if (fclose(f))
        return perror("blocks.obj"), 2;
    if (!(f = open_in(argv[2], "blocks.mtl")))
        return 2;
    fprintf(f, "newmtl blocks\nKd 1 1 1\nmap_Kd atlas.ppm\nmap_d white.ppm\n");
    if (fclose(f))
        return perror("blocks.mtl"), 2;
    if (!(f = open_in(argv[2], "atlas.ppm")))
        return 2;
    fprintf(f, "P6\n32 32\n255\n");
    for (int y = 0; y < 32; y++)
        for (int x = 0; x < 32; x++) {
            const int t = x / 16 + 2 * (y / 16);
            fputc(60 * t + 3 * (x % 16), f);
            fputc(200 - 50 * t + 2 * (y % 16), f);
            fputc(40 + 50 * (t % 2) + 3 * ((x + y) % 16), f);
        }
    if (fclose(f))
        return perror("atlas.ppm"), 2;
    if (!(f = open_in(argv[2], "white.ppm")))
        return 2;
    fprintf(f, "P6\n1 1\n255\n");
    fputc(255, f), fputc(255, f), fputc(255, f);
    return fclose(f) ? (perror("white.ppm"), 2) : 0;
}
