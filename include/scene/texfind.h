/* texfind.h: the texture a model without an MTL most likely means, found by its name.
 *
 * Models passed around without their MTL (tinyrenderer's african_head and diablo3_pose,
 * Keenan Crane's spot) keep their texture beside them under a naming habit. For
 * DIR/STEM.obj the candidates are, first found wins, each with the extensions png, jpg,
 * jpeg, tga, bmp (also upper case):
 *   DIR/P_diffuse.EXT, DIR/P_texture.EXT, DIR/P.EXT   for P = STEM, then STEM cut at each
 *                                                     '_' from the right (spot_triangulated
 *                                                     -> spot_texture.png)
 *   DIR/texture.EXT, DIR/diffuse.EXT
 * Only a lookup: nothing is loaded. Callers (cmd_load_scene) use it when the model has uvs,
 * no material from an MTL and no --texture; a file found that does not decode is a warning
 * (the model draws untextured), as a model's own missing map_Kd is. */
#ifndef RASTTY_TEXFIND_H
#define RASTTY_TEXFIND_H

#include <stddef.h>

/* The path of the first readable candidate in out (size n); 0, or -1 when there is none. */
int texfind_beside(const char *model_path, char *out, size_t n);
/* The same for a normal map (tinyrenderer's habit): DIR/P_nm_tangent.EXT, P_nm.EXT,
 * P_normal.EXT, P_normals.EXT for the same P as above. The caller looks for it only where
 * it found the diffuse texture by name (a model named on the command line with a --texture
 * keeps the conventions' look: the Mesa oracle draws the head without its normal map). */
int texfind_normal_beside(const char *model_path, char *out, size_t n);

#endif
