/* sky.c: the default procedural sky as six cubemap faces.
 *
 * Face layout follows the OpenGL cube-map convention (GL 4.6 core spec, table 8.19, "Selection
 * of cube map images"): for direction r with major axis ma, the face is chosen by ma and
 *     s = (sc / |ma| + 1) / 2,  t = (tc / |ma| + 1) / 2
 * with
 *     face   ma   sc    tc          so (sc, tc) -> direction, as sky_face_dir() returns:
 *     posx   +rx  -rz   -ry         ( 1, -tc, -sc)
 *     negx   -rx  +rz   -ry         (-1, -tc,  sc)
 *     posy   +ry  +rx   +rz         (sc,   1,  tc)
 *     negy   -ry  +rx   -rz         (sc,  -1, -tc)
 *     posz   +rz  +rx   -ry         (sc, -tc,   1)
 *     negz   -rz  -rx   -ry         (-sc, -tc, -1)
 * and texel (i, j) of a face image, j = 0 being the FIRST (top) row of the PNG, has its centre
 * at s = (i + 0.5) / size, t = (j + 0.5) / size. GL uploads the first row at t = 0, so side
 * faces have the sky in their top rows, posy's top row looks toward -Z and negy's toward +Z.
 * This is the layout of /work/shared/models/skybox (see its readme.txt). Laid out as a cross
 *         posy
 *   negx  posz  posx  negz
 *         negy
 * the unrotated images join edge to edge (a view from outside the cube).
 *
 * Every texel is computed from its own direction, so colours agree across face edges up to the
 * half-texel step. The sky: horizon -> zenith gradient above y = 0, haze fading into ground
 * colour below it, and a sun disc with glow toward normalize(1, 1, 1), the direction rastty's
 * default light comes from (this is exactly a cube corner: posx, posy and posz share it). */
#include "gen.h"

#include <math.h>

const char *const SKY_FACE_NAME[SKY_FACE_COUNT] = {
    "posx", "negx", "posy", "negy", "posz", "negz",
};

gen_vec3 sky_face_dir(enum sky_face f, double sc, double tc)
{
    switch (f) {
    case SKY_POSX: return gen_vec(1, -tc, -sc);
    case SKY_NEGX: return gen_vec(-1, -tc, sc);
    case SKY_POSY: return gen_vec(sc, 1, tc);
    case SKY_NEGY: return gen_vec(sc, -1, -tc);
    case SKY_POSZ: return gen_vec(sc, -tc, 1);
    default:       return gen_vec(-sc, -tc, -1);
    }
}

static double smoothstep(double e0, double e1, double x)
{
    double t = (x - e0) / (e1 - e0);
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    return t * t * (3 - 2 * t);
}

static gen_vec3 lerp3(gen_vec3 a, gen_vec3 b, double t)
{
    return gen_add(a, gen_scale(gen_sub(b, a), t));
}

gen_vec3 sky_colour(gen_vec3 d)
{
    const gen_vec3 zenith = gen_vec(0.13, 0.32, 0.72), horizon = gen_vec(0.72, 0.83, 0.94);
    const gen_vec3 ground = gen_vec(0.30, 0.27, 0.23);
    const gen_vec3 sun_c = gen_vec(1.0, 0.96, 0.84), glow_c = gen_vec(1.0, 0.80, 0.55);
    const double sun_radius = 0.045;   /* radians: about 2.6 degrees, 7 texels at 256 */
    const double sun_edge = 0.006;     /* soft rim, about 1.7 texels */
    gen_vec3 c;
    if (d.y >= 0)
        c = lerp3(horizon, zenith, pow(d.y, 0.6));
    else
        c = lerp3(horizon, ground, smoothstep(0.0, 0.12, -d.y));
    gen_vec3 sun = gen_norm(gen_vec(1, 1, 1));
    double cosang = gen_dot(d, sun);
    double ang = acos(cosang > 1 ? 1 : cosang < -1 ? -1 : cosang);
    if (cosang > 0) {
        double g = 0.35 * pow(cosang, 400.0) + 0.18 * pow(cosang, 24.0);
        c = gen_add(c, gen_scale(glow_c, g));
    }
    double disc = 1.0 - smoothstep(sun_radius - sun_edge, sun_radius + sun_edge, ang);
    return lerp3(c, sun_c, disc);
}

void sky_face_image(enum sky_face f, int size, unsigned char *rgb_out)
{
    for (int j = 0; j < size; j++) {
        for (int i = 0; i < size; i++) {
            double sc = 2.0 * (i + 0.5) / size - 1.0;
            double tc = 2.0 * (j + 0.5) / size - 1.0;
            gen_vec3 c = sky_colour(gen_norm(sky_face_dir(f, sc, tc)));
            unsigned char *p = rgb_out + ((size_t)j * size + i) * 3;
            double ch[3] = { c.x, c.y, c.z };
            for (int k = 0; k < 3; k++) {
                double v = ch[k] < 0 ? 0 : ch[k] > 1 ? 1 : ch[k];
                p[k] = (unsigned char)floor(v * 255.0 + 0.5);
            }
        }
    }
}
