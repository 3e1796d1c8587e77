/* prepare.h: what every subcommand (render, dump, the viewer, bench) does around its frames
 * — the scene loaded as the command line asks, its camera and methods, the sky, the
 * statistics printed. */
#ifndef RASTTY_PREPARE_H
#define RASTTY_PREPARE_H

#include <stdbool.h>
#include <stddef.h>

#include "err.h"
#include "options.h"
#include "pipeline.h"
#include "scene.h"

/* The camera and render options for a scene. The command line
 * wins over the scene file (camera, near/far, lights, background); `frame` fits the camera
 * to the scene's bounding box, keeping the view direction, when the scene gives none (or
 * --eye/--target/--up/--fov override it). */
void prepare_camera(const struct options *o, const struct scene *s, double aspect, bool frame,
                    struct camera *cam_out, struct render_opts *ro_out);
/* The cameras the scene's model file defines (glTF): how many, and camera k (1-based) as a
 * struct camera in the world (its target where its view passes the scene's centre, a far
 * plane past the scene when the file has none); -1 when there is no such camera. The
 * default view uses the first (--camera N another, 0 rastty's framing; the viewer's C key
 * cycles them). */
int prepare_camera_count(const struct scene *s);
int prepare_file_camera(const struct scene *s, int k, struct camera *out);
void prepare_print_stats(const struct frame_stats *st);
/* A built-in asset (demo.rsc, floor.obj, ...) by name into out: $RASTTY_ASSETS, else
 * assets/ next to the binary (a build tree), else ../share/rastty from the binary (an
 * installed tree, wherever PREFIX was), else ./assets (running from the source tree), else
 * the compiled-in RASTTY_DATADIR. Returns 0 when the file is readable there, else -1 (out
 * holds the last place tried). */
int prepare_find_asset(const char *name, char *out, size_t n);
/* The sky to draw: the scene's, else with --sky procedural the generated one (built into
 * *tmp, sun toward ro's first light: call before the headlight replaces it), else NULL. */
int prepare_sky(const struct options *o, const struct scene *s, const struct render_opts *ro,
            struct skybox *tmp, const struct skybox **sky_out, struct err *e);
/* scene_load, then --texture over every item, then the scene's warnings to stderr (one line
 * each, "warning: file:line: ..."); a model with uvs but no MTL material and no --texture
 * gets the texture found beside it by name (texfind.h), unless --no-texture. The file found
 * goes to found_out (size n, "" if none; may be NULL). Then the levels of detail when they
 * may be drawn (--lod not off: built before returning; the viewer: always, in the
 * background). On failure nothing is left allocated. */
int prepare_scene(const struct options *o, const char *path, struct scene *s, char *found_out,
                   size_t n, struct err *e);

#endif
