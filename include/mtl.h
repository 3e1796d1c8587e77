/* mtl.h: Wavefront MTL material library.
 *
 * newmtl, Kd, Ka, Ks, Ns, map_Kd (options such as -mm 0 1, -o u v w, -s u v w, -bm x,
 * -clamp on may precede the file name; the rest of the line is the file name). Other
 * statements (illum, d, Tr, Ni, Ke, Tf, map_Ks, map_Bump, ...) are accepted and ignored.
 * Ka is ignored, unchecked: the ambient term is fixed at 0.1 * albedo by the conventions,
 * and real files carry typos there (sportsCar.mtl:336 "Ka 0.0000 0.0000 0.0000c") that
 * must not stop a model from loading. Kd, Ks and Ns are used, so bad numbers there are
 * errors.
 * "Kd r" alone means r r r (as the MTL spec says). Statements before the first newmtl are
 * ignored. A name defined twice keeps both entries; lookups take the first.
 * Comments: '#' anywhere ends a line of numbers ("Kd 1 0 0 # red"); on a newmtl or map_Kd
 * line only a '#' at the start or after whitespace does, so "map_Kd tex#1.png" keeps it.
 * Ns < 0 is clamped to 0 (a negative exponent would blow up the specular term).
 * Textures are not decoded here: mtl_parse only records the resolved path and the line of
 * each map_Kd, and obj.c loads the ones its faces use (mtl_load_texture) so that the
 * error names the MTL line. Errors: "path:line: message", return -1.
 *
 * Called by obj.c. Whitespace, tokens, the comment rule for names, the number syntax and the
 * whole-file read are lex.h's, shared with obj.c: one syntax for both formats. */
#ifndef RASTTY_MTL_H
#define RASTTY_MTL_H

#include "err.h"
#include "mesh.h"

struct mtl_lib {
    struct material *materials; /* texture is always -1 here (see mtl_load_texture) */
    char **texture_paths; /* per material: resolved map_Kd path or NULL */
    char **names;         /* per material: full name as written, trimmed; usemtl matches it */
    unsigned long *texture_lines; /* per material: line of its map_Kd statement, 0 if none */
    char *path;           /* copy of the path given (for messages), NULL if parsed from memory */
    uint32_t n;
};

int mtl_load(const char *path, struct mtl_lib *out, struct err *e);
/* path: for messages and to resolve map_Kd names (relative to its directory); may be NULL.
 * On failure *out is left empty (mtl_free is harmless). */
int mtl_parse(const char *text, size_t len, const char *path, struct mtl_lib *out, struct err *e);
void mtl_free(struct mtl_lib *lib);
/* Default material values (kd 1, ks 0.5, ns 32, no texture). */
void mtl_default(struct material *m, const char *name);

/* Decode material i's map_Kd (texture_paths[i] must be non-NULL). Errors name the MTL file
 * and line: "lib.mtl:7: cannot open texture 'dir/x.png': No such file or directory". */
int mtl_load_texture(const struct mtl_lib *lib, uint32_t i, struct texture *out, struct err *e);

#endif
