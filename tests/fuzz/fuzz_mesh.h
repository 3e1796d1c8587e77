/* fuzz_mesh.h: the mesh contract every loader's fuzz target checks after a success, and
 * the message contract after a failure (included by the fuzz targets only). */
#ifndef RASTTY_FUZZ_MESH_H
#define RASTTY_FUZZ_MESH_H

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mesh.h"

/* indices in range, materials in range, finite positions and uvs, unit normals, bounds
 * holding every vertex, textures with texels */
static inline void fuzz_check_mesh(const struct mesh *m)
{
    if (m->n_tris == 0 || m->n_verts == 0 || m->n_materials < 1)
        abort();
    for (uint32_t i = 0; i < m->n_tris; i++) {
        if (m->tri_material[i] >= m->n_materials)
            abort();
        for (int k = 0; k < 3; k++)
            if (m->tris[i][k] >= m->n_verts ||
                m->vert_material[m->tris[i][k]] != m->tri_material[i])
                abort();
    }
    for (uint32_t i = 0; i < m->n_materials; i++)
        if (m->materials[i].texture >= (int)m->n_textures)
            abort();
    for (uint32_t i = 0; i < m->n_textures; i++)
        if (m->textures[i].w < 1 || m->textures[i].h < 1 || !m->textures[i].rgba)
            abort();
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

/* after a failure: the mesh is zeroed, the message starts with prefix and is printable */
static inline void fuzz_check_failure(const struct mesh *m, const char *msg, const char *prefix)
{
    struct mesh zero;
    memset(&zero, 0, sizeof zero);
    if (memcmp(m, &zero, sizeof *m) != 0 || strncmp(msg, prefix, strlen(prefix)) != 0)
        abort();
    for (const char *c = msg; *c; c++)
        if (*c < 0x20 || *c > 0x7e)
            abort();
}

#endif
