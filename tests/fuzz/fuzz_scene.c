/* fuzz_scene.c: libFuzzer target for the scene-file parser (scene.c).
 * The loader reads a path, so each input is written to a private temporary file first.
 * Contract checked beyond "no crash": a failure leaves an empty scene and a one-line,
 * printable message that starts with the file's name; a success has at least one item,
 * and every item's mesh belongs to the scene. Build and run: see tests/fuzz/README. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "scene.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static char path[64];
    if (!path[0])
        /* inside the repository (run from its root), so the corpus can name test models
         * relative to it: ../../tests/data/... */
        snprintf(path, sizeof path, "build/fuzz-work/scene-input-%d.rsc", (int)getpid());
    FILE *f = fopen(path, "wb");
    if (!f)
        return 0;
    fwrite(data, 1, size, f);
    fclose(f);
    struct scene *s = malloc(sizeof *s);
    if (!s)
        return 0;
    struct err e = {""};
    if (scene_load_file(path, s, &e) == 0) {
        if (s->n_items < 1)
            abort();
        for (int i = 0; i < s->n_items; i++)
            if (s->items[i].mesh < s->meshes || s->items[i].mesh >= s->meshes + s->n_meshes)
                abort();
        scene_free(s);
    } else {
        if (s->n_items != 0 || strncmp(e.msg, path, strlen(path)) != 0)
            abort();
        for (const char *c = e.msg; *c; c++)
            if ((unsigned char)*c < 0x20 || (unsigned char)*c >= 0x7f)
                abort();
    }
    free(s);
    return 0;
}
