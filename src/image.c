/* image.c: PPM / PNG / PFM output (see image.h). */
#include "image.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include <stb_image_write.h>

/* not declared in stb_image_write.h unless STBIW_... is set, but libstb exports it */
unsigned char *stbi_write_png_to_mem(const unsigned char *pixels, int stride_bytes, int x, int y,
                                     int n, int *out_len);

static int has_ext(const char *path, const char *ext)
{
    size_t n = strlen(path), k = strlen(ext);
    return n > k && strcasecmp(path + n - k, ext) == 0;
}

int image_color_ext_ok(const char *path)
{
    return has_ext(path, ".ppm") || has_ext(path, ".png");
}

static int finish(FILE *f, const char *path, struct err *e)
{
    int bad = ferror(f);
    if (fclose(f) != 0 || bad)
        return err_set(e, "%s: write failed: %s", path, strerror(errno ? errno : EIO));
    return 0;
}

int image_write_ppm(const char *path, const struct fb *fb, struct err *e)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return err_set(e, "%s: cannot create: %s", path, strerror(errno));
    fprintf(f, "P6\n%d %d\n255\n", fb->w, fb->h);
    fwrite(fb->rgb, 3, (size_t)fb->w * (size_t)fb->h, f);
    return finish(f, path, e);
}

int image_write_png(const char *path, const struct fb *fb, struct err *e)
{
    /* stbi_write_png ignores fwrite/fclose errors (a full disk would "succeed"): encode to
     * memory with stb, write and check here */
    int len;
    unsigned char *png = stbi_write_png_to_mem(fb->rgb, fb->w * 3, fb->w, fb->h, 3, &len);
    if (!png)
        return err_set(e, "%s: cannot encode PNG", path);
    FILE *f = fopen(path, "wb");
    if (!f) {
        free(png);
        return err_set(e, "%s: cannot create: %s", path, strerror(errno));
    }
    fwrite(png, 1, (size_t)len, f);
    free(png);
    return finish(f, path, e);
}

int image_write_color(const char *path, const struct fb *fb, struct err *e)
{
    if (has_ext(path, ".ppm"))
        return image_write_ppm(path, fb, e);
    if (has_ext(path, ".png"))
        return image_write_png(path, fb, e);
    return err_set(e, "%s: unknown image type (use .ppm or .png)", path);
}

int image_write_pfm(const char *path, const struct fb *fb, struct err *e)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return err_set(e, "%s: cannot create: %s", path, strerror(errno));
    fprintf(f, "Pf\n%d %d\n-1.0\n", fb->w, fb->h);
    for (int y = fb->h - 1; y >= 0; y--) {
        for (int x = 0; x < fb->w; x++) {
            /* window depth whatever the depth method (--depth) stored */
            float d = (float)fb_depth_window(fb, (size_t)y * (size_t)fb->w + (size_t)x);
            unsigned char b[4];
            uint32_t u;
            memcpy(&u, &d, 4);
            b[0] = (unsigned char)u, b[1] = (unsigned char)(u >> 8);
            b[2] = (unsigned char)(u >> 16), b[3] = (unsigned char)(u >> 24);
            fwrite(b, 1, 4, f);
        }
    }
    return finish(f, path, e);
}
