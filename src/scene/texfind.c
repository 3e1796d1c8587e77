/* texfind.c: a model's texture by naming habit (see texfind.h). */
#include "texfind.h"

#include <stdio.h>
#include <string.h>
#include <unistd.h>

static const char *const EXTS[] = {"png", "jpg", "jpeg", "tga", "bmp",
                                   "PNG", "JPG", "JPEG", "TGA", "BMP"};

/* DIR + name + suffix + "." + each extension; 0 when one is readable. */
static int try_name(const char *dir, int dir_len, const char *name, int name_len,
                    const char *suffix, char *out, size_t n)
{
    for (size_t i = 0; i < sizeof EXTS / sizeof EXTS[0]; i++) {
        int k = snprintf(out, n, "%.*s%.*s%s.%s", dir_len, dir, name_len, name, suffix, EXTS[i]);
        if (k > 0 && (size_t)k < n && access(out, R_OK) == 0)
            return 0;
    }
    return -1;
}

/* The model's stem, and each shorter stem cut at a '_' from the right, with each suffix in
 * order (NULL-terminated): 0 with out naming the first readable one, else -1. */
static int try_stems(const char *model_path, const char *const *suffixes, char *out, size_t n)
{
    const char *slash = strrchr(model_path, '/');
    const char *base = slash ? slash + 1 : model_path;
    int dir_len = (int)(base - model_path);
    const char *dot = strrchr(base, '.');
    int stem_len = dot && dot != base ? (int)(dot - base) : (int)strlen(base);
    for (int len = stem_len; len > 0;) {
        for (const char *const *sfx = suffixes; *sfx; sfx++)
            if (try_name(model_path, dir_len, base, len, *sfx, out, n) == 0)
                return 0;
        while (--len > 0 && base[len] != '_') /* cut at the next '_' from the right */
            ;
    }
    return -1;
}

int texfind_beside(const char *model_path, char *out, size_t n)
{
    static const char *const suffixes[] = {"_diffuse", "_texture", "", NULL};
    if (try_stems(model_path, suffixes, out, n) == 0)
        return 0;
    const char *slash = strrchr(model_path, '/');
    int dir_len = slash ? (int)(slash + 1 - model_path) : 0;
    if (try_name(model_path, dir_len, "texture", 7, "", out, n) == 0 ||
        try_name(model_path, dir_len, "diffuse", 7, "", out, n) == 0)
        return 0;
    if (n)
        out[0] = '\0';
    return -1;
}

int texfind_normal_beside(const char *model_path, char *out, size_t n)
{
    static const char *const suffixes[] = {"_nm_tangent", "_nm", "_normal", "_normals", NULL};
    if (try_stems(model_path, suffixes, out, n) == 0)
        return 0;
    if (n)
        out[0] = '\0';
    return -1;
}
