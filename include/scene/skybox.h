/* skybox.h: the sky's cube map — a cubemap drawn behind everything (render/sky.h draws it),
 * following the camera's rotation only.
 *
 * Faces: posx negx posy negy posz negz, any texture format (texture.h), square, all the same
 * size; faces larger than SKYBOX_MAX_FACE are downscaled while decoding (a face spans 90
 * degrees: at terminal sizes 2048 texels are more than any frame shows), and decoded one
 * at a time.
 * Orientation is OpenGL's cube-map convention: a direction d picks the face of its largest
 * component, then (sc, tc, ma) from the GL table, s = (sc/|ma| + 1)/2, t = (tc/|ma| + 1)/2,
 * with t = 0 the FIRST (top) row of the face image and s = 0 its left column.
 * Seams: each face level is stored with a one-texel border copied from its neighbours, so
 * bilinear filtering near an edge blends across it instead of clamping (no visible seams).
 * Minification: a 512-texel face seen through a 160-pixel view would alias and shimmer as
 * the camera turns (and cost terminal bytes); faces keep a box-filtered mip chain and each
 * frame blends the two levels around the one whose texel matches a pixel (trilinear).
 * Measured on the shared cube map, 2-degree orbit at 160x96: trilinear instead of the
 * nearest level costs 0.25 ms a frame and cuts diff+tolerance-4 bytes from 207 to 87 KB.
 * skybox_procedural() bakes the default sky (gradient, ground, sun toward the light) into
 * the same cubemap form, so there is one sampling path. */
#ifndef RASTTY_SKYBOX_H
#define RASTTY_SKYBOX_H

#include <stdint.h>

#include "camera.h"
#include "err.h"

#define SKYBOX_MAX_LEVELS 12
#define SKYBOX_MAX_FACE 2048

struct skybox_level {
    int n;          /* face interior is n x n; stored (n+2) x (n+2) with the border */
    uint8_t *rgb[6]; /* per face, (n+2)^2 texels of 4 bytes (r, g, b, 0: one 32-bit load) */
};

struct skybox {
    int n_levels;
    struct skybox_level level[SKYBOX_MAX_LEVELS];
};

/* Load six face images (order posx negx posy negy posz negz); a face larger than
 * SKYBOX_MAX_FACE is downscaled with a warning in w (may be NULL). */
int skybox_load(struct skybox *s, const char *const paths[6], struct warnings *w,
                struct err *e);
/* The default sky: sun toward sun_dir (need not be unit). */
int skybox_procedural(struct skybox *s, vec3 sun_dir, struct err *e);
void skybox_free(struct skybox *s);

/* Bilinear sample of one level in direction d (for tests). */
void skybox_sample(const struct skybox *s, int level, vec3 d, float rgb_out[3]);

#endif
