/* model.h: opening a model file of any format: detection, then one loader interface.
 *
 * A loader turns a file's bytes into a struct mesh (mesh.h) and its materials, with
 * "file:line: message" errors (binary formats: "file: byte N: message"). The format is
 * chosen by content before the name:
 *   magic "glTF" (GLB), "ply", "DRACO", "Kaydara FBX", JSON with "asset" (glTF), XML
 *   <COLLADA ...>, a binary STL (80-byte header, count, exactly 50 bytes per triangle),
 *   "solid ... facet" (ASCII STL, any case); then the extension (.obj .stl .ply .gltf .glb
 *   .drc .fbx .dae .3ds ...); then OBJ, the text format with no magic.
 *   Images and archives are named: "posx.jpg: not a model (JPEG image)"; UTF-16 text says
 *   so instead of failing line by line.
 * Loaders: obj.c, stl.c, ply.c, gltf.c (rastty's own parsers), draco.c (raw .drc files,
 * Google's decoder in a child process) and import.c (assimp, for FBX, COLLADA, 3DS and the
 * other formats it reads, in a child process with limits). After the loader, model.c
 * turns the file's up axis to +Y, sorts blended triangles last and makes the tangents a
 * tangent-space normal map needs (model_finish).
 * Materials and their textures are resolved by material.c for every format; a material's
 * missing or corrupt file is a warning, never an error. */
#ifndef RASTTY_MODEL_H
#define RASTTY_MODEL_H

#include <stdbool.h>
#include <stddef.h>

#include "err.h"
#include "mesh.h"
#include "texture.h"

/* How models are read: the command line's choices (--crease, --up-axis,
 * --allow-outside). Zero-initialised: the defaults. */
enum model_up { MODEL_UP_AUTO, MODEL_UP_X, MODEL_UP_Y, MODEL_UP_Z, MODEL_UP_COUNT };
struct model_opts {
    bool crease_set;   /* --crease given */
    float crease_deg;  /* generated normals' crease angle (mesh.h) */
    enum model_up up;  /* which axis of the file is up: AUTO = the file's own (its metadata,
                          else its format's convention: STL Z, the others Y) */
    bool any_path;     /* --allow-outside: a glTF's buffers and images may be files outside
                          the model's folder tree (else refused: a downloaded model must not
                          draw another file of the machine) */
};

/* What every loader gets besides the bytes. */
struct model_ctx {
    const char *path;            /* the file: for messages, and other files (MTL, textures,
                                    glTF buffers) are relative to its directory; NULL = in
                                    memory: messages say "<memory>", no other file is opened */
    struct texture_cache *cache; /* textures load through it; NULL: the mesh owns them */
    struct warnings *warn;       /* NULL: warnings are dropped */
    const struct model_opts *opts; /* NULL: the defaults */
};

enum model_format { MODEL_OBJ, MODEL_STL, MODEL_PLY, MODEL_IMPORT, MODEL_GLTF, MODEL_DRACO,
                    MODEL_FORMAT_COUNT };

/* Which loader reads these bytes; -1 with "name: not a model (JPEG image)" and the like. */
int model_detect(const char *data, size_t len, const char *path, enum model_format *fmt_out,
                 struct err *e);

/* Detect and load from memory (ctx->path as above). On failure *out is zeroed. */
int model_parse(const char *data, size_t len, const struct model_ctx *ctx, struct mesh *out,
                struct err *e);
/* The same with the format given. */
int model_parse_as(enum model_format f, const char *data, size_t len,
                   const struct model_ctx *ctx, struct mesh *out, struct err *e);
/* A model read from standard input (the name `-`) is named this in messages; as it has no
 * folder, the files it names (mtllib, textures, buffers) are relative to the current one. */
#define MODEL_STDIN_NAME "<stdin>"
/* Read the file (regular files only, FILE_MAX_MODEL; `-`: standard input, a pipe or a
 * redirected file, never a terminal) and model_parse it, its format by content. */
int model_load(const char *path, struct texture_cache *cache, struct warnings *w,
               struct mesh *out, struct err *e);
/* The same with the reading options (NULL: the defaults). */
int model_load_with(const char *path, const struct model_opts *opts,
                    struct texture_cache *cache, struct warnings *w, struct mesh *out,
                    struct err *e);
/* After a loader (model_parse_as calls it): the up axis turned to +Y, mesh.features from the
 * materials, blended triangles sorted last (mesh.n_opaque), tangents made for a
 * tangent-space normal map when the file has none (mesh_tangents). 0 or -1 (out of memory). */
int model_finish(struct mesh *out, const struct model_ctx *ctx, struct err *e);
/* The options in force for a context (never NULL). */
const struct model_opts *model_opts_of(const struct model_ctx *ctx);

/* The loaders (same contract as model_parse, format already chosen). */
int obj_read(const char *data, size_t len, const struct model_ctx *ctx, struct mesh *out,
             struct err *e);
int stl_read(const char *data, size_t len, const struct model_ctx *ctx, struct mesh *out,
             struct err *e);
int ply_read(const char *data, size_t len, const struct model_ctx *ctx, struct mesh *out,
             struct err *e);
int import_read(const char *data, size_t len, const struct model_ctx *ctx, struct mesh *out,
                struct err *e);
int gltf_read(const char *data, size_t len, const struct model_ctx *ctx, struct mesh *out,
              struct err *e);
int draco_read(const char *data, size_t len, const struct model_ctx *ctx, struct mesh *out,
               struct err *e);

#endif
