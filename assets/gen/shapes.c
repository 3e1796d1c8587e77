/* shapes.c: textured primitives: cube, UV sphere, torus, floor.
 *
 * Sizes (object space, Y up, centred at the origin unless said):
 *   cube   edge 1, [-0.5, 0.5]^3; 8 shared positions (watertight), one flat vn per face, and
 *          each face maps the whole texture [0,1]^2, upright: side faces have v = 1 at the top
 *          (+Y), the top face has v = 1 toward -Z, the bottom face has v = 1 toward +Z.
 *   sphere radius 0.5; one vertex per pole (watertight), per-pole-triangle vt so the texture
 *          does not twist at the poles; u = 0 and u = 1 meet at the back (-Z) seam, u = 0.5
 *          faces +Z; v = 1 at the north pole (+Y).
 *   torus  major radius 0.35, tube radius 0.15, axis Y (lying flat; y in [-0.15, 0.15]);
 *          u in [0, 2] around the axis (two texture repeats, so texels are near square),
 *          v in [0, 1] around the tube starting at the outer equator going up.
 *   floor  20 x 20 quad at y = 0, x and z in [-10, 10], normal +Y, uv in [0, 10] (repeat).
 * All meshes wind counter-clockwise seen from outside, and the texture reads unmirrored from
 * outside: u grows to the viewer's right, v grows upward (seen with +Y up).
 *
 * Why u runs this way: the point facing direction d = (sin a, 0, cos a) is seen from outside by
 * a viewer looking along -d with up +Y; the viewer's right is (-d) x Y = d/da, so u must grow
 * with a. a = 2*pi*u + pi puts the seam (u = 0) at the back. */
#include "gen.h"

#include <math.h>

#define PI 3.14159265358979323846

/* Horizontal unit direction for u in [0,1]: u = 0 -> -Z, u = 0.25 -> -X, u = 0.5 -> +Z. */
static gen_vec3 around(double u)
{
    double a = 2.0 * PI * u + PI;
    return gen_vec(sin(a), 0.0, cos(a));
}

void shapes_cube(struct trimesh *m)
{
    /* Per face: normal n, right r, up w with r x w = n, so corners c-r-w, c+r-w, c+r+w, c-r+w
     * are counter-clockwise from outside and carry uv (0,0) (1,0) (1,1) (0,1). */
    static const double FACE[6][3][3] = {
        { { 0, 0, 1 }, { 1, 0, 0 }, { 0, 1, 0 } },     /* +Z front */
        { { 1, 0, 0 }, { 0, 0, -1 }, { 0, 1, 0 } },    /* +X right */
        { { 0, 0, -1 }, { -1, 0, 0 }, { 0, 1, 0 } },   /* -Z back */
        { { -1, 0, 0 }, { 0, 0, 1 }, { 0, 1, 0 } },    /* -X left */
        { { 0, 1, 0 }, { 1, 0, 0 }, { 0, 0, -1 } },    /* +Y top */
        { { 0, -1, 0 }, { 1, 0, 0 }, { 0, 0, 1 } },    /* -Y bottom */
    };
    static const double CORNER[4][2] = { { -1, -1 }, { 1, -1 }, { 1, 1 }, { -1, 1 } };
    /* The 8 corners, indexed by sign bits (x > 0) | (y > 0) << 1 | (z > 0) << 2. */
    int corner[8];
    for (int b = 0; b < 8; b++)
        corner[b] = trimesh_add_v(m, gen_vec(b & 1 ? 0.5 : -0.5, b & 2 ? 0.5 : -0.5,
                                             b & 4 ? 0.5 : -0.5));
    int vt[4];
    for (int k = 0; k < 4; k++)
        vt[k] = trimesh_add_vt(m, 0.5 * (CORNER[k][0] + 1.0), 0.5 * (CORNER[k][1] + 1.0));
    for (int f = 0; f < 6; f++) {
        const double *n = FACE[f][0], *r = FACE[f][1], *w = FACE[f][2];
        int vn = trimesh_add_vn(m, gen_vec(n[0], n[1], n[2]));
        int v[4];
        for (int k = 0; k < 4; k++) {
            double p[3];
            for (int a = 0; a < 3; a++)
                p[a] = 0.5 * (n[a] + CORNER[k][0] * r[a] + CORNER[k][1] * w[a]);
            v[k] = corner[(p[0] > 0) | (p[1] > 0) << 1 | (p[2] > 0) << 2];
        }
        trimesh_add_tri(m, (int[3]){ v[0], v[1], v[2] }, (int[3]){ vt[0], vt[1], vt[2] },
                     (int[3]){ vn, vn, vn });
        trimesh_add_tri(m, (int[3]){ v[0], v[2], v[3] }, (int[3]){ vt[0], vt[2], vt[3] },
                     (int[3]){ vn, vn, vn });
    }
}

void shapes_sphere(struct trimesh *m, int stacks, int slices)
{
    const double radius = 0.5;
    /* Positions (and vn, same index): north pole, rings 1..stacks-1 of `slices` each, south. */
    int north = trimesh_add_v(m, gen_vec(0, radius, 0));
    trimesh_add_vn(m, gen_vec(0, 1, 0));
    for (int i = 1; i < stacks; i++) {
        double th = PI * i / stacks;
        for (int j = 0; j < slices; j++) {
            gen_vec3 d = around((double)j / slices);
            gen_vec3 n = gen_vec(d.x * sin(th), cos(th), d.z * sin(th));
            trimesh_add_v(m, gen_scale(n, radius));
            trimesh_add_vn(m, n);
        }
    }
    int south = trimesh_add_v(m, gen_vec(0, -radius, 0));
    trimesh_add_vn(m, gen_vec(0, -1, 0));

    /* vt: rings with slices+1 columns (the seam column is doubled), then one vt per pole
     * triangle at the middle of its slice. */
    int vt_ring0 = m->nvt;
    for (int i = 1; i < stacks; i++)
        for (int j = 0; j <= slices; j++)
            trimesh_add_vt(m, (double)j / slices, 1.0 - (double)i / stacks);
    int vt_north = m->nvt;
    for (int j = 0; j < slices; j++)
        trimesh_add_vt(m, (j + 0.5) / slices, 1.0);
    int vt_south = m->nvt;
    for (int j = 0; j < slices; j++)
        trimesh_add_vt(m, (j + 0.5) / slices, 0.0);

#define RING_V(i, j) (1 + ((i) - 1) * slices + (j) % slices)
#define RING_T(i, j) (vt_ring0 + ((i) - 1) * (slices + 1) + (j))
    for (int j = 0; j < slices; j++) {
        int v[3] = { RING_V(1, j), RING_V(1, j + 1), north };
        int t[3] = { RING_T(1, j), RING_T(1, j + 1), vt_north + j };
        trimesh_add_tri(m, v, t, v);
    }
    for (int i = 1; i + 1 < stacks; i++) {
        for (int j = 0; j < slices; j++) {
            /* a b lower ring (i+1), c d upper ring (i): counter-clockwise in uv */
            int a = RING_V(i + 1, j), b = RING_V(i + 1, j + 1);
            int c = RING_V(i, j + 1), d = RING_V(i, j);
            int ta = RING_T(i + 1, j), tb = RING_T(i + 1, j + 1);
            int tc = RING_T(i, j + 1), td = RING_T(i, j);
            trimesh_add_tri(m, (int[3]){ a, b, c }, (int[3]){ ta, tb, tc }, (int[3]){ a, b, c });
            trimesh_add_tri(m, (int[3]){ a, c, d }, (int[3]){ ta, tc, td }, (int[3]){ a, c, d });
        }
    }
    for (int j = 0; j < slices; j++) {
        int v[3] = { south, RING_V(stacks - 1, j + 1), RING_V(stacks - 1, j) };
        int t[3] = { vt_south + j, RING_T(stacks - 1, j + 1), RING_T(stacks - 1, j) };
        trimesh_add_tri(m, v, t, v);
    }
#undef RING_V
#undef RING_T
}

void shapes_torus(struct trimesh *m, int rings, int sides)
{
    const double major = 0.35, minor = 0.15, u_repeat = 2.0;
    for (int i = 0; i < rings; i++) {
        gen_vec3 d = around((double)i / rings);
        for (int j = 0; j < sides; j++) {
            double th = 2.0 * PI * j / sides;
            gen_vec3 n = gen_vec(d.x * cos(th), sin(th), d.z * cos(th));
            trimesh_add_v(m, gen_add(gen_scale(d, major), gen_scale(n, minor)));
            trimesh_add_vn(m, n);
        }
    }
    for (int i = 0; i <= rings; i++)
        for (int j = 0; j <= sides; j++)
            trimesh_add_vt(m, u_repeat * i / rings, (double)j / sides);
#define TV(i, j) (((i) % rings) * sides + (j) % sides)
#define TT(i, j) ((i) * (sides + 1) + (j))
    for (int i = 0; i < rings; i++) {
        for (int j = 0; j < sides; j++) {
            int a = TV(i, j), b = TV(i + 1, j), c = TV(i + 1, j + 1), d = TV(i, j + 1);
            int ta = TT(i, j), tb = TT(i + 1, j), tc = TT(i + 1, j + 1), td = TT(i, j + 1);
            trimesh_add_tri(m, (int[3]){ a, b, c }, (int[3]){ ta, tb, tc }, (int[3]){ a, b, c });
            trimesh_add_tri(m, (int[3]){ a, c, d }, (int[3]){ ta, tc, td }, (int[3]){ a, c, d });
        }
    }
#undef TV
#undef TT
}

void shapes_floor(struct trimesh *m)
{
    const double half = 10.0, repeat = 10.0;
    /* counter-clockwise seen from above: right = +X, up (v) = -Z */
    int v0 = trimesh_add_v(m, gen_vec(-half, 0, half));
    int v1 = trimesh_add_v(m, gen_vec(half, 0, half));
    int v2 = trimesh_add_v(m, gen_vec(half, 0, -half));
    int v3 = trimesh_add_v(m, gen_vec(-half, 0, -half));
    int t0 = trimesh_add_vt(m, 0, 0);
    int t1 = trimesh_add_vt(m, repeat, 0);
    int t2 = trimesh_add_vt(m, repeat, repeat);
    int t3 = trimesh_add_vt(m, 0, repeat);
    int n = trimesh_add_vn(m, gen_vec(0, 1, 0));
    trimesh_add_tri(m, (int[3]){ v0, v1, v2 }, (int[3]){ t0, t1, t2 }, (int[3]){ n, n, n });
    trimesh_add_tri(m, (int[3]){ v0, v2, v3 }, (int[3]){ t0, t2, t3 }, (int[3]){ n, n, n });
}
