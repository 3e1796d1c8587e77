/* fuzz_import.c: libFuzzer target for the assimp loader (import.c) through rastty's entry
 * points, in this process (no fork, so a crash inside assimp is seen as one): the bytes go
 * to import_flatten (assimp with rastty's file rules: from memory, no other file may be
 * opened) under the name the bytes suggest (.glb, .gltf, .dae, .fbx, .3ds), and its reply
 * to import_build. assimp itself is not instrumented: libFuzzer's guidance comes from
 * rastty's code and the seeds; ASan still sees bad reads through intercepted calls and
 * any crash. Contract: fuzz_mesh.h. */
#include <stdint.h>
#include <stdio.h>

#include "fuzz_mesh.h"
#include "import.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char name[32];
    snprintf(name, sizeof name, "memory.%s", import_guess_ext((const char *)data, size));
    struct import_result r;
    if (import_flatten((const char *)data, size, name, false, &r) == 0) {
        struct mesh m;
        struct err e = {{0}};
        struct warnings w = {0};
        struct texture_cache c = {0};
        struct model_ctx ctx = {.cache = &c, .warn = &w};
        memset(&m, 0, sizeof m);
        if (import_build(r.reply.p, r.reply.n, &ctx, "<memory>", &m, &e) == 0) {
            fuzz_check_mesh(&m);
            mesh_free(&m);
        } else {
            mesh_free(&m);
            for (const char *p = e.msg; *p; p++)
                if (*p < 0x20 || *p > 0x7e)
                    abort();
        }
        texture_cache_free(&c);
    }
    import_result_free(&r);
    return 0;
}
