/* teapot.c: the Utah teapot, tessellated from Newell's 32 Bezier patches (teapot_data.h).
 *
 * Placement: the data is Z-up. It is turned Y-up with (x, y, z) -> (x, z, -y) (a rotation, so
 * windings are kept), scaled uniformly so that the tessellated surface is exactly 2 units wide
 * along X (handle to spout tip), centred on its bounding box in X and Z, and put with its
 * bottom on y = 0 (height about 0.97). The spout points to +X, the handle to -X.
 *
 * Patch p is S(s,t) = sum_r sum_c B_r(s) B_c(t) P[r*4+c] with cubic Bernstein B: s walks the
 * rows of the 4x4 control net, t the columns. In this data set dS/ds x dS/dt points INTO the pot
 * for all 32 patches (checked one by one), so the outward normal is dS/dt x dS/ds and the
 * texture mapping u = t, v = s looks unmirrored from outside. Each patch has its own UVs,
 * [0,1]^2.
 *
 * Degenerate corners: the lid knob and the bottom patches have control row 0 collapsed to one
 * point (the top of the knob, the centre of the bottom), where dS/dt = 0 and the cross product
 * vanishes. Near s = 0, dS/dt ~= s * d2S/(ds dt), so the mixed derivative gives the limit normal
 * there (with the sign flipped at s = 1, and the same for dS/ds at t = 0 or 1).
 *
 * Welding: a sample is merged with an earlier vertex of the same part when closer than
 * WELD_EPS (in data units), which closes every seam between patches. Parts are
 * rim+body+bottom, handle, spout and lid; they are never welded to each other because the
 * handle's lower end touches the body in a single point and merging it would blend two
 * unrelated normals. A welded vertex's normal is the normalised sum of its samples' unit
 * normals; vn index = v index. A quad whose corners merged (at the poles) keeps the one
 * triangle that still has area. Open edges that remain are the ones the teapot really has:
 * the lid's rim, the body's rim, both ends of the spout and both ends of the handle
 * (16 * steps edges). */
#include "gen.h"
#include "teapot_data.h"

#include <math.h>
#include <stdlib.h>

#define WELD_EPS 1e-6
#define DEGENERATE_EPS 1e-9
#define TEAPOT_WIDTH 2.0

enum { PART_BODY, PART_HANDLE, PART_SPOUT, PART_LID };

static int patch_part(int p)
{
    if (p < 12 || p >= 28)
        return PART_BODY;
    if (p < 16)
        return PART_HANDLE;
    if (p < 20)
        return PART_SPOUT;
    return PART_LID;
}

/* Cubic Bernstein basis b and its derivative d at t. */
static void bernstein(double t, double b[4], double d[4])
{
    double u = 1.0 - t;
    b[0] = u * u * u;
    b[1] = 3.0 * t * u * u;
    b[2] = 3.0 * t * t * u;
    b[3] = t * t * t;
    d[0] = -3.0 * u * u;
    d[1] = 3.0 * u * u - 6.0 * t * u;
    d[2] = 6.0 * t * u - 3.0 * t * t;
    d[3] = 3.0 * t * t;
}

/* Position and outward unit normal of patch p at (s, t), in data space (Z up). */
static void eval_patch(int p, double s, double t, gen_vec3 *pos_out, gen_vec3 *n_out)
{
    double bs[4], ds[4], bt[4], dt[4];
    bernstein(s, bs, ds);
    bernstein(t, bt, dt);
    gen_vec3 zero = gen_vec(0, 0, 0), pos = zero, du_s = zero, du_t = zero, mixed = zero;
    for (int r = 0; r < 4; r++) {
        for (int c = 0; c < 4; c++) {
            const double *q = TEAPOT_CP[TEAPOT_PATCH[p][r * 4 + c]];
            gen_vec3 cp = gen_vec(q[0], q[1], q[2]);
            pos = gen_add(pos, gen_scale(cp, bs[r] * bt[c]));
            du_s = gen_add(du_s, gen_scale(cp, ds[r] * bt[c]));
            du_t = gen_add(du_t, gen_scale(cp, bs[r] * dt[c]));
            mixed = gen_add(mixed, gen_scale(cp, ds[r] * dt[c]));
        }
    }
    if (gen_len(du_t) < DEGENERATE_EPS)
        du_t = gen_scale(mixed, s < 0.5 ? 1.0 : -1.0);
    if (gen_len(du_s) < DEGENERATE_EPS)
        du_s = gen_scale(mixed, t < 0.5 ? 1.0 : -1.0);
    *pos_out = pos;
    *n_out = gen_norm(gen_cross(du_t, du_s));
}

struct sample { gen_vec3 pos, n; int part; };

void teapot_build(struct trimesh *m, int steps)
{
    int per = (steps + 1) * (steps + 1);
    int count = TEAPOT_PATCH_COUNT * per;
    struct sample *smp = malloc((size_t)count * sizeof *smp);
    int *vidx = malloc((size_t)count * sizeof *vidx);
    int *vtidx = malloc((size_t)count * sizeof *vtidx);
    int *vpart = malloc((size_t)count * sizeof *vpart);
    gen_vec3 *nsum = malloc((size_t)count * sizeof *nsum);
    if (!smp || !vidx || !vtidx || !vpart || !nsum) {
        m->failed = 1;
        goto out;
    }

    /* 1. Sample every patch and find the bounding box (data space). */
    gen_vec3 lo = gen_vec(1e30, 1e30, 1e30), hi = gen_vec(-1e30, -1e30, -1e30);
    for (int p = 0; p < TEAPOT_PATCH_COUNT; p++) {
        for (int i = 0; i <= steps; i++) {
            for (int j = 0; j <= steps; j++) {
                struct sample *sp = &smp[p * per + i * (steps + 1) + j];
                eval_patch(p, (double)i / steps, (double)j / steps, &sp->pos, &sp->n);
                sp->part = patch_part(p);
                lo = gen_vec(fmin(lo.x, sp->pos.x), fmin(lo.y, sp->pos.y), fmin(lo.z, sp->pos.z));
                hi = gen_vec(fmax(hi.x, sp->pos.x), fmax(hi.y, sp->pos.y), fmax(hi.z, sp->pos.z));
            }
        }
    }
    double scale = TEAPOT_WIDTH / (hi.x - lo.x);
    gen_vec3 centre = gen_vec(0.5 * (lo.x + hi.x), 0.5 * (lo.y + hi.y), lo.z);

    /* 2. Weld within each part (first vertex wins), emit positions and UVs. */
    int nv = 0;
    for (int k = 0; k < count; k++) {
        const struct sample *sp = &smp[k];
        int found = -1;
        for (int w = 0; w < nv && found < 0; w++) {
            if (vpart[w] == sp->part && gen_len(gen_sub(smp[vidx[w]].pos, sp->pos)) < WELD_EPS)
                found = w;
        }
        if (found < 0) {
            found = nv;
            vpart[nv] = sp->part;
            vidx[nv] = k;           /* representative sample of vertex nv */
            nsum[nv] = gen_vec(0, 0, 0);
            nv++;
        }
        nsum[found] = gen_add(nsum[found], sp->n);
        vtidx[k] = found;           /* reused below as "vertex of sample k" */
    }
    for (int w = 0; w < nv; w++) {
        gen_vec3 d = gen_scale(gen_sub(smp[vidx[w]].pos, centre), scale);
        gen_vec3 n = gen_norm(nsum[w]);
        trimesh_add_v(m, gen_vec(d.x, d.z, -d.y));
        trimesh_add_vn(m, gen_vec(n.x, n.z, -n.y));
    }

    /* 3. Triangles: quad (u=t, v=s) corners a b c d counter-clockwise from outside. */
    for (int p = 0; p < TEAPOT_PATCH_COUNT; p++) {
        int vt0 = m->nvt;
        for (int i = 0; i <= steps; i++)
            for (int j = 0; j <= steps; j++)
                trimesh_add_vt(m, (double)j / steps, (double)i / steps);
        for (int i = 0; i < steps; i++) {
            for (int j = 0; j < steps; j++) {
                int k00 = p * per + i * (steps + 1) + j, k01 = k00 + 1;
                int k10 = k00 + steps + 1, k11 = k10 + 1;
                int l00 = vt0 + i * (steps + 1) + j, l01 = l00 + 1;
                int l10 = l00 + steps + 1, l11 = l10 + 1;
                int quad_v[4] = { vtidx[k00], vtidx[k01], vtidx[k11], vtidx[k10] };
                int quad_t[4] = { l00, l01, l11, l10 };
                static const int TRI[2][3] = { { 0, 1, 2 }, { 0, 2, 3 } };
                for (int h = 0; h < 2; h++) {
                    int v[3], t[3];
                    for (int c = 0; c < 3; c++) {
                        v[c] = quad_v[TRI[h][c]];
                        t[c] = quad_t[TRI[h][c]];
                    }
                    if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2])
                        continue;
                    trimesh_add_tri(m, v, t, v);
                }
            }
        }
    }
out:
    free(smp);
    free(vidx);
    free(vtidx);
    free(vpart);
    free(nsum);
}
