/* image.h: writing framebuffers to files.
 *
 * PPM (binary P6) and PNG (stb_image_write) for colour, chosen by the file extension;
 * PFM for depth: "Pf" greyscale, little-endian (scale -1), rows bottom-to-top as the format
 * requires, 1.0 where nothing was drawn.
 * Every file is written atomically (file.h): on a failed write (a full disk) the old file is
 * left as it was and no partial file remains. */
#ifndef RASTTY_IMAGE_H
#define RASTTY_IMAGE_H

#include <stdbool.h>

#include "err.h"
#include "fb.h"

/* .ppm or .png by extension (case-insensitive); anything else is an error. */
int image_write_color(const char *path, const struct fb *fb, struct err *e);
int image_write_ppm(const char *path, const struct fb *fb, struct err *e);
int image_write_png(const char *path, const struct fb *fb, struct err *e);
int image_write_pfm(const char *path, const struct fb *fb, struct err *e);
/* The picture to standard output, PPM or PNG (`--out -`); the caller has refused a terminal. */
int image_write_stdout(const struct fb *fb, bool ppm, struct err *e);
/* Does path end in .ppm or .png? */
int image_color_ext_ok(const char *path);

#endif
