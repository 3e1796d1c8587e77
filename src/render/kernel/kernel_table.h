/* kernel_table.h: one instruction set's table (kernel.h, struct kernel) from the bodies'
 * functions, defined by the kernel_*.c file that includes it after the bodies:
 *     #define KERNEL_TABLE kernel_sse2
 *     #define KERNEL_NAME "sse2"
 *     #include "kernel_table.h"      (defines const struct kernel kernel_sse2) */
#ifndef RASTTY_KERNEL_TABLE_H
#define RASTTY_KERNEL_TABLE_H

#include "kernel.h"
#include "kernel_edge.h"
#include "kernel_sky.h"
#include "kernel_span.h"
#include "kernel_vertex.h"

const struct kernel KERNEL_TABLE = {
    .name = KERNEL_NAME,
    .lanes = SIMD_LANES,
    .span_one_pixel = {[SHADE_UNLIT] = span_one_pixel_unlit,
                       [SHADE_FLAT] = span_one_pixel_flat,
                       [SHADE_GOURAUD] = span_one_pixel_gouraud,
                       [SHADE_PHONG] = span_one_pixel_phong,
                       [SHADE_WIRE] = span_one_pixel_wire},
    .span_packs_z = {[SHADE_UNLIT] = {span_packs_z_unlit_nearest, span_packs_z_unlit_bilinear,
                                      span_packs_z_unlit_trilinear},
                     [SHADE_FLAT] = {span_packs_z_flat_nearest, span_packs_z_flat_bilinear,
                                     span_packs_z_flat_trilinear},
                     [SHADE_GOURAUD] = {span_packs_z_gouraud_nearest,
                                        span_packs_z_gouraud_bilinear,
                                        span_packs_z_gouraud_trilinear},
                     [SHADE_PHONG] = {span_packs_z_phong_nearest, span_packs_z_phong_bilinear,
                                      span_packs_z_phong_trilinear},
                     [SHADE_WIRE] = {span_packs_z_wire, span_packs_z_wire, span_packs_z_wire}},
    .span_packs = {[SHADE_UNLIT] = span_packs_unlit,
                   [SHADE_FLAT] = span_packs_flat,
                   [SHADE_GOURAUD] = span_packs_gouraud,
                   [SHADE_PHONG] = span_packs_phong,
                   [SHADE_WIRE] = span_packs_wire},
    .span_runs = {[SHADE_UNLIT] = span_runs_unlit,
                  [SHADE_FLAT] = span_runs_flat,
                  [SHADE_GOURAUD] = span_runs_gouraud,
                  [SHADE_PHONG] = span_runs_phong,
                  [SHADE_WIRE] = span_runs_wire},
    .span_rich = {[SHADE_UNLIT] = span_rich_unlit,
                  [SHADE_FLAT] = span_rich_flat,
                  [SHADE_GOURAUD] = span_rich_gouraud,
                  [SHADE_PHONG] = span_rich_phong,
                  [SHADE_WIRE] = span_packs_wire},
    .raster = {[RASTER_EDGE] = raster_edge,
               [RASTER_SCANLINE] = raster_scanline,
               [RASTER_TILED] = raster_tiled},
    .vertex_run = vertex_run,
    .position_run = position_run,
    .vertex_shade_many = vertex_shade_many,
    .sky_rows = sky_rows,
};
_Static_assert(SHADE_COUNT == 5 && TEX_FILTER_COUNT == 3 && RASTER_COUNT == 3,
               "every method has its entry in the table above");

#endif
