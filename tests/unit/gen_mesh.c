/* gen_mesh.c: meshes the unit tests make for themselves (see gen_mesh.h). */
#include "gen_mesh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

double gen_rnd(unsigned *s, double lo, double hi)
{
    *s = *s * 1103515245u + 12345u;
    return lo + (hi - lo) * ((*s >> 8) & 0xffffff) / 16777216.0;
}

int gen_bumpy_sphere(struct mesh *m, int rows, int dup, int every, float crease_deg)
{
    const int cols = 2 * rows, n_pos = (rows - 1) * cols + 2;
    int n_tris = 4 * rows * (rows - 1);
    float *pos = malloc((size_t)n_pos * 3 * sizeof *pos);
    struct mesh_corner *c = malloc((size_t)(n_tris + dup) * 3 * sizeof *c);
    uint16_t *mat = calloc((size_t)(n_tris + dup), sizeof *mat);
    if (!pos || !c || !mat) {
        free(pos);
        free(c);
        free(mat);
        return -1;
    }
    for (int k = 0; k < n_pos; k++) {
        double lat = k == 0 ? M_PI / 2 : k == n_pos - 1 ? -M_PI / 2
                                                        : M_PI / 2 - M_PI * (1 + (k - 1) / cols) / rows;
        double lon = k == 0 || k == n_pos - 1 ? 0 : 2 * M_PI * ((k - 1) % cols) / cols;
        double r = 1 + 0.1 * sin(5 * lat) * cos(4 * lon) + 0.04 * sin(13 * lat + 1) * sin(11 * lon);
        pos[3 * k] = (float)(r * cos(lat) * cos(lon));
        pos[3 * k + 1] = (float)(r * sin(lat));
        pos[3 * k + 2] = (float)(-r * cos(lat) * sin(lon));
    }
#define V(r, s) ((uint32_t)(1 + ((r) - 1) * cols + ((s) % cols)))
    int t = 0;
#define TRI(a, b, d)                                                                       \
    c[3 * t] = (struct mesh_corner){a, MESH_NONE, MESH_NONE},                              \
    c[3 * t + 1] = (struct mesh_corner){b, MESH_NONE, MESH_NONE},                          \
    c[3 * t + 2] = (struct mesh_corner){d, MESH_NONE, MESH_NONE}, t++
    for (int s = 0; s < cols; s++)
        TRI(0, V(1, s), V(1, s + 1));
    for (int r = 1; r < rows - 1; r++)
        for (int s = 0; s < cols; s++) {
            TRI(V(r, s), V(r + 1, s), V(r + 1, s + 1));
            TRI(V(r, s), V(r + 1, s + 1), V(r, s + 1));
        }
    for (int s = 0; s < cols; s++)
        TRI(V(rows - 1, s), (uint32_t)(n_pos - 1), V(rows - 1, s + 1));
#undef TRI
#undef V
    for (int k = 0; k < dup; k++) {
        memcpy(&c[3 * (t + k)], &c[3 * (k * 7 % t)], 3 * sizeof *c);
        mat[t + k] = 1;
    }
    for (int k = 0; every > 0 && k < t; k += every)
        mat[k] = 1;
    n_tris = t + dup;
    struct mesh_source src = {.pos = pos, .n_pos = (uint32_t)n_pos, .corners = c,
                              .tri_material = mat, .n_tris = (uint32_t)n_tris,
                              .crease_set = true, .crease_deg = crease_deg};
    memset(m, 0, sizeof *m);
    int rc = mesh_build(&src, m, NULL);
    free(pos);
    free(c);
    free(mat);
    return rc ? -1 : 0;
}
