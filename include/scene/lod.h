/* lod.h: mesh level of detail — a chain of simplified copies of each mesh, built at load, and
 * the copy a frame draws (--lod auto|off|RATIO).
 *
 * At terminal sizes a dense mesh puts many triangles on each pixel: the sports car's 300k
 * triangles cover 15k pixels at 160x96. Its coarser levels draw what the screen can show.
 *
 * The chain (lod_build, lod_start): level 0 is the mesh itself; level k+1 is level k
 * simplified by meshoptimizer (meshopt_simplify, edge collapses ranked by quadric error) to
 * half its triangles. The simplifier collapses an edge only onto one of its own vertices,
 * so every level's vertices are the source's: positions, uvs, normals and colours keep their
 * values. Vertices that share a position but not the rest (uv and normal seams, and material
 * borders: mesh.h makes vertices unique per material) are "seams" to it and stay seams, so
 * every triangle keeps one material and its uvs, and a closed mesh stays closed. Each level
 * has its own compact vertex array (in order of first use), so the vertex stage does less
 * work too, and borrows the source's materials and textures.
 *   The simplifier reports its error relative to the mesh's extent; a level's error
 * (lod_level_error) is the sum of the steps' errors down to it, in object-space units: an
 * estimate of how far its surface lies from the source's (quadric error, a mean-square
 * plane distance, not a bound). A mesh whose calm materials (a lod_shade_weight under LOD_CALM: dark, dull
 * ones, whose colour a turned normal barely moves) hold LOD_CALM_SHARE of its triangles or
 * more, and that has others, gets a calm level first: the calm triangles simplified to
 * LOD_CALM_KEEP of their number, their border with the others locked, the others as they
 * are (kept when it saves an eighth); the chain halves the whole from it. The sports car's
 * tyres, brake discs and black trim are 143k of its 300k triangles: its calm level keeps
 * 204k, at 0.087 px and 61 dB from the benchmark's eye (README, "Level of detail"), where
 * its first halved level (150k: the same 0.036 px) lost the highlights of its chrome (38-45
 * dB over nine views) and was refused. The chain stops where a step cannot reach 3/4 of its
 * triangles (everything is a seam or a border: a block world's faces), where a level
 * would have fewer than LOD_MIN_TRIS triangles, where its error passes LOD_MAX_ERROR of the
 * mesh's extent, or at LOD_MAX_LEVELS. Meshes smaller than 2 * LOD_MIN_TRIS, without
 * vert_material, or with non-finite positions get no levels.
 *   A mesh on the features path (mesh.h) gets a chain only when it has atlas tiles (tiles.h:
 * a block world, every vertex a seam): level 1 is the source over its vertices welded per
 * tile, simplified only where that costs no error (LOD_TILE_ERROR: coplanar faces of a
 * tile merged, LOD_TILE_CHUNK triangles of the file's order at a time, each chunk's border
 * locked; made when it merges a tenth or more), the chain going on from it as above;
 * its levels draw the tiles' derived materials, and it keeps no cache file. Without tiles,
 * or with a second uv set, tangents or blended triangles, such a mesh gets none.
 *
 *   A level also has a shading error (lod_level_shade_error, lod_shade_error): the
 * simplifier weighs positions only, but a level keeps the source's normals at the vertices
 * it keeps and interpolates them across larger triangles, which moves the light and the
 * highlights even where the surface barely moves (the displaced sphere of tests/bench
 * loses 6 dB a level that way, the bunny's scanned bumps and the car's highlights too).
 * It is the RMS angle, in radians, between the source's normals at up to 2048 of its
 * vertices (one from each equal stretch of the vertex array) and the normal the level
 * interpolates at the nearest point of its surface (of the nearest triangles, the one whose
 * normal is nearest: the vertex's side of a crease), found through a grid of the level's
 * triangles; each angle weighted by the vertex's material (lod_shade_weight: what the
 * angle moves its colour, as an angle of the material the bound was measured on, and no
 * more than the duller colour can move at all), so a dark part's turned normals count
 * little.
 *
 * The cache (lod_cache.h): a mesh of LOD_CACHE_MIN_TRIS triangles or more keeps its
 * finished chain in a file per mesh content ($RASTTY_CACHE_DIR, else $XDG_CACHE_HOME/rastty
 * or ~/.cache/rastty; RASTTY_CACHE_DIR set and empty: none), and the next build of the same
 * mesh reads it instead of simplifying: the same levels, the same bytes drawn. The folder
 * keeps under LOD_CACHE_MAX_MB (lod_cache.h): the files used least recently go first.
 *
 * The choice (lod_choose, per frame and draw item):
 *   off   : level 0.
 *   auto  : the coarsest level whose error, projected at the nearest point of the item's
 *           bounding sphere (view depth, vertical fov, framebuffer height; orthographic: view
 *           height), is below o->lod_px pixels of the framebuffer being drawn (with --ssaa,
 *           the supersampled one), and whose shading error times the square root of the
 *           item's share of the framebuffer (lod_share: the bounding sphere's disc or a quarter of
 *           the surface area, projected at the centre's depth, over the framebuffer) is below LOD_SHADE_BOUND (times lod_px / LOD_DEFAULT_PX:
 *           auto:PX scales both). Shading error does not shrink with distance as a
 *           position error does; what shrinks is the part of the picture it covers, and
 *           with it the picture's mean square error: an error of e (a fraction of full
 *           intensity) over a share s of the pixels gives a PSNR of -10 log10(e^2 s). The
 *           defaults, LOD_DEFAULT_PX and LOD_SHADE_BOUND, come from measurements (README,
 *           "Level of detail": at least 40 dB against --lod off).
 *   RATIO : the level whose triangle count is nearest (by ratio) to RATIO x the source's.
 * Only complete levels are chosen: while a background build runs, the chain grows.
 *
 * Vertex-cache, overdraw and vertex-fetch reordering (meshopt_optimize*) were measured on the
 * shared models and do not pay here (README): the source's triangle order is kept. */
#ifndef RASTTY_LOD_H
#define RASTTY_LOD_H

#include <stdbool.h>
#include <stddef.h>

#include "camera.h"
#include "mesh.h"

/* Mesh level of detail (--lod; this file picks the level per frame and draw item): off draws
 * every mesh in full, auto the coarsest level whose error stays under lod_px pixels on
 * screen, RATIO (LOD_RATIO) the level nearest to that fraction of the triangles, clusters
 * (LOD_CLUSTERS) the cut of a mesh's cluster hierarchy (dag.h) whose errors stay under
 * lod_px (meshes without one: as auto). Only off and auto have names (render_lod_names in
 * render.h, the chart's `lod` axis). */
enum lod_mode { LOD_OFF, LOD_AUTO, LOD_RATIO, LOD_CLUSTERS };
#define LOD_NAMED 2
/* auto's error bound in pixels, chosen from the methods chart (README, "Level of detail") */
#define LOD_DEFAULT_PX 0.15f
/* auto's shading bound: a level's shading error (radians) times sqrt(the item's share of the
 * framebuffer) stays under it (README, "Level of detail") */
#define LOD_SHADE_BOUND 0.025

#define LOD_MAX_LEVELS 8   /* simplified levels after level 0 */
#define LOD_CACHE_MIN_TRIS 131072 /* meshes this large keep their chain in the cache */
#define LOD_MIN_TRIS 512   /* no level smaller than this */
#define LOD_MAX_ERROR 0.05 /* of meshopt_simplifyScale (the largest side of the box) */
#define LOD_CALM 0.25       /* a material whose lod_shade_weight is under it is calm */
#define LOD_CALM_SHARE 0.25  /* of the triangles: the fewest calm ones that get a calm level */
#define LOD_CALM_KEEP 0.33   /* of them: what the calm level keeps */
#define LOD_TILE_ERROR 1e-6f /* of it: a tiled chain's first level, merged flat faces */
#define LOD_TILE_CHUNK 1024  /* triangles: a tiled chain's first level merges within them */

/* Build m's chain now, on this thread. 0, or -1 out of memory (m keeps the levels made so
 * far and is still fine to draw). */
int lod_build(struct mesh *m, struct err *e);

/* Build the chains of meshes[0..n) on a background thread; lod_finish waits for it. The
 * meshes must not move or be freed before lod_finish. clusters: first each mesh's cluster
 * hierarchy (dag.h; --lod clusters), and the chain only for a mesh that gets none. */
struct lod_job;
int lod_start(struct mesh *meshes, int n, bool clusters, struct lod_job **out, struct err *e);
/* Has the job finished every chain? (NULL: yes.) */
bool lod_done(const struct lod_job *j);
/* Wait for the job and free it (NULL: nothing); cancel: stop after the level being built (a
 * viewer quitting), the meshes keep the levels finished so far. */
void lod_finish(struct lod_job *j, bool cancel);
/* Free m's levels (scene_free does it, before mesh_free). */
void lod_free(struct mesh *m);

/* Bytes m's chain holds (its levels' geometry and clusters; 0: none). */
size_t lod_bytes(const struct mesh *m);
/* Levels ready to draw, level 0 included (1 when m has no chain). */
int lod_level_count(const struct mesh *m);
/* Level k (0 = m itself), k < lod_level_count(m). */
const struct mesh *lod_level(const struct mesh *m, int k);
/* Level k's error in m's object-space units (0 for level 0). */
double lod_level_error(const struct mesh *m, int k);
/* Where m's chain came from: the cache's file (read), the simplifier and then the file
 * (written), or the simplifier alone (none: a small mesh, no cache folder, a write that
 * failed). */
enum lod_cache_use { LOD_CACHE_NONE, LOD_CACHE_READ, LOD_CACHE_WRITTEN };
int lod_cache_use(const struct mesh *m);
/* The key of m's chain in the cache (its file: lod-KEY.bin, KEY in 16 hex digits). */
uint64_t lod_chain_key(const struct mesh *m);
/* Level k's shading error in radians (0 for level 0; see the top of this file). */
double lod_level_shade_error(const struct mesh *m, int k);
/* The shading error of level lvl of src (its vertices are some of src's): see the top of
 * this file. -1 when out of memory. */
double lod_shade_error(const struct mesh *src, const struct mesh *lvl);
/* How fast material mt of mesh m changes colour as a normal turns, against the material
 * LOD_SHADE_BOUND was measured on (albedo 0.8, no highlight), at most 1: light.h's model
 * under a white light, its slope per radian as a root mean square over the directions a
 * normal may face — the diffuse term's LIGHT_DIFFUSE x albedo x sqrt(2/3), the highlight's
 * about ks / sqrt(2) at any ns. 1 for the conventions' materials (the implicit one: 1.17,
 * kept at 1) and on the features path (another light model); less for a dark, dull one
 * (the sports car's tyres 0.028, its brake discs 0.088). A texture or vertex colour can
 * only darken the albedo (a texel is at most 1). */
double lod_shade_weight(const struct mesh *m, uint32_t mt);

/* Pixels of the framebuffer per world unit at the nearest point of a sphere (world space),
 * for a framebuffer fb_h pixels high: where a level's error is largest on screen. */
double lod_pixels_per_unit(const struct camera *cam, int fb_h, vec3 center, double radius);
/* The level to draw (see the top of this file); px_per_unit: pixels per object-space unit
 * (lod_pixels_per_unit times the model matrix's largest scale); share: the item's share of
 * the framebuffer's pixels, 0..1 (lod_share). */
int lod_choose(const struct mesh *m, enum lod_mode mode, float ratio, float max_px,
               double px_per_unit, double share);
/* The share of a fb_w x fb_h framebuffer's pixels that m covers at px_per_unit (pixels per
 * object unit at its centre's depth), at most 1: the smaller of its bounding sphere's disc
 * and a quarter of its surface area (a convex body's mean projected area, Cauchy's
 * formula; more than a folded or layered mesh shows). */
double lod_share(const struct mesh *m, double px_per_unit, int fb_w, int fb_h);

#endif
