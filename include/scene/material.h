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
 * "map_Kd .\tex\wood.jpg"), then by its last part in a textures/ (or Textures/) folder
 * beside the referring file (3DS and FBX exports keep their images there). Only running
 * out of memory is an error. */
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
/* Room for n textures (a glTF: one per image its materials use). */
int material_reserve_n(struct mesh *m, uint32_t n, struct err *e);
/* An image as a texture of m, not tied to a material: its index in m->textures (the same
 * image twice: the same index), or -1 when it cannot be used (the warning is given). */
int material_image_file(struct mesh *m, const char *path, const char *where, unsigned long line,
                        const struct model_ctx *ctx);
int material_image_bytes(struct mesh *m, const uint8_t *data, size_t len, const char *name,
                         const struct model_ctx *ctx);
/* What an image given as a normal map holds, told apart by its texels: a tangent-space
 * normal map (blue: z = b above 100/255 nearly everywhere, a mean blue above 200), an
 * object-space one (normals in every direction: over 1% of the texels below 100 in blue),
 * or a bump map (grey: a height; tinyrenderer's and many MTL files' bump). */
enum material_map_kind { MATERIAL_MAP_TANGENT, MATERIAL_MAP_OBJECT, MATERIAL_MAP_HEIGHT };
enum material_map_kind material_normal_kind(const struct texture *t);
/* Material mat's normal map from the file path (MTL norm, map_Bump and bump; --normal-map):
 * classified (material_normal_kind); a height map becomes a tangent-space normal map (its
 * slopes times `strength`, the MTL's -bm, owned by the mesh); a normal map's xy scaled by
 * strength. A file that cannot be used is a warning (as map_Kd's). m->textures needs room
 * for one more. 0, or -1 when out of memory. */
int material_normal_map(struct mesh *m, uint32_t mat, const char *path, const char *where,
                        unsigned long line, float strength, const struct model_ctx *ctx,
                        struct err *e);
/* Blinn-Phong's highlight for a physically based material (glTF; light.h documents the
 * mapping): ns from the roughness (rounded, 1..1024), ks (display values) from the
 * dielectric specular colour f0 (linear: 0.04 unless the file says) and the base colour
 * (linear) mixed by metallic, scaled by the exponent's energy (ns + 8) / 8 and brought
 * under 1 by its largest channel, so a metal's highlight keeps the metal's hue. */
void material_pbr_highlight(const float base_lin[3], const float f0[3], float metallic,
                            float roughness, float ks_out[3], float *ns_out);
/* linear -> display value (the sRGB transfer function), clamped to [0, 1]; and back */
float material_srgb_encode(float x);
float material_srgb_decode(float x);
/* path relative to the directory of the file `from` (absolute paths unchanged); malloc'd,
 * NULL when out of memory. */
char *material_path_beside(const char *from, const char *name, size_t name_len);

#endif
