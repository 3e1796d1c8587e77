/* fuzz_texture.c: libFuzzer target for texture decoding (imgdec.c: libpng, libjpeg-turbo,
 * rastty's PNM and HDR readers, stb_image for TGA/BMP/PSD/GIF) with rastty's limits. The
 * first byte picks the size limit (so downscaling is fuzzed too); the rest is the file.
 * stb_image is compiled into this target with the sanitizers (stb_impl.c), so its bugs
 * are seen too. Contract: a success has 1..limit texels a side and every texel readable;
 * a failure leaves the texture empty and a printable message naming the input. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "imgdec.h"
#include "texture.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerInitialize(int *argc, char ***argv);

/* A progressive JPEG's coefficients get what half of MemAvailable holds (imgdec.c): here
 * as if 512 MiB were available, so a 30-byte header asking for 16384^2 stays within
 * libFuzzer's 2 GB RSS limit, as it did under libjpeg's 256 MiB cap alone */
int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    setenv("RASTTY_TEST_MEMAVAILABLE_MIB", "512", 0);
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1)
        return 0;
    static const int limits[4] = {TEXTURE_MAX_SIDE, 64, 7, 1};
    int max_side = limits[data[0] & 3];
    struct imgdec_image t;
    struct err e = {{0}};
    struct warnings w = {0};
    if (imgdec_decode(data + 1, size - 1, "<memory>", max_side, &t, &w, &e) == 0) {
        if (t.w < 1 || t.h < 1 || t.w > max_side || t.h > max_side || !t.rgba)
            abort();
        unsigned sum = 0;
        for (size_t i = 0; i < (size_t)t.w * (size_t)t.h * 4; i++)
            sum += t.rgba[i]; /* every texel written (MSan would say; ASan: in bounds) */
        (void)sum;
        free(t.rgba);
    } else {
        if (t.rgba || strncmp(e.msg, "<memory>: ", 10) != 0)
            abort();
        for (const char *c = e.msg; *c; c++)
            if (*c < 0x20 || *c > 0x7e)
                abort();
    }
    return 0;
}
