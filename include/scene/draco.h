/* draco.h: Draco-compressed meshes (KHR_draco_mesh_compression's buffer views, raw .drc
 * files) decoded by Google's Draco library (Debian's libdraco-dev).
 *
 * Why a library, and why in a child: Draco's bitstream (edgebreaker connectivity, predicted
 * and quantised attributes) is a format of its own with one reference decoder; Debian ships
 * it, as C++ only, so a small C++ file (draco_shim.cc: one C function around
 * draco::Decoder, nothing else) is the one C++ source of rastty. Like assimp, the decoder
 * is a large C++ library fed untrusted bytes, so it runs in a child process with limits
 * (sandbox.h): a crash or an allocation storm is one error line.
 *
 * Out: the points (each glTF vertex, or .drc point), their attributes as floats in the
 * attribute's own components, and triangles as point indices. */
#ifndef RASTTY_DRACO_H
#define RASTTY_DRACO_H

#include <stddef.h>
#include <stdint.h>

#include "err.h"

/* The attributes rastty asks for: by glTF's attribute ids (KHR_draco_mesh_compression's
 * "attributes" map), or for a raw .drc file by kind (id -1: the first of that kind). */
enum draco_attr { DRACO_POSITION, DRACO_NORMAL, DRACO_UV0, DRACO_UV1, DRACO_COLOR, DRACO_TANGENT,
                  DRACO_JOINTS, DRACO_WEIGHTS, DRACO_ATTR_COUNT };

struct draco_mesh {
    uint32_t n_points, n_faces;
    uint32_t *faces;                 /* 3 per face */
    float *attr[DRACO_ATTR_COUNT];   /* n_points * comps[a] floats, or NULL (absent) */
    int comps[DRACO_ATTR_COUNT];
};

/* Decode bytes; ids[a] is the unique id of attribute a (glTF), -1 to leave it out, or
 * DRACO_BY_KIND to take the first attribute of that kind (a raw .drc file). On failure -1
 * and e says why in the decoder's words (quoted). */
#define DRACO_BY_KIND (-2)
int draco_decode(const uint8_t *data, size_t len, const int ids[DRACO_ATTR_COUNT],
                 struct draco_mesh *out, struct err *e);
void draco_mesh_free(struct draco_mesh *m);
/* Does this look like a Draco bitstream ("DRACO" magic)? */
int draco_is(const void *data, size_t len);

#endif
