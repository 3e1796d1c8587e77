/* sweep.h: where each method fails — `rastty bench --sweep NAME`.
 *
 * A sweep varies one stress parameter over a fixed range, draws a scene built for it at
 * every step with every value of one method axis, and measures an error against an exact
 * answer computed independently (ray casts, box integrals, counting), plus NaN/inf depths.
 * A method's failure point is the first step where its error passes the sweep's threshold
 * (or a NaN/inf appears); `failed` stays 1 from there on. Where theory predicts a failure
 * point, it is computed and reported beside the measured one.
 *
 *   grazing       textured ground seen from 90 down to 1 degree (camera rolled 30 degrees,
 *                 so rows are not lines of equal depth), per --persp; error: mean texel
 *                 error of the sampled uv against a ray cast (a ramp texture makes colour
 *                 proportional to uv). Theory: affine's error grows as the angle flattens
 *                 (1/w varies more across each triangle), spans fail later, correct never.
 *   depthrange    two parallel quads 0.01 apart, 20 units away, far plane 100, near plane
 *                 moved in so far/near goes 10..1e7, per --depth; error: fraction of pixels
 *                 where the farther quad (drawn first) wins. Theory: a depth step at
 *                 distance D spans q * D^2 (far - near) / (far * near) units for a step q
 *                 of window depth (q = 1/65535 for z16, 2^-24 for float z near 1); the
 *                 quads tie in a fraction 1 - gap/step of the pixels once the step passes
 *                 the gap: z16 fails (> 1%) at far/near = 1 + 65535 far gap / (0.99 D^2).
 *   magnitude     a watertight sphere translated 1..1e7 units, camera following, per
 *                 --raster; error: enclosed background pixels (cracks); also jitter (pixels
 *                 whose coverage differs from the sphere at the origin). Theory: no cracks
 *                 until the input's own float precision runs out (a coordinate's float step
 *                 reaching a pixel).
 *   sliver        a closed fan of triangles filling a rectangle of aspect 1..1e7 (8 pixels
 *                 across, up to 8e7 long: clipped by the guard band), per --raster; error:
 *                 pixels covered other than exactly once inside / never outside (holes,
 *                 overdraw); also pixels whose uv is off. Theory: exact integer coverage
 *                 never fails.
 *   nearplane     the camera flies through a closed box (from 3 units before it to 3
 *                 behind), per --depth; error: pixels whose fragment count differs from the
 *                 number of box faces the pixel's ray crosses in front of the near plane
 *                 (holes, a triangle twice, anything from behind the eye); NaN counts also
 *                 stored depths outside the method's range (w <= 0).
 *   minification  a white-noise texture at 1..64 texels per pixel, per filter and --ssaa;
 *                 error: RMS against the exact box filter of the texels under each pixel.
 *                 Theory: averaging m independent texels of a texture with deviation s
 *                 leaves an RMS error of s sqrt(1/m - 1/k^2) at k texels per pixel, so
 *                 nearest (m = 1) fails at once, --ssaa n (m = n^2) at
 *                 k = 1 / sqrt(1/n^2 - (t/s)^2). Trilinear (the default) reads box-filtered
 *                 mip levels: no closed form, its error stays near the levels'
 *                 misalignment with the pixels' footprints instead of growing.
 * Sizes: any framebuffer (default 160x96); tests use small ones.
 * Each sweep is one entry of a constant table in sweep.c (its words, range, methods,
 * threshold, scene and theory), which sweep_run walks: a new sweep is an entry there. */
#ifndef RASTTY_SWEEP_H
#define RASTTY_SWEEP_H

#include <stdbool.h>
#include <stdio.h>

#include "err.h"
#include "plot.h"

enum sweep_kind { SWEEP_GRAZING, SWEEP_DEPTHRANGE, SWEEP_MAGNITUDE, SWEEP_SLIVER,
                  SWEEP_NEARPLANE, SWEEP_MINIFICATION, SWEEP_COUNT };

#define SWEEP_MAX_STEPS 32
#define SWEEP_MAX_METHODS 8

struct sweep_result {
    enum sweep_kind kind;
    const char *name;        /* "grazing" */
    const char *what;        /* one line: the scene and the method axis */
    const char *param_name;  /* "degrees above the ground" */
    const char *error_name;  /* "mean texel error" */
    const char *extra_name;  /* a second measure per step and method (NAN: none), or NULL;
                              * where theory predicts the error itself, the prediction */
    double threshold;        /* fails when error > threshold (or a NaN/inf appears) */
    char threshold_text[160];
    char theory[1024];       /* the prediction, with its numbers */
    int n_steps, n_methods;
    int default_method;      /* index of the default method */
    double param[SWEEP_MAX_STEPS];
    char method[SWEEP_MAX_METHODS][16]; /* flag values: affine, z16, ssaa4 (--ssaa 4) */
    double error[SWEEP_MAX_STEPS][SWEEP_MAX_METHODS];
    double extra[SWEEP_MAX_STEPS][SWEEP_MAX_METHODS];
    long nan[SWEEP_MAX_STEPS][SWEEP_MAX_METHODS];
    int fail_at[SWEEP_MAX_METHODS];      /* first failing step, -1 = never */
    double predicted[SWEEP_MAX_METHODS]; /* param where theory says it fails; NAN = never */
    double holds_until;      /* theory: the default must not fail before this param */
    bool extra_is_theory;    /* extra predicts error (drawn as dotted curves) */
    bool xlog, ylog, reversed;           /* how to plot: log axes; param decreasing */
};

const char *sweep_name(enum sweep_kind k); /* "grazing" */
int sweep_parse(const char *name);         /* -1 if unknown */

/* Run sweep k at w x h. */
int sweep_run(enum sweep_kind k, int w, int h, struct sweep_result *out, struct err *e);

void sweep_write_table(const struct sweep_result *r, FILE *f);
/* sweep,param,method,error,nan,failed — one row per step and method */
int sweep_write_csv(const struct sweep_result *r, FILE *f);
/* error against the parameter, one line per method, the threshold, the failure points */
void sweep_draw(const struct sweep_result *r, struct plot *p);

#endif
