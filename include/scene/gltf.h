/* gltf.h: glTF 2.0 (.gltf with its buffers and images, and .glb) -> struct mesh, rastty's
 * own reader behind model.h (gltf_read has model.h's loader contract).
 *
 * What is read (the man page's MODEL FORMATS says it for users):
 *   - the container: JSON text, or GLB (header, JSON chunk, BIN chunk), lengths checked
 *     before anything is allocated; the JSON by json.h (byte offsets in every message);
 *   - buffers: the GLB's BIN chunk, data: URIs (base64), and files beside the model —
 *     confined to the model's folder tree (file.h's file_inside_dir_of) unless
 *     model_opts.any_path (--allow-outside): a downloaded model may not draw /etc/passwd;
 *   - accessors: every component type, normalized integers, byte strides, sparse storage,
 *     accessors without a buffer view (zeros), KHR_mesh_quantization's integer positions,
 *     normals, tangents and uvs, EXT_meshopt_compression's buffer views (meshoptimizer's
 *     decoders and filters);
 *   - primitives: triangles, strips and fans (points and lines are skipped with a warning),
 *     KHR_draco_mesh_compression (draco.h), morph targets at the mesh's or node's default
 *     weights, skins in the pose the nodes give (joint matrices x inverse bind matrices);
 *   - the default scene's node tree (matrix or TRS), meshes instanced as often as nodes name
 *     them and by EXT_mesh_gpu_instancing, every placement baked into the mesh (mirrored
 *     nodes keep their normals outward and their winding); the cameras nodes carry;
 *   - materials: metallic-roughness, KHR_materials_pbrSpecularGlossiness, unlit,
 *     KHR_materials_emissive_strength, KHR_materials_specular and _ior's factors, alpha
 *     modes, doubleSided, base colour / emissive / normal / occlusion / metallic-roughness
 *     (specular-glossiness) textures with their samplers (wrap modes, NEAREST magnification),
 *     texCoord sets 0 and 1 and KHR_texture_transform; colour factors and vertex colours
 *     are linear and become display values (light.h);
 *   - extensionsRequired: one rastty cannot draw is an error naming it; extensionsUsed: one
 *     it cannot draw is a warning naming it and the fallback the specification allows.
 * Everything else that changes the picture (animations, lights, clear coat, ...) is a
 * warning naming it; a file with nothing to draw is an error saying why. */
#ifndef RASTTY_GLTF_H
#define RASTTY_GLTF_H

#include <stddef.h>

#include "err.h"
#include "mesh.h"
#include "model.h"

/* Triangles after instancing a glTF may have (the vertex records of a frame would pass
 * 2 GiB beyond this). */
#define GLTF_MAX_TRIS (16u << 20)
#define GLTF_MAX_VERTS (16u << 20)

int gltf_read(const char *data, size_t len, const struct model_ctx *ctx, struct mesh *out,
              struct err *e);

#endif
