/* tiles.h: atlas tiles — a block world as voxel exporters write it (lost_empire): every
 * face a quad of its own corners mapping one whole tile of a texture atlas, so that every
 * vertex is a uv seam and a simplifier (meshoptimizer 0.18: positions alone, vertices of
 * one position and other attributes seams) can collapse nothing. tiles_build welds them for
 * the simplifiers (the cluster hierarchy, dag.h; the chain, lod.h):
 *
 *   - a material whose faces all have their uvs on the corners of their uv box (that box:
 *     the face's tile; half a tile cut corner to corner too), its textures on uv set 0,
 *     untransformed, repeated, has its faces put in tile classes: one material, one tile,
 *     one mapping from position to tile units, t = g pos + c (g rounded to 10 significant
 *     bits, c modulo 1 to 1/1024 of the tile: neighbouring faces of one plane and tile
 *     agree); an untextured material's faces are one class (their uvs unread);
 *   - a vertex is in its triangles' class when they all have the same (a vertex of two
 *     classes, or of a face in none, is in none, nor are its faces);
 *   - the vertices of one class at one position, with one normal and colour, are one
 *     (weld[]): a plateau of one block kind is one surface whose inside collapses at no
 *     error;
 *   - a simplified face's vertex copy (tiles_vertex) gets t as its uv and a derived
 *     material, the source's with every texture slot wrapping inside the tile (mesh.h's
 *     tex_slot.tile: u' = u0 + (t - floor t) du, its derivatives scaled by du, so a point
 *     samples the texel and mip level the source's face did there), one per (material,
 *     tile).
 *
 * Derived materials are drawn by the features path (shade.h); only a mesh already on it is
 * tiled (its callers' rule), so its own faces are drawn as before. */
#ifndef RASTTY_TILES_H
#define RASTTY_TILES_H

#include <stdint.h>

#include "mesh.h"

struct tile_class;

struct mesh_tiles {
    uint32_t *weld;        /* per vertex: the vertex it is one with (itself if none), or
                              NULL: nothing welded (no faces in classes) */
    int32_t *vcls;         /* per vertex: its class, or < 0 */
    struct tile_class *cls;
    uint32_t n_cls;
    struct material *mats; /* the source's materials, then the derived ones */
    uint32_t n_mats;
};

/* Build m's tiles into *t (zeroed first): 0 (t->weld NULL when nothing welds, and then
 * nothing is held), or -1 out of memory (nothing held). */
int tiles_build(const struct mesh *m, struct mesh_tiles *t);
/* The copy of m's vertex v in a simplified level: *out and *material (set by the caller
 * to v's own) get v's tile uv and derived material when v is in a textured class. */
void tiles_vertex(const struct mesh_tiles *t, const struct mesh *m, uint32_t v,
                  struct mesh_vertex *out, uint16_t *material);
/* m's triangle corners as the vertices they are welded to (t->weld set): out[3 n_tris) */
void tiles_welded_corners(const struct mesh_tiles *t, const struct mesh *m, uint32_t *out);
void tiles_free(struct mesh_tiles *t);

#endif
