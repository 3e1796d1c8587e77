/* material.h: a model's materials and their textures, the same for every format.
 *
 * Loaders build mesh.materials (materials[0] is always the default material) and ask here
 * for textures: by file (OBJ's map_Kd, a glTF's external image) or by bytes (a GLB's
 * embedded image). Textures go through the context's texture cache (texture.h: each file
 * decoded once, within the budget); one image used by several materials is one entry of
 * mesh.textures.
 *
 * A texture that cannot be used (missing, unreadable, not an image, over the budget) is a
 * warning naming where it was asked for ("lib.mtl:7: cannot open texture 'x.png': No such
 * file or directory; drawn without it"), and the material keeps its Kd. A name that is not
 * found as written is tried once more with '\' read as '/' (Windows exporters write
 * "map_Kd .\tex\wood.jpg"). Only running out of memory is an error. */
#ifndef RASTTY_MATERIAL_H
#define RASTTY_MATERIAL_H

#include <stdint.h>

#include "err.h"
#include "mesh.h"
#include "model.h"

/* Room for one texture per material: call once materials are known (n_materials set). */
int material_reserve_textures(struct mesh *m, struct err *e);
/* Material mat of m gets the texture in the file path (already resolved against the
 * referring file's directory). where/line name the statement asking for it (line 0: no
 * line). */
int material_texture_file(struct mesh *m, uint32_t mat, const char *path, const char *where,
                          unsigned long line, const struct model_ctx *ctx, struct err *e);
/* ... or in these bytes (an embedded image); name is for messages. */
int material_texture_bytes(struct mesh *m, uint32_t mat, const uint8_t *data, size_t len,
                           const char *name, const struct model_ctx *ctx, struct err *e);
/* path relative to the directory of the file `from` (absolute paths unchanged); malloc'd,
 * NULL when out of memory. */
char *material_path_beside(const char *from, const char *name, size_t name_len);

#endif
