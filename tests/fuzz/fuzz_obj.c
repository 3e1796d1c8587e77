/* fuzz_obj.c: libFuzzer target for obj_parse (in-memory, path NULL: no files touched).
 * Besides crashes and sanitizer reports it aborts when a parse breaks the documented
 * contract: indices in range, unit normals, bounds holding every vertex, clean messages,
 * and a zeroed mesh after a failure. See tests/fuzz/README. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "obj.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void check_ok(const struct mesh *m)
{
    if (m->n_tris == 0 || m->n_verts == 0 || m->n_materials < 1 || m->n_textures != 0)
        abort();
    if (strcmp(m->materials[0].name, "default") != 0)
        abort();
    for (uint32_t i = 0; i < m->n_tris; i++) {
        if (m->tri_material[i] >= m->n_materials)
            abort();
        for (int k = 0; k < 3; k++)
            if (m->tris[i][k] >= m->n_verts ||
                m->vert_material[m->tris[i][k]] != m->tri_material[i])
                abort();
    }
    for (uint32_t i = 0; i < m->n_verts; i++) {
        const struct mesh_vertex *v = &m->verts[i];
        double n2 = 0, d2 = 0;
        for (int k = 0; k < 3; k++) {
            if (!isfinite(v->pos[k]) || !isfinite(v->uv[k % 2]))
                abort();
            if (v->pos[k] < m->bbox_min[k] || v->pos[k] > m->bbox_max[k])
                abort();
            n2 += (double)v->nrm[k] * v->nrm[k];
            double d = (double)v->pos[k] - m->center[k];
            d2 += d * d;
        }
        if (fabs(n2 - 1) > 1e-4 || sqrt(d2) > m->radius)
            abort();
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    struct mesh m;
    struct err e = {{0}};
    if (obj_parse((const char *)data, size, NULL, &m, &e) == 0) {
        check_ok(&m);
        mesh_free(&m);
        return 0;
    }
    struct mesh zero;
    memset(&zero, 0, sizeof zero);
    if (memcmp(&m, &zero, sizeof m) != 0 || strncmp(e.msg, "<memory>", 8) != 0)
        abort();
    for (const char *c = e.msg; *c; c++)
        if (*c < 0x20 || *c > 0x7e)
            abort();
    return 0;
}
