/* gen_mesh.h: meshes (and the random numbers for views of them) the unit tests make for
 * themselves (tests/unit/gen_mesh.c). */
#ifndef RASTTY_TEST_GEN_MESH_H
#define RASTTY_TEST_GEN_MESH_H

#include "mesh.h"

/* A displaced sphere: a latitude/longitude grid of `rows` rings of 2 rows positions
 * between two poles (radius 1 +- 0.14), 4 rows (rows - 1) triangles wound outward, then
 * the first `dup` of them again (triangle k * 7 % t: the same corners, so every pixel they
 * cover is a tie of depth the file's order decides). Material 1 for the copies and, when
 * every > 0, for every every-th triangle of the grid; material 0 for the rest. Normals by
 * mesh_build with crease angle crease_deg (180: smooth, one vertex a position; 0: faceted,
 * several). Materials are the caller's to add (m->materials is NULL). 0, or -1. */
int gen_bumpy_sphere(struct mesh *m, int rows, int dup, int every, float crease_deg);

/* The next number of the sequence *s (a linear congruential step), scaled into [lo, hi):
 * the random views the tests draw, the same on every machine. */
double gen_rnd(unsigned *s, double lo, double hi);

#endif
