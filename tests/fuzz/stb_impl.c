/* stb_impl.c: stb_image's implementation compiled into the fuzz targets with the
 * sanitizers, so undefined behaviour inside stb (what rastty still hands it: TGA, BMP,
 * PSD, GIF) is reported. The targets' definitions take precedence over libstb.so's. */
#define STB_IMAGE_IMPLEMENTATION
#define STBI_NO_STDIO
#include <stb_image.h>
