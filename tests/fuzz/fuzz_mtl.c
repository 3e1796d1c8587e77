/* fuzz_mtl.c: libFuzzer target for mtl_parse (path NULL) and, differentially, for the
 * number lexer lex_float (lex.h, shared with OBJ): every whitespace-separated token it
 * accepts must give exactly strtof's float (the fuzzer runs in the C locale). See
 * tests/fuzz/README. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "lex.h"
#include "mtl.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void check_numbers(const char *s, size_t n)
{
    size_t i = 0;
    while (i < n) {
        while (i < n && (s[i] == ' ' || s[i] == '\n' || s[i] == '\t'))
            i++;
        size_t j = i;
        while (j < n && s[j] != ' ' && s[j] != '\n' && s[j] != '\t')
            j++;
        float got;
        int rc = lex_float(s + i, j - i, &got);
        if (rc != LEX_NUM_SYNTAX) {
            char *tok = malloc(j - i + 1), *endp;
            if (!tok)
                abort();
            memcpy(tok, s + i, j - i);
            tok[j - i] = '\0';
            float want = strtof(tok, &endp);
            if (*endp != '\0') /* we accepted something strtof does not read whole */
                abort();
            if (rc == LEX_NUM_RANGE ? !isinf(want) : memcmp(&got, &want, sizeof got) != 0)
                abort();
            free(tok);
        }
        i = j;
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *text = (const char *)data;
    struct mtl_lib lib;
    struct err e = {{0}};
    if (mtl_parse(text, size, NULL, &lib, NULL, &e) == 0) {
        for (uint32_t i = 0; i < lib.n; i++) {
            const struct material *m = &lib.materials[i];
            if (!lib.names[i] || m->texture != -1 || !(m->ns >= 0) || !isfinite(m->ns))
                abort();
            if ((lib.texture_paths[i] != NULL) != (lib.texture_lines[i] != 0))
                abort();
            for (const char *c = m->name; *c; c++)
                if (*c < 0x20 || *c > 0x7e)
                    abort();
        }
        mtl_free(&lib);
    } else {
        if (lib.n != 0 || lib.materials || strncmp(e.msg, "<memory>:", 9) != 0)
            abort();
        for (const char *c = e.msg; *c; c++)
            if (*c < 0x20 || *c > 0x7e)
                abort();
    }
    if (size < 4096)
        check_numbers(text, size);
    return 0;
}
