/* obj.h: Wavefront OBJ -> struct mesh.
 *
 * Reads v (x y z [w] [r g b], extra values ignored), vt (u [v [w]]), vn, f in all four corner
 * forms (v, v/vt, v//vn, v/vt/vn; negative = relative indices), polygons through polygon.h
 * (convex: fanned as (0,i,i+1); concave: ear-clipped in the face's plane), o/g/s
 * (accepted, ignored), usemtl, mtllib (via mtl.h; textures named by map_Kd are loaded
 * relative to the MTL file), comments, CRLF, tabs, blank lines, a UTF-8 byte-order mark.
 * Errors: "path:line: message" in e, return -1. Warnings (ctx->warn), and the model still
 * loads: a missing, unreadable or malformed mtllib (default materials), a missing or
 * corrupt map_Kd texture (the material's Kd), a vt or vn index past the end (that corner
 * has no uv / generated normal), an empty newmtl name, an unknown map_Kd option.
 *
 * Details a caller may rely on:
 *   - The whole file is read at once and lines may be any length. Unknown statements are
 *     ignored (l, p, vp, curves, binary junk, ...).
 *   - '#' starts a comment anywhere on a line of numbers or indices; on a line holding a
 *     name (usemtl, mtllib) only at the start or after whitespace, as in mtl.h.
 *   - mtllib: the whole rest of the line is tried as one name first ("my cube.mtl"), then
 *     with "\ " as an escaped space, then as whitespace-separated names; resolved against
 *     the OBJ's directory (absolute names as they are); it may come after the usemtl that
 *     needs it. A name not found as written is tried with '\' as '/' (material.h).
 *   - A face corner may lack vt or vn while others in the same face have them: missing uv is
 *     (0,0), a missing normal is generated (mesh.h). Position indices must name elements
 *     defined on earlier lines; 0 and |index| > 2^31-1 are errors.
 *   - Materials: mesh.materials[0] is always the default material "default" (mtl_default),
 *     used by faces before any usemtl, after an empty usemtl, and for names no loaded MTL
 *     defines (common in real files, not an error). Then every material faces actually use,
 *     in order of first use (the first definition wins if libraries repeat a name). Only
 *     those materials' map_Kd files are decoded, each distinct path once.
 *   - A file without faces is an error ("path: no faces"; with only l/p elements it says
 *     so), as is UTF-16 text, or a mesh beyond the uint32 / uint16 limits of mesh.h (65535
 *     materials).
 *   - On failure *out is zeroed, so mesh_free(out) is harmless either way. */
#ifndef RASTTY_OBJ_H
#define RASTTY_OBJ_H

#include "err.h"
#include "mesh.h"

/* The loader itself is obj_read (model.h). These two are for callers that know they hold an
 * OBJ and want no texture cache or warnings (tests, tools): */
int obj_load(const char *path, struct mesh *out, struct err *e);
/* Parse from memory (path is used for messages and to resolve mtllib; NULL: mtllib ignored
 * and messages say "<memory>"). text need not be NUL-terminated. */
int obj_parse(const char *text, size_t len, const char *path, struct mesh *out, struct err *e);

#endif
