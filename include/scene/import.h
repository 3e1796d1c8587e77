/* import.h: the pieces of import.c (assimp) that the fuzz target and the tests call
 * directly, without the child process: import_read (model.h) = fork, import_flatten in
 * the child, import_build in the parent. */
#ifndef RASTTY_IMPORT_H
#define RASTTY_IMPORT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "err.h"
#include "mesh.h"
#include "model.h"
#include "sandbox.h"

struct import_result {
    struct sandbox_blob reply; /* the flattened scene (see import_build) */
    char msg[220]; /* why it failed */
};

/* Run assimp on the bytes (name picks the importer by its extension; other files are
 * opened only when others is true). 0 with r->reply filled, or -1 with r->msg. */
int import_flatten(const char *data, size_t len, const char *name, bool others,
                   struct import_result *r);
void import_result_free(struct import_result *r);
/* The reply into a mesh, textures through material.h. */
int import_build(const uint8_t *reply, size_t n, const struct model_ctx *ctx,
                 const char *where, struct mesh *out, struct err *e);
/* "glb", "gltf", "fbx", "dae" or "3ds" for bytes read from memory. */
const char *import_guess_ext(const char *data, size_t len);

#endif
