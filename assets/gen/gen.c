/* gen.c: errors, paths and the deterministic hash shared by the generator modules. */
#include "gen.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include <stb_image_write.h>

int gen_err_set(struct gen_err *e, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(e->msg, sizeof e->msg, fmt, ap);
    va_end(ap);
    return -1;
}

int gen_path(char *path_out, size_t cap, const char *dir, const char *name, struct gen_err *e)
{
    int n = snprintf(path_out, cap, "%s/%s", dir, name);
    if (n < 0 || (size_t)n >= cap)
        return gen_err_set(e, "%s: output path too long", name);
    return 0;
}

/* "lowbias32" integer hash (Chris Wellons, hash-prospector): a bijection on 32 bits with
 * good avalanche, so neighbouring inputs (brick numbers, pixel coordinates) look unrelated. */
uint32_t gen_hash32(uint32_t x)
{
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
}

double gen_rand01(uint32_t a, uint32_t b, uint32_t c)
{
    uint32_t h = gen_hash32(a ^ gen_hash32(b ^ gen_hash32(c + 0x9e3779b9U)));
    return (double)(h >> 8) / 16777216.0;
}

double gen_len(gen_vec3 a)
{
    return sqrt(gen_dot(a, a));
}

gen_vec3 gen_norm(gen_vec3 a)
{
    double l = gen_len(a);
    return l > 0 ? gen_scale(a, 1.0 / l) : a;
}

int gen_write_png(const char *dir, const char *name, int w, int h,
                      const unsigned char *rgb, struct gen_err *e)
{
    char path[4096];
    if (gen_path(path, sizeof path, dir, name, e))
        return -1;
    /* no row filter: stb's per-row choice (mostly Paeth) made these synthetic images larger
     * (321 -> 306 KB in all) and costs libpng ~30 instructions a pixel to undo at every
     * start: the demo scene loads in 11.7 instead of 15.2 ms (median of 11), the same
     * pixels */
    stbi_write_force_png_filter = 0;
    /* stb keeps no reason; stbi_write_png returns 0 on any failure (open or write). */
    if (!stbi_write_png(path, w, h, 3, rgb, w * 3))
        return gen_err_set(e, "%s: cannot write PNG", path);
    return 0;
}
