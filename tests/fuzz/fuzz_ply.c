/* fuzz_ply.c: libFuzzer target for the PLY loader (ply.c) through rastty's entry point
 * (model_parse_as, in memory: no other file is opened). Aborts on a crash, a sanitizer
 * report, or a broken contract (fuzz_mesh.h). See tests/fuzz/README. */
#include <stdint.h>

#include "fuzz_mesh.h"
#include "model.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    struct mesh m;
    struct err e = {{0}};
    struct warnings w = {0};
    struct model_ctx ctx = {.warn = &w};
    if (model_parse_as(MODEL_PLY, (const char *)data, size, &ctx, &m, &e) == 0) {
        fuzz_check_mesh(&m);
        mesh_free(&m);
    } else {
        fuzz_check_failure(&m, e.msg, "<memory>");
    }
    return 0;
}
