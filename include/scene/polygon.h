/* polygon.h: one planar polygon -> triangles, for the loaders (OBJ and PLY faces).
 *
 * In: n >= 3 corners in order, as positions (pos + 3*idx[k]). Out: n-2 triangles of corner
 * numbers (0..n-1), each wound like the polygon.
 *   - A convex polygon (every turn the same way in the polygon's plane, degenerate corners
 *     allowed) is fanned (0, i, i+1), as OBJ readers always did: cheap, and the
 *     triangles an exporter expects.
 *   - Any other polygon is ear-clipped in its plane: the Newell normal picks the plane, the
 *     corners are projected on the axis plane the normal is most aligned with, and a corner
 *     is an ear when it turns the polygon's way and no other corner lies in its triangle
 *     (corners at the same position as the ear's, as on a ring's bridge edge, do not
 *     count). A polygon with no ear left (self-intersecting) has its next corner clipped
 *     anyway, so there are always n-2 triangles.
 *   - Ear clipping costs O(n^2) tests per polygon (O(n^3) at worst): concave polygons of
 *     more than POLYGON_MAX_EAR corners are fanned, and the caller is told. */
#ifndef RASTTY_POLYGON_H
#define RASTTY_POLYGON_H

#include <stdint.h>

#define POLYGON_MAX_EAR 256

enum polygon_how { POLYGON_FAN, POLYGON_EARS, POLYGON_FAN_TOO_BIG };

/* out: room for n-2 triangles; scratch: room for 2*n uint32_t. */
enum polygon_how polygon_triangulate(const float *pos, const uint32_t *idx, uint32_t n,
                                     uint32_t (*out)[3], uint32_t *scratch);

#endif
