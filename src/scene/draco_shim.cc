// draco_shim.cc: the one C++ file of rastty — draco::Decoder behind one C function
// (draco.h explains why). Called in the sandbox's child only (draco.c).
#include <cstdlib>
#include <cstring>
#include <memory>
#include <new>

#include <draco/compression/decode.h>
#include <draco/mesh/mesh.h>

extern "C" {
#include "draco.h"
int draco_shim_decode(const uint8_t *data, size_t len, const int ids[DRACO_ATTR_COUNT],
                      struct draco_mesh *out, char msg[200]);
}

static const draco::PointAttribute *pick(const draco::Mesh &m, int a, int id)
{
    if (id >= 0)
        return m.GetAttributeByUniqueId(static_cast<uint32_t>(id));
    if (id != DRACO_BY_KIND)
        return nullptr;
    switch (a) {
    case DRACO_POSITION: return m.GetNamedAttribute(draco::GeometryAttribute::POSITION);
    case DRACO_NORMAL: return m.GetNamedAttribute(draco::GeometryAttribute::NORMAL);
    case DRACO_UV0:
        return m.NumNamedAttributes(draco::GeometryAttribute::TEX_COORD) > 0
                   ? m.GetNamedAttribute(draco::GeometryAttribute::TEX_COORD, 0)
                   : nullptr;
    case DRACO_UV1:
        return m.NumNamedAttributes(draco::GeometryAttribute::TEX_COORD) > 1
                   ? m.GetNamedAttribute(draco::GeometryAttribute::TEX_COORD, 1)
                   : nullptr;
    case DRACO_COLOR: return m.GetNamedAttribute(draco::GeometryAttribute::COLOR);
    default: return nullptr;
    }
}

int draco_shim_decode(const uint8_t *data, size_t len, const int ids[DRACO_ATTR_COUNT],
                      struct draco_mesh *out, char msg[200])
{
    std::memset(out, 0, sizeof *out);
    try {
        draco::DecoderBuffer buf;
        buf.Init(reinterpret_cast<const char *>(data), len);
        draco::Decoder dec;
        auto r = dec.DecodeMeshFromBuffer(&buf);
        if (!r.ok()) {
            std::snprintf(msg, 200, "not a Draco mesh (%s)", r.status().error_msg());
            return -1;
        }
        std::unique_ptr<draco::Mesh> m = std::move(r).value();
        const uint32_t np = m->num_points(), nf = m->num_faces();
        if (np == 0 || nf == 0) {
            std::snprintf(msg, 200, "the Draco mesh has %u points and %u faces", np, nf);
            return -1;
        }
        out->n_points = np;
        out->n_faces = nf;
        out->faces = static_cast<uint32_t *>(std::malloc(sizeof(uint32_t) * 3 * nf));
        if (!out->faces)
            throw std::bad_alloc();
        for (uint32_t f = 0; f < nf; f++) {
            const draco::Mesh::Face &face = m->face(draco::FaceIndex(f));
            for (int k = 0; k < 3; k++)
                out->faces[3 * f + k] = face[k].value();
        }
        for (int a = 0; a < DRACO_ATTR_COUNT; a++) {
            const draco::PointAttribute *att = pick(*m, a, ids[a]);
            if (!att || att->num_components() < 1 || att->num_components() > 16)
                continue;
            const int c = att->num_components();
            float *v = static_cast<float *>(std::malloc(sizeof(float) * c * np));
            if (!v)
                throw std::bad_alloc();
            for (uint32_t p = 0; p < np; p++)
                if (!att->ConvertValue<float>(att->mapped_index(draco::PointIndex(p)),
                                              static_cast<int8_t>(c), v + (size_t)c * p))
                    for (int k = 0; k < c; k++)
                        v[(size_t)c * p + k] = 0;
            out->attr[a] = v;
            out->comps[a] = c;
        }
        if (!out->attr[DRACO_POSITION] || out->comps[DRACO_POSITION] != 3) {
            std::snprintf(msg, 200, "the Draco mesh has no 3-component position attribute");
            return -1;
        }
        return 0;
    } catch (const std::bad_alloc &) {
        std::snprintf(msg, 200, "out of memory decoding the Draco mesh");
        return -1;
    } catch (...) {
        std::snprintf(msg, 200, "the Draco decoder failed");
        return -1;
    }
}
