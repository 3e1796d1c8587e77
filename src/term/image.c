/* image.c: PPM / PNG / PFM output (see image.h). */
#include "image.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include <stb_image_write.h>

#include "file.h"

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

int image_write_ppm(const char *path, const struct fb *fb, struct err *e)
{
    struct file_out o;
    if (file_out_open(&o, path, e))
        return -1;
    fprintf(o.f, "P6\n%d %d\n255\n", fb->w, fb->h);
    fwrite(fb->rgb, 3, (size_t)fb->w * (size_t)fb->h, o.f);
    return file_out_commit(&o, e);
}

int image_write_png(const char *path, const struct fb *fb, struct err *e)
{
    /* stbi_write_png ignores fwrite/fclose errors (a full disk would "succeed"): encode to
     * memory with stb, write and check here */
    char q[FILE_QUOTE_SIZE];
    int len;
    unsigned char *png = stbi_write_png_to_mem(fb->rgb, fb->w * 3, fb->w, fb->h, 3, &len);
    if (!png)
        return err_set(e, "%s: cannot encode PNG", file_quote(path, q, sizeof q));
    struct file_out o;
    if (file_out_open(&o, path, e)) {
        free(png);
        return -1;
    }
    fwrite(png, 1, (size_t)len, o.f);
    free(png);
    return file_out_commit(&o, e);
}

int image_write_stdout(const struct fb *fb, bool ppm, struct err *e)
{
    int len = 0;
    unsigned char *png = ppm ? NULL
                             : stbi_write_png_to_mem(fb->rgb, fb->w * 3, fb->w, fb->h, 3, &len);
    if (!ppm && !png)
        return err_set(e, "standard output: cannot encode PNG");
    errno = 0;
    if (ppm) {
        printf("P6\n%d %d\n255\n", fb->w, fb->h);
        fwrite(fb->rgb, 3, (size_t)fb->w * (size_t)fb->h, stdout);
    } else {
        fwrite(png, 1, (size_t)len, stdout);
        free(png);
    }
    if (fflush(stdout) != 0 || ferror(stdout))
        return err_set(e, "standard output: write failed: %s", strerror(errno ? errno : EIO));
    return 0;
}

int image_write_color(const char *path, const struct fb *fb, struct err *e)
{
    if (has_ext(path, ".ppm"))
        return image_write_ppm(path, fb, e);
    if (has_ext(path, ".png"))
        return image_write_png(path, fb, e);
    char q[FILE_QUOTE_SIZE];
    return err_set(e, "%s: unknown image type (use .ppm or .png)", file_quote(path, q, sizeof q));
}

int image_write_pfm(const char *path, const struct fb *fb, struct err *e)
{
    struct file_out o;
    if (file_out_open(&o, path, e))
        return -1;
    FILE *f = o.f;
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
    return file_out_commit(&o, e);
}
