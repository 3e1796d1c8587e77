/* fuzz_obj.c: libFuzzer target for obj_parse (in-memory, path NULL: no files touched).
 * Besides crashes and sanitizer reports it aborts when a parse breaks the documented
 * contract: indices in range, unit normals, bounds holding every vertex, clean messages,
 * and a zeroed mesh after a failure. See tests/fuzz/README. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_mesh.h"
#include "obj.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* the OBJ parser's own part of the contract, then every loader's (fuzz_mesh.h) */
static void check_ok(const struct mesh *m)
{
    if (m->n_materials < 1 || m->n_textures != 0 || strcmp(m->materials[0].name, "default") != 0)
        abort();
    fuzz_check_mesh(m);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    struct mesh m;
    struct err e = {{0}};
    if (obj_parse((const char *)data, size, NULL, &m, &e) == 0) {
        check_ok(&m);
        mesh_free(&m);
        return 0;
    }
    fuzz_check_failure(&m, e.msg, "<memory>");
    return 0;
}
