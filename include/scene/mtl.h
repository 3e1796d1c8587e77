/* mtl.h: Wavefront MTL material library.
 *
 * newmtl, Kd, Ka, Ks, Ns, d (opacity: below 1 the material blends) or Tr (1 - d; d wins),
 * map_Kd, map_d (an opacity map: the material cuts out below 0.5, or blends when d < 1 too),
 * map_Bump / bump (a bump map, or a normal map written under that name: told apart by its
 * texels, material.h) with -bm, norm (a normal map). The maps take the format's options
 * (-blendu -blendv -boost -mm -o -s -t -texres -clamp -bm -imfchan -type -cc may precede
 * the file name; an option the format does not define, such as -colorspace sRGB, is skipped
 * with one value and a warning; the rest of the line is the file name, spaces included).
 * Ke (emission) is not drawn: the conventions' OBJ lighting has none (the Mesa oracle's
 * Cornell box carries a Ke), so a non-zero Ke is a warning. map_Ks, map_Ns,
 * map_Ke, refl, disp and decal change the picture and are not drawn: a warning each, once
 * per file. Other statements (illum, Ni, Tf, ...) are accepted and ignored.
 * Ka is ignored, unchecked: the ambient term is fixed at 0.1 * albedo by the conventions,
 * and real files carry typos there (sportsCar.mtl:336 "Ka 0.0000 0.0000 0.0000c") that
 * must not stop a model from loading. Kd, Ks and Ns are used, so bad numbers there are
 * errors.
 * "Kd r" alone means r r r (as the MTL spec says). Statements before the first newmtl are
 * ignored. A name defined twice keeps both entries; lookups take the first. An empty newmtl
 * name is a warning (the material exists, no usemtl can name it). A UTF-8 byte-order mark
 * is skipped.
 * Comments: '#' anywhere ends a line of numbers ("Kd 1 0 0 # red"); on a newmtl or map_Kd
 * line only a '#' at the start or after whitespace does, so "map_Kd tex#1.png" keeps it.
 * Ns < 0 is clamped to 0 (a negative exponent would blow up the specular term).
 * Textures are not decoded here: mtl_parse only records the resolved path and the line of
 * each map_Kd; mtl_resolve, after the OBJ is read, loads the ones its faces use (through
 * material.h, so a missing or corrupt one is a warning naming the MTL line).
 * Errors: "path:line: message", return -1.
 *
 * Called by obj.c. Whitespace, tokens, the comment rule for names and the number syntax are
 * lex.h's, shared with obj.c: one syntax for both formats. */
#ifndef RASTTY_MTL_H
#define RASTTY_MTL_H

#include <stdbool.h>

#include "err.h"
#include "mesh.h"
#include "model.h"
#include "strmap.h"

enum { MTL_MAP_D, MTL_MAP_BUMP, MTL_MAP_NORM, MTL_MAP_COUNT };
struct mtl_maps { /* a material's maps besides map_Kd: resolved paths (or NULL), lines */
    char *path[MTL_MAP_COUNT];
    unsigned long line[MTL_MAP_COUNT];
    float bm; /* the bump map's -bm (1) */
};

struct mtl_lib {
    struct material *materials; /* texture is always -1 here (see mtl_resolve) */
    struct mtl_maps *maps;      /* per material */
    char **texture_paths; /* per material: resolved map_Kd path or NULL */
    char **names;         /* per material: full name as written, trimmed; usemtl matches it */
    unsigned long *texture_lines; /* per material: line of its map_Kd statement, 0 if none */
    char *path;           /* copy of the path given (for messages), NULL if parsed from memory */
    uint32_t n;
};

/* Read (regular files only, FILE_MAX_TEXT) and parse. */
int mtl_load(const char *path, struct mtl_lib *out, struct warnings *w, struct err *e);
/* path: for messages and to resolve map_Kd names (relative to its directory); may be NULL.
 * Warnings go to w (may be NULL). On failure *out is left empty (mtl_free is harmless). */
int mtl_parse(const char *text, size_t len, const char *path, struct mtl_lib *out,
              struct warnings *w, struct err *e);
void mtl_free(struct mtl_lib *lib);
/* Default material values (kd 1, ks 0.5, ns 32, no texture). */
void mtl_default(struct material *m, const char *name);

/* A model's material names (slots[s] for s >= 1 in order of first use; slot 0 = faces
 * without usemtl; used[s]: some face uses it) against the libraries: out->materials gets
 * the default material, then every used name a library defines (first definition wins),
 * in order of first use; their map_Kd textures are loaded (material.h); slot_mat_out[s] is
 * the material of slot s (0 for unknown or unused names). Errors: out of memory only. */
int mtl_resolve(const struct mtl_lib *libs, size_t n_libs, const struct strmap_key *slots,
                const bool *used, size_t n_slots, const struct model_ctx *ctx,
                struct mesh *out, uint16_t *slot_mat_out, struct err *e);

#endif
