/* texture.c: image decoding through stb_image and texture sampling (see texture.h). */
#include "texture.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stb_image.h>

#define TEXTURE_MAX_DIM 16384

static int from_hdr(const char *path, FILE *f, struct texture *out, struct err *e)
{
    int w, h, n;
    float *px = stbi_loadf_from_file(f, &w, &h, &n, 3);
    if (!px)
        return err_set(e, "%s: cannot decode HDR image (%s)", path, stbi_failure_reason());
    out->rgba = malloc((size_t)w * (size_t)h * 4);
    if (!out->rgba) {
        stbi_image_free(px);
        return err_set(e, "%s: out of memory", path);
    }
    out->w = w;
    out->h = h;
    for (size_t i = 0; i < (size_t)w * (size_t)h; i++) {
        for (int c = 0; c < 3; c++) {
            float x = px[3 * i + c];
            x = x > 0 ? x / (1.0f + x) : 0; /* Reinhard */
            out->rgba[4 * i + c] = (uint8_t)(powf(x, 1.0f / 2.2f) * 255.0f + 0.5f);
        }
        out->rgba[4 * i + 3] = 255;
    }
    stbi_image_free(px);
    return 0;
}

int texture_load(const char *path_raw, struct texture *out, struct err *e)
{
    /* the path may come from an MTL file: never echo its raw bytes */
    char path[200];
    err_quote(path_raw, strlen(path_raw), 160, path, sizeof path);
    memset(out, 0, sizeof *out);
    FILE *f = fopen(path_raw, "rb");
    if (!f)
        return err_set(e, "%s: cannot open texture: %s", path, strerror(errno));
    int w, h, n, rc;
    if (!stbi_info_from_file(f, &w, &h, &n)) {
        rc = err_set(e, "%s: not a readable image (%s)", path, stbi_failure_reason());
    } else if (w < 1 || h < 1 || w > TEXTURE_MAX_DIM || h > TEXTURE_MAX_DIM) {
        rc = err_set(e, "%s: image is %dx%d (limit %d per side)", path, w, h, TEXTURE_MAX_DIM);
    } else if (stbi_is_hdr_from_file(f)) {
        rc = from_hdr(path, f, out, e);
    } else {
        uint8_t *px = stbi_load_from_file(f, &w, &h, &n, 4);
        if (!px) {
            rc = err_set(e, "%s: cannot decode image (%s)", path, stbi_failure_reason());
        } else {
            rc = texture_from_rgba(w, h, px, out, e);
            stbi_image_free(px);
        }
    }
    fclose(f);
    return rc;
}

int texture_from_rgba(int w, int h, const uint8_t *rgba, struct texture *out, struct err *e)
{
    size_t n = (size_t)w * (size_t)h * 4;
    out->rgba = malloc(n);
    if (!out->rgba)
        return err_set(e, "out of memory for a %dx%d texture", w, h);
    memcpy(out->rgba, rgba, n);
    out->w = w;
    out->h = h;
    return 0;
}

void texture_free(struct texture *t)
{
    free(t->rgba);
    memset(t, 0, sizeof *t);
}
