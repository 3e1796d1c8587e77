/* fuzz_import.c: libFuzzer target for the assimp loader (import.c) through rastty's entry
 * point: model_parse_as(MODEL_IMPORT) from memory, which runs assimp in a child process
 * (fork, limits) and rebuilds the mesh from its reply. A crash or hang inside assimp must
 * come back as an error line, never take rastty down: that is the contract fuzzed here
 * (fuzz_mesh.h on success, a clean "<memory>: ..." message on failure).
 *
 * RASTTY_FUZZ_IN_PROCESS=1 calls import_flatten/import_build in this process instead, to
 * hunt assimp's own crashes (assimp is not instrumented: guidance comes from the seeds and
 * rastty's code; ASan still sees the crash). tests/fuzz/README lists what it found. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "fuzz_mesh.h"
#include "import.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void in_process(const uint8_t *data, size_t size)
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
        if (import_build(r.reply.p, r.reply.n, &ctx, "<memory>", &m, &e) == 0)
            fuzz_check_mesh(&m);
        mesh_free(&m);
        texture_cache_free(&c);
    }
    import_result_free(&r);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static int mode = -1;
    if (mode < 0)
        mode = getenv("RASTTY_FUZZ_IN_PROCESS") != NULL;
    if (mode) {
        in_process(data, size);
        return 0;
    }
    struct mesh m;
    struct err e = {{0}};
    struct warnings w = {0};
    struct model_ctx ctx = {.warn = &w};
    if (model_parse_as(MODEL_IMPORT, (const char *)data, size, &ctx, &m, &e) == 0) {
        fuzz_check_mesh(&m);
        mesh_free(&m);
    } else {
        fuzz_check_failure(&m, e.msg, "<memory>: ");
    }
    return 0;
}
