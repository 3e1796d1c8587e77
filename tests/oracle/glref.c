/* glref.c: the oracle's reference renderer — rastty's rendering conventions drawn by Mesa.
 *
 * Same command line as `rastty render` (minus --shade wire), so a scene is one line of flags
 * shared by both programs. It is written from the conventions (the preamble and the comments
 * in rastty's headers), not from rastty's rasterizer, so agreement means something.
 *
 * Pipeline: own OBJ/MTL reader -> non-indexed triangles -> clip coordinates computed on the CPU
 * in double (matrices as gluLookAt/glFrustum/glOrtho) and triangles crossing a frustum plane
 * clipped there in double -> OSMesa core-profile 3.3 context -> FBO (RGBA32F colour,
 * DEPTH_COMPONENT32F depth) -> GLSL 330 shaders implementing unlit/flat/gouraud/phong ->
 * glReadPixels(GL_FLOAT) -> quantise on the CPU with floor(clamp(c,0,1)*255+0.5) -> PPM/PNG
 * with row 0 = top; depth as PFM (rows bottom-to-top, 1.0 where empty).
 * Why clip on the CPU: Mesa transforms and clips in float. With 1e6 coordinates a new vertex
 * interpolated between w=0.1 and w=1e6 is off by ~0.1 in w, and llvmpipe then misses a
 * 10-pixel wedge of a ground triangle at 640x480 (measured; --gl-clip restores Mesa's own
 * float path for comparison; elsewhere the two paths agree well inside the bars).
 * Conventions it relies on GL for: pixel centres at half-integers, depth = 0.5*z_ndc+0.5,
 * depth test LESS, front face = CCW in window coordinates, perspective-correct varyings,
 * screen-linear depth, llvmpipe's 8-bit subpixel snapping and fill rule. GALLIUM_DRIVER
 * picks the Mesa driver (llvmpipe when unset; softpipe calibrates the bars).
 * Exit status: 0 ok, 1 rendering/file error, 2 usage error. */
#define GL_GLEXT_PROTOTYPES 1
#include <GL/osmesa.h>
#include <GL/gl.h>
#include <GL/glext.h>

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stddef.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include <stb_image.h>
#include <stb_image_write.h>

#define MAX_DIM 8192
#define NAME_MAX_LEN 64

struct ref_err {
    char msg[512];
};

__attribute__((format(printf, 2, 3))) static int fail(struct ref_err *e, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(e->msg, sizeof e->msg, fmt, ap);
    va_end(ap);
    return -1;
}

/* ---------------------------------------------------------------- options */

enum { SH_UNLIT, SH_FLAT, SH_GOURAUD, SH_PHONG };
enum { CULL_OFF, CULL_BACK_FACES, CULL_FRONT_FACES };

struct opts {
    const char *model;
    int w, h;
    double eye[3], target[3], up[3];
    double fov_deg, near, far, ortho_h; /* ortho_h 0 = perspective */
    double light[3];                    /* toward the light */
    int shade, linear, cull; /* linear: 0 nearest, 1 bilinear, 2 trilinear (mipmaps) */
    const char *texture, *out, *depth_out;
    int bg[3];
    int verbose;
    int gl_clip; /* Mesa's float transform and clipper instead of ours (calibration) */
};

static int parse_vec3(const char *s, double v_out[3])
{
    char *end;
    for (int i = 0; i < 3; i++) {
        errno = 0;
        v_out[i] = strtod(s, &end);
        if (end == s || errno || !isfinite(v_out[i]))
            return -1;
        s = end;
        if (i < 2) {
            if (*s != ',')
                return -1;
            s++;
        }
    }
    return *s ? -1 : 0;
}

static int parse_num(const char *s, double *out)
{
    char *end;
    errno = 0;
    *out = strtod(s, &end);
    return (end == s || *end || errno || !isfinite(*out)) ? -1 : 0;
}

static int parse_opts(int argc, char **argv, struct opts *o, struct ref_err *e)
{
    memset(o, 0, sizeof *o);
    o->w = 160, o->h = 96;
    o->eye[2] = 3;
    o->up[1] = 1;
    o->fov_deg = 50, o->near = 0.1, o->far = 100;
    o->light[0] = o->light[1] = o->light[2] = 1;
    o->shade = SH_PHONG;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "render") == 0 && i == 1)
            continue; /* accept rastty's subcommand word so scene lines can be pasted */
        if (strcmp(a, "--verbose") == 0) {
            o->verbose = 1;
            continue;
        }
        if (strcmp(a, "--gl-clip") == 0) {
            o->gl_clip = 1;
            continue;
        }
        if (a[0] != '-') {
            if (o->model)
                return fail(e, "glref: more than one model given (%s)", a);
            o->model = a;
            continue;
        }
        if (i + 1 >= argc)
            return fail(e, "glref: %s: missing value", a);
        const char *v = argv[++i];
        double d;
        if (strcmp(a, "--size") == 0) {
            char x;
            int n = 0;
            if (sscanf(v, "%d%c%d%n", &o->w, &x, &o->h, &n) != 3 || x != 'x' || v[n] ||
                o->w < 1 || o->h < 1 || o->w > MAX_DIM || o->h > MAX_DIM)
                return fail(e, "glref: --size: expected WxH, 1..%d", MAX_DIM);
        } else if (strcmp(a, "--eye") == 0) {
            if (parse_vec3(v, o->eye))
                return fail(e, "glref: --eye: expected x,y,z");
        } else if (strcmp(a, "--target") == 0) {
            if (parse_vec3(v, o->target))
                return fail(e, "glref: --target: expected x,y,z");
        } else if (strcmp(a, "--up") == 0) {
            if (parse_vec3(v, o->up))
                return fail(e, "glref: --up: expected x,y,z");
        } else if (strcmp(a, "--light") == 0) {
            if (parse_vec3(v, o->light))
                return fail(e, "glref: --light: expected x,y,z");
        } else if (strcmp(a, "--fov") == 0) {
            if (parse_num(v, &o->fov_deg) || o->fov_deg <= 0 || o->fov_deg >= 180)
                return fail(e, "glref: --fov: expected 0 < DEG < 180");
        } else if (strcmp(a, "--near") == 0) {
            if (parse_num(v, &o->near) || o->near <= 0)
                return fail(e, "glref: --near: expected a positive number");
        } else if (strcmp(a, "--far") == 0) {
            if (parse_num(v, &o->far) || o->far <= 0)
                return fail(e, "glref: --far: expected a positive number");
        } else if (strcmp(a, "--ortho") == 0) {
            if (parse_num(v, &d) || d <= 0)
                return fail(e, "glref: --ortho: expected a positive view height");
            o->ortho_h = d;
        } else if (strcmp(a, "--shade") == 0) {
            static const char *const names[] = {"unlit", "flat", "gouraud", "phong"};
            o->shade = -1;
            for (int k = 0; k < 4; k++)
                if (strcmp(v, names[k]) == 0)
                    o->shade = k;
            if (o->shade < 0)
                return fail(e, "glref: --shade: expected unlit|flat|gouraud|phong");
        } else if (strcmp(a, "--filter") == 0) {
            if (strcmp(v, "nearest") && strcmp(v, "bilinear") && strcmp(v, "trilinear"))
                return fail(e, "glref: --filter: expected nearest|bilinear|trilinear");
            o->linear = strcmp(v, "bilinear") == 0 ? 1 : strcmp(v, "trilinear") == 0 ? 2 : 0;
        } else if (strcmp(a, "--cull") == 0) {
            if (strcmp(v, "none") == 0)
                o->cull = CULL_OFF;
            else if (strcmp(v, "back") == 0)
                o->cull = CULL_BACK_FACES;
            else if (strcmp(v, "front") == 0)
                o->cull = CULL_FRONT_FACES;
            else
                return fail(e, "glref: --cull: expected back|front|none");
        } else if (strcmp(a, "--background") == 0) {
            double c[3];
            if (parse_vec3(v, c))
                return fail(e, "glref: --background: expected r,g,b");
            for (int k = 0; k < 3; k++) {
                if (c[k] < 0 || c[k] > 255 || c[k] != floor(c[k]))
                    return fail(e, "glref: --background: components must be integers 0..255");
                o->bg[k] = (int)c[k];
            }
        } else if (strcmp(a, "--texture") == 0) {
            o->texture = v;
        } else if (strcmp(a, "--out") == 0) {
            o->out = v;
        } else if (strcmp(a, "--depth-out") == 0) {
            o->depth_out = v;
        } else {
            return fail(e, "glref: unknown flag %s", a);
        }
    }
    if (!o->model)
        return fail(e, "glref: no model given");
    size_t n = o->out ? strlen(o->out) : 0;
    if (n < 5 || (strcasecmp(o->out + n - 4, ".ppm") && strcasecmp(o->out + n - 4, ".png")))
        return fail(e, "glref: --out FILE.ppm|FILE.png is required");
    if (o->far <= o->near)
        return fail(e, "glref: --far must be greater than --near");
    if (o->light[0] == 0 && o->light[1] == 0 && o->light[2] == 0)
        return fail(e, "glref: --light: zero vector");
    return 0;
}

/* ---------------------------------------------------------------- OBJ / MTL */

struct ref_mat {
    char name[NAME_MAX_LEN];
    float kd[3], ks[3], ns;
    char *map_kd; /* resolved path or NULL */
    int implicit; /* the material of faces that name none: untextured, albedo 0.8 (GL's default) */
};

struct corner {
    long p, t, n; /* 0-based, t/n = -1 when absent */
};

struct objdata {
    double (*pos)[3];
    size_t npos, cappos;
    double (*uv)[2];
    size_t nuv, capuv;
    double (*nrm)[3];
    size_t nnrm, capnrm;
    struct corner *tri; /* 3 per triangle */
    int *tri_mat;
    size_t ntri, captri, captrimat;
    struct ref_mat *mats;
    size_t nmat, capmat;
};

static int grow(void *pp, size_t *cap, size_t need, size_t elem)
{
    void **p = pp;
    if (need <= *cap)
        return 0;
    size_t nc = *cap ? *cap : 64;
    while (nc < need)
        nc *= 2;
    void *q = realloc(*p, nc * elem);
    if (!q)
        return -1;
    *p = q;
    *cap = nc;
    return 0;
}

static void mat_default(struct ref_mat *m, const char *name)
{
    memset(m, 0, sizeof *m);
    snprintf(m->name, sizeof m->name, "%s", name);
    m->kd[0] = m->kd[1] = m->kd[2] = 1;
    m->ks[0] = m->ks[1] = m->ks[2] = 0.5f;
    m->ns = 32;
}

static char *read_file(const char *path, size_t *len_out, struct ref_err *e)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return fail(e, "%s: %s", path, strerror(errno)), NULL;
    size_t cap = 1 << 16, n = 0;
    char *buf = malloc(cap + 1);
    for (;;) {
        if (!buf)
            break;
        n += fread(buf + n, 1, cap - n, f);
        if (n < cap)
            break;
        cap *= 2;
        char *nb = realloc(buf, cap + 1);
        if (!nb) {
            free(buf);
            buf = NULL;
        } else {
            buf = nb;
        }
    }
    int bad = ferror(f);
    fclose(f);
    if (!buf || bad) {
        free(buf);
        return fail(e, "%s: read error", path), NULL;
    }
    buf[n] = 0;
    *len_out = n;
    return buf;
}

/* Directory part of path including the slash, or "" */
static void dir_of(const char *path, char *out, size_t cap)
{
    const char *s = strrchr(path, '/');
    size_t n = s ? (size_t)(s - path + 1) : 0;
    if (n >= cap)
        n = cap - 1;
    memcpy(out, path, n);
    out[n] = 0;
}

static char *join_path(const char *dir, const char *name)
{
    size_t n = strlen(dir) + strlen(name) + 1;
    char *p = malloc(n);
    if (p)
        snprintf(p, n, "%s%s", name[0] == '/' ? "" : dir, name);
    return p;
}

/* Next whitespace-separated token of *s (modified in place), or NULL. */
static char *token(char **s)
{
    char *p = *s;
    while (*p == ' ' || *p == '\t')
        p++;
    if (!*p)
        return *s = p, NULL;
    char *t = p;
    while (*p && *p != ' ' && *p != '\t')
        p++;
    if (*p)
        *p++ = 0;
    *s = p;
    return t;
}

static int parse_floats(char **s, double *out, int n)
{
    for (int i = 0; i < n; i++) {
        char *t = token(s), *end;
        if (!t)
            return -1;
        out[i] = strtod(t, &end);
        if (*end || !isfinite(out[i]))
            return -1;
    }
    return 0;
}

/* Iterate lines: strips CR, comments, and leading blanks. */
static char *next_line(char **cursor, int *lineno)
{
    char *p = *cursor;
    if (!*p)
        return NULL;
    char *nl = strchr(p, '\n');
    if (nl) {
        *nl = 0;
        *cursor = nl + 1;
    } else {
        *cursor = p + strlen(p);
    }
    (*lineno)++;
    char *hash = strchr(p, '#');
    if (hash)
        *hash = 0;
    size_t n = strlen(p);
    while (n && (p[n - 1] == '\r' || p[n - 1] == ' ' || p[n - 1] == '\t'))
        p[--n] = 0;
    while (*p == ' ' || *p == '\t')
        p++;
    return p;
}

static int mtl_read(const char *path, struct objdata *d, struct ref_err *e)
{
    size_t len;
    char *text = read_file(path, &len, e);
    if (!text)
        return -1;
    char dir[4096];
    dir_of(path, dir, sizeof dir);
    char *cur = text, *line;
    int ln = 0, rc = 0;
    struct ref_mat *m = NULL;
    while (rc == 0 && (line = next_line(&cur, &ln))) {
        char *kw = token(&line);
        if (!kw)
            continue;
        double v[3];
        if (strcmp(kw, "newmtl") == 0) {
            char *name = token(&line);
            if (!name || grow(&d->mats, &d->capmat, d->nmat + 1, sizeof *d->mats)) {
                rc = fail(e, "%s:%d: bad newmtl", path, ln);
                break;
            }
            m = &d->mats[d->nmat++];
            mat_default(m, name);
        } else if (!m) {
            continue; /* statements before the first newmtl */
        } else if (strcmp(kw, "Kd") == 0 || strcmp(kw, "Ks") == 0) {
            if (parse_floats(&line, v, 1)) {
                rc = fail(e, "%s:%d: bad %s", path, ln, kw);
                break;
            }
            if (parse_floats(&line, v + 1, 2))
                v[1] = v[2] = v[0]; /* one value = grey */
            float *dst = kw[1] == 'd' ? m->kd : m->ks;
            for (int k = 0; k < 3; k++)
                dst[k] = (float)v[k];
        } else if (strcmp(kw, "Ns") == 0) {
            if (parse_floats(&line, v, 1)) {
                rc = fail(e, "%s:%d: bad Ns", path, ln);
                break;
            }
            m->ns = (float)v[0];
        } else if (strcmp(kw, "map_Kd") == 0) {
            /* options (-o u v w, -clamp on, ...) precede the name: take the last token */
            char *t, *last = NULL;
            while ((t = token(&line)))
                last = t;
            if (!last) {
                rc = fail(e, "%s:%d: map_Kd without a file name", path, ln);
                break;
            }
            t = last;
            free(m->map_kd);
            m->map_kd = join_path(dir, t);
        }
    }
    free(text);
    return rc;
}

static long resolve_index(const char *s, char **end, size_t count)
{
    long i = strtol(s, end, 10);
    if (*end == s)
        return -2;
    if (i < 0)
        i += (long)count;
    else
        i -= 1;
    return (i < 0 || (size_t)i >= count) ? -3 : i;
}

static int obj_read(const char *path, struct objdata *d, struct ref_err *e)
{
    memset(d, 0, sizeof *d);
    if (grow(&d->mats, &d->capmat, 1, sizeof *d->mats))
        return fail(e, "out of memory");
    mat_default(&d->mats[0], "(default)");
    d->mats[0].implicit = 1;
    d->nmat = 1;
    size_t len;
    char *text = read_file(path, &len, e);
    if (!text)
        return -1;
    char dir[4096];
    dir_of(path, dir, sizeof dir);
    char *cur = text, *line;
    int ln = 0, rc = 0, mat = 0;
    struct corner *poly = NULL;
    size_t cappoly = 0;
    while (rc == 0 && (line = next_line(&cur, &ln))) {
        char *kw = token(&line);
        if (!kw)
            continue;
        double v[3];
        if (strcmp(kw, "v") == 0) {
            if (parse_floats(&line, v, 3) || grow(&d->pos, &d->cappos, d->npos + 1, sizeof *d->pos))
                rc = fail(e, "%s:%d: bad vertex", path, ln);
            else
                memcpy(d->pos[d->npos++], v, sizeof(double[3]));
        } else if (strcmp(kw, "vt") == 0) {
            if (parse_floats(&line, v, 1) || grow(&d->uv, &d->capuv, d->nuv + 1, sizeof *d->uv)) {
                rc = fail(e, "%s:%d: bad texture coordinate", path, ln);
            } else {
                if (parse_floats(&line, v + 1, 1))
                    v[1] = 0;
                d->uv[d->nuv][0] = v[0];
                d->uv[d->nuv++][1] = v[1];
            }
        } else if (strcmp(kw, "vn") == 0) {
            if (parse_floats(&line, v, 3) || grow(&d->nrm, &d->capnrm, d->nnrm + 1, sizeof *d->nrm))
                rc = fail(e, "%s:%d: bad normal", path, ln);
            else
                memcpy(d->nrm[d->nnrm++], v, sizeof(double[3]));
        } else if (strcmp(kw, "f") == 0) {
            size_t n = 0;
            char *t;
            while (rc == 0 && (t = token(&line))) {
                if (grow(&poly, &cappoly, n + 1, sizeof *poly)) {
                    rc = fail(e, "out of memory");
                    break;
                }
                char *end;
                struct corner c = {resolve_index(t, &end, d->npos), -1, -1};
                if (c.p < 0) {
                    rc = fail(e, "%s:%d: bad position index", path, ln);
                    break;
                }
                if (*end == '/') {
                    t = end + 1;
                    if (*t != '/') {
                        c.t = resolve_index(t, &end, d->nuv);
                        if (c.t < 0) {
                            rc = fail(e, "%s:%d: bad uv index", path, ln);
                            break;
                        }
                    } else {
                        end = t;
                    }
                    if (*end == '/') {
                        t = end + 1;
                        c.n = resolve_index(t, &end, d->nnrm);
                        if (c.n < 0) {
                            rc = fail(e, "%s:%d: bad normal index", path, ln);
                            break;
                        }
                    }
                }
                if (*end) {
                    rc = fail(e, "%s:%d: bad face corner", path, ln);
                    break;
                }
                poly[n++] = c;
            }
            if (rc)
                break;
            if (n < 3) {
                rc = fail(e, "%s:%d: face with fewer than 3 corners", path, ln);
                break;
            }
            for (size_t i = 1; i + 1 < n; i++) { /* fan (0, i, i+1) */
                if (grow(&d->tri, &d->captri, 3 * (d->ntri + 1), sizeof *d->tri) ||
                    grow(&d->tri_mat, &d->captrimat, d->ntri + 1, sizeof *d->tri_mat)) {
                    rc = fail(e, "out of memory");
                    break;
                }
                d->tri[3 * d->ntri] = poly[0];
                d->tri[3 * d->ntri + 1] = poly[i];
                d->tri[3 * d->ntri + 2] = poly[i + 1];
                d->tri_mat[d->ntri++] = mat;
            }
        } else if (strcmp(kw, "mtllib") == 0) {
            char *name = line;
            while (*name == ' ' || *name == '\t')
                name++;
            char *p = join_path(dir, name);
            if (!p || mtl_read(p, d, e))
                rc = -1;
            free(p);
        } else if (strcmp(kw, "usemtl") == 0) {
            char *name = token(&line);
            mat = 0;
            for (size_t k = 1; name && k < d->nmat; k++)
                if (strcmp(d->mats[k].name, name) == 0)
                    mat = (int)k;
        }
        /* o, g, s, l, p, ...: ignored */
    }
    free(poly);
    free(text);
    return rc;
}

static void obj_free(struct objdata *d)
{
    for (size_t k = 0; k < d->nmat; k++)
        free(d->mats[k].map_kd);
    free(d->mats);
    free(d->pos);
    free(d->uv);
    free(d->nrm);
    free(d->tri);
    free(d->tri_mat);
}

/* ---------------------------------------------------------------- small vector helpers */

static void cross3(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void normalize3(double v[3], const double fallback[3])
{
    double l = sqrt(dot3(v, v));
    if (l > 0) {
        v[0] /= l, v[1] /= l, v[2] /= l;
    } else {
        v[0] = fallback[0], v[1] = fallback[1], v[2] = fallback[2];
    }
}

/* ---------------------------------------------------------------- matrices (double) */

/* Column-major 4x4, as GL wants it: m[col*4 + row]. */
static void mat_mul(const double a[16], const double b[16], double out[16])
{
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++) {
            double s = 0;
            for (int k = 0; k < 4; k++)
                s += a[k * 4 + r] * b[c * 4 + k];
            out[c * 4 + r] = s;
        }
}

/* gluLookAt: rows s, u, -f; then translate by -eye. */
static int look_at(const double eye[3], const double target[3], const double up[3], double m[16])
{
    double f[3] = {target[0] - eye[0], target[1] - eye[1], target[2] - eye[2]};
    double lf = sqrt(dot3(f, f));
    if (lf == 0)
        return -1;
    for (int k = 0; k < 3; k++)
        f[k] /= lf;
    double s[3], u[3];
    cross3(f, up, s);
    double ls = sqrt(dot3(s, s));
    if (ls == 0)
        return -1;
    for (int k = 0; k < 3; k++)
        s[k] /= ls;
    cross3(s, f, u);
    memset(m, 0, 16 * sizeof *m);
    for (int k = 0; k < 3; k++) {
        m[k * 4 + 0] = s[k];
        m[k * 4 + 1] = u[k];
        m[k * 4 + 2] = -f[k];
    }
    m[12] = -dot3(s, eye);
    m[13] = -dot3(u, eye);
    m[14] = dot3(f, eye);
    m[15] = 1;
    return 0;
}

/* glFrustum(-r, r, -t, t, n, f) with t = n*tan(fov/2), r = t*aspect; or glOrtho with
 * t = H/2, r = t*aspect. */
static void projection(const struct opts *o, double m[16])
{
    double aspect = (double)o->w / o->h, n = o->near, f = o->far;
    memset(m, 0, 16 * sizeof *m);
    if (o->ortho_h > 0) {
        double t = o->ortho_h / 2, r = t * aspect;
        m[0] = 1 / r;
        m[5] = 1 / t;
        m[10] = -2 / (f - n);
        m[14] = -(f + n) / (f - n);
        m[15] = 1;
    } else {
        double t = n * tan(o->fov_deg * M_PI / 360.0), r = t * aspect;
        m[0] = n / r;
        m[5] = n / t;
        m[10] = -(f + n) / (f - n);
        m[11] = -1;
        m[14] = -2 * f * n / (f - n);
    }
}

/* ---------------------------------------------------------------- vertex data and clipping */

/* One vertex as the GPU gets it.
 *   clip       clip-space position, computed on the CPU in double and rounded once
 *   uv/wpos/nrm  this vertex's attributes (world space; the model matrix is the identity)
 *   bary       its barycentrics in its source triangle ((1,0,0) etc. unless clipping made it)
 *   tp, tn     the source triangle's three world positions and normals, in file order:
 *              flat computes the face normal and centroid from tp in GLSL, gouraud lights
 *              the three source corners in GLSL and blends them with bary, which is what a
 *              clipper does to gouraud's per-vertex results. */
struct gpu_vert {
    float clip[4], uv[2], wpos[3], nrm[3], bary[3];
    float tp[3][3], tn[3][3];
};

/* A vertex during clipping: everything that is interpolated, in double. */
struct cvert {
    double clip[4], uv[2], wpos[3], nrm[3], bary[3];
};

#define CLIP_MAX_VERTS 9 /* a triangle cut by 6 planes */

/* Signed distance to frustum plane k (inside >= 0): w+x, w-x, w+y, w-y, w+z, w-z. */
static double plane_dist(const double c[4], int k)
{
    double s = (k & 1) ? -1.0 : 1.0;
    return c[3] + s * c[k >> 1];
}

static void cvert_lerp(const struct cvert *a, const struct cvert *b, double t, struct cvert *out)
{
    const double *pa = (const double *)a, *pb = (const double *)b;
    double *po = (double *)out;
    for (size_t i = 0; i < sizeof *a / sizeof(double); i++)
        po[i] = pa[i] + t * (pb[i] - pa[i]);
}

/* Sutherland-Hodgman against the 6 planes, in double. The new vertex on an edge is always
 * interpolated from its inside end, so two triangles sharing an edge get bit-identical
 * vertices. Returns the vertex count (0 = nothing left). */
static int clip_polygon(struct cvert poly[CLIP_MAX_VERTS], int n)
{
    struct cvert tmp[CLIP_MAX_VERTS];
    for (int k = 0; k < 6 && n > 0; k++) {
        int m = 0;
        for (int i = 0; i < n; i++) {
            const struct cvert *a = &poly[i], *b = &poly[(i + 1) % n];
            double da = plane_dist(a->clip, k), db = plane_dist(b->clip, k);
            if (da >= 0)
                tmp[m++] = *a;
            if ((da >= 0) != (db >= 0)) {
                const struct cvert *in = da >= 0 ? a : b, *out = da >= 0 ? b : a;
                double din = da >= 0 ? da : db, dout = da >= 0 ? db : da;
                cvert_lerp(in, out, din / (din - dout), &tmp[m++]);
            }
        }
        memcpy(poly, tmp, (size_t)m * sizeof *tmp);
        n = m;
    }
    return n;
}

struct vert_buf {
    struct gpu_vert *v;
    size_t n, cap;
};

static int emit(struct vert_buf *b, const struct cvert *c, const double tp[3][3],
                const double tn[3][3])
{
    if (grow(&b->v, &b->cap, b->n + 1, sizeof *b->v))
        return -1;
    struct gpu_vert *g = &b->v[b->n++];
    for (int k = 0; k < 4; k++)
        g->clip[k] = (float)c->clip[k];
    for (int k = 0; k < 3; k++) {
        g->wpos[k] = (float)c->wpos[k];
        g->nrm[k] = (float)c->nrm[k];
        g->bary[k] = (float)c->bary[k];
        for (int j = 0; j < 3; j++) {
            g->tp[j][k] = (float)tp[j][k];
            g->tn[j][k] = (float)tn[j][k];
        }
    }
    g->uv[0] = (float)c->uv[0];
    g->uv[1] = (float)c->uv[1];
    return 0;
}

/* Missing normals: per position index, the sum of the unnormalised face normals
 * cross(p1-p0, p2-p0) of every triangle using that position, normalised; zero -> (0,0,1). */
static double (*generated_normals(const struct objdata *d))[3]
{
    static const double zplus[3] = {0, 0, 1};
    double(*gen)[3] = calloc(d->npos ? d->npos : 1, sizeof *gen);
    if (!gen)
        return NULL;
    for (size_t t = 0; t < d->ntri; t++) {
        const struct corner *c = &d->tri[3 * t];
        double e1[3], e2[3], n[3];
        for (int k = 0; k < 3; k++) {
            e1[k] = d->pos[c[1].p][k] - d->pos[c[0].p][k];
            e2[k] = d->pos[c[2].p][k] - d->pos[c[0].p][k];
        }
        cross3(e1, e2, n);
        for (int j = 0; j < 3; j++)
            for (int k = 0; k < 3; k++)
                gen[c[j].p][k] += n[k];
    }
    for (size_t i = 0; i < d->npos; i++)
        normalize3(gen[i], zplus);
    return gen;
}

/* Expand to non-indexed vertices, grouped by material: material m's vertices are
 * [first_out[m], first_out[m+1]). With cpu_clip, triangles crossing a frustum plane are
 * clipped here in double and fanned (0,i,i+1); otherwise Mesa clips them (in float). */
static int build_vertices(const struct objdata *d, const double mvp[16], int cpu_clip,
                          struct vert_buf *out, size_t *first_out)
{
    static const double zplus[3] = {0, 0, 1};
    double(*gen)[3] = generated_normals(d);
    if (!gen)
        return -1;
    memset(out, 0, sizeof *out);
    for (size_t mat = 0; mat < d->nmat; mat++) {
        first_out[mat] = out->n;
        for (size_t t = 0; t < d->ntri; t++) {
            if ((size_t)d->tri_mat[t] != mat)
                continue;
            const struct corner *c = &d->tri[3 * t];
            struct cvert poly[CLIP_MAX_VERTS];
            double tp[3][3], tn[3][3];
            memset(poly, 0, 3 * sizeof *poly);
            for (int j = 0; j < 3; j++) {
                struct cvert *v = &poly[j];
                memcpy(tp[j], d->pos[c[j].p], sizeof tp[j]);
                if (c[j].n >= 0) {
                    memcpy(tn[j], d->nrm[c[j].n], sizeof tn[j]);
                    normalize3(tn[j], zplus);
                } else {
                    memcpy(tn[j], gen[c[j].p], sizeof tn[j]);
                }
                memcpy(v->wpos, tp[j], sizeof v->wpos);
                memcpy(v->nrm, tn[j], sizeof v->nrm);
                if (c[j].t >= 0)
                    memcpy(v->uv, d->uv[c[j].t], sizeof v->uv);
                v->bary[j] = 1;
                for (int r = 0; r < 4; r++)
                    v->clip[r] = mvp[r] * tp[j][0] + mvp[4 + r] * tp[j][1] +
                                 mvp[8 + r] * tp[j][2] + mvp[12 + r];
            }
            int inside = 1;
            for (int j = 0; j < 3; j++)
                for (int k = 0; k < 6; k++)
                    inside &= plane_dist(poly[j].clip, k) >= 0;
            int n = (cpu_clip && !inside) ? clip_polygon(poly, 3) : 3;
            for (int i = 1; i + 1 < n; i++)
                if (emit(out, &poly[0], tp, tn) || emit(out, &poly[i], tp, tn) ||
                    emit(out, &poly[i + 1], tp, tn)) {
                    free(gen);
                    return -1;
                }
        }
    }
    first_out[d->nmat] = out->n;
    free(gen);
    return 0;
}

/* ---------------------------------------------------------------- shaders */

/* Shared by all stages: the lighting model of the conventions. */
static const char *const glsl_light =
    "uniform vec3 u_eye;      // world space (model matrix = identity)\n"
    "uniform vec3 u_light;    // unit, toward the light\n"
    "uniform int u_ortho;\n"
    "uniform vec3 u_back;     // orthographic V\n"
    "uniform vec3 u_ks;\n"
    "uniform float u_ns;\n"
    "float spec_pow(float x) {\n"
    "    if (u_ns >= 1.0 && u_ns <= 1024.0 && u_ns == floor(u_ns)) {  // as rastty: by squaring\n"
    "        int k = int(u_ns); float r = 1.0;\n"
    "        for (int i = 0; i < 11; i++) {\n"
    "            if (k % 2 == 1) r *= x;\n"
    "            k /= 2;\n"
    "            if (k == 0) break;\n"
    "            x *= x;\n"
    "        }\n"
    "        return r;\n"
    "    }\n"
    "    return x > 0.0 ? pow(x, u_ns) : 0.0;\n"
    "}\n"
    "vec3 view_dir(vec3 p) { return u_ortho != 0 ? u_back : normalize(u_eye - p); }\n"
    "vec2 blinn_phong(vec3 n, vec3 v) {  // (diffuse, specular)\n"
    "    vec3 h = normalize(u_light + v);\n"
    "    return vec2(max(0.0, dot(n, u_light)), spec_pow(max(0.0, dot(n, h))));\n"
    "}\n";

/* Flat: face normal from the source triangle's world positions in file order, lit once with
 * V from its centroid; every vertex of the triangle (and of its clipped pieces) computes the
 * same value. Gouraud: the three source corners lit per vertex, blended with bary. */
static const char *const glsl_vs =
    "layout(location = 0) in vec4 a_clip;\n"
    "layout(location = 1) in vec2 a_uv;\n"
    "layout(location = 2) in vec3 a_wpos;\n"
    "layout(location = 3) in vec3 a_nrm;\n"
    "layout(location = 4) in vec3 a_bary;\n"
    "layout(location = 5) in vec3 a_tp0;\n"
    "layout(location = 6) in vec3 a_tp1;\n"
    "layout(location = 7) in vec3 a_tp2;\n"
    "layout(location = 8) in vec3 a_tn0;\n"
    "layout(location = 9) in vec3 a_tn1;\n"
    "layout(location = 10) in vec3 a_tn2;\n"
    "uniform mat4 u_mvp;\n"
    "uniform int u_gl_transform;  // --gl-clip: float MVP here, Mesa clips\n"
    "out vec2 v_uv;\n"
    "out vec3 v_wpos;\n"
    "out vec3 v_nrm;\n"
    "out vec2 v_ds;\n"
    "flat out vec2 v_flat;\n"
    "void main() {\n"
    "    gl_Position = u_gl_transform != 0 ? u_mvp * vec4(a_wpos, 1.0) : a_clip;\n"
    "    v_uv = a_uv;\n"
    "    v_wpos = a_wpos;\n"
    "    v_nrm = a_nrm;\n"
    "    v_ds = vec2(0.0);\n"
    "    v_flat = vec2(0.0);\n"
    "#if MODE == 1\n"
    "    vec3 n = normalize(cross(a_tp1 - a_tp0, a_tp2 - a_tp0));\n"
    "    v_flat = blinn_phong(n, view_dir((a_tp0 + a_tp1 + a_tp2) / 3.0));\n"
    "#elif MODE == 2\n"
    "    v_ds = a_bary.x * blinn_phong(normalize(a_tn0), view_dir(a_tp0))\n"
    "         + a_bary.y * blinn_phong(normalize(a_tn1), view_dir(a_tp1))\n"
    "         + a_bary.z * blinn_phong(normalize(a_tn2), view_dir(a_tp2));\n"
    "#endif\n"
    "}\n";

static const char *const glsl_fs =
    "in vec2 v_uv;\n"
    "in vec3 v_wpos;\n"
    "in vec3 v_nrm;\n"
    "in vec2 v_ds;\n"
    "flat in vec2 v_flat;\n"
    "uniform sampler2D u_tex;\n"
    "uniform int u_has_tex;\n"
    "uniform vec3 u_kd;\n"
    "layout(location = 0) out vec4 o_color;\n"
    "void main() {\n"
    "    vec3 albedo = u_kd * (u_has_tex != 0 ? texture(u_tex, v_uv).rgb : vec3(1.0));\n"
    "#if MODE == 0\n"
    "    vec3 c = albedo;\n"
    "#elif MODE == 1\n"
    "    vec3 c = albedo * (0.1 + 0.9 * v_flat.x) + u_ks * v_flat.y;\n"
    "#elif MODE == 2\n"
    "    vec3 c = albedo * (0.1 + 0.9 * v_ds.x) + u_ks * v_ds.y;\n"
    "#else\n"
    "    vec2 ds = blinn_phong(normalize(v_nrm), view_dir(v_wpos));\n"
    "    vec3 c = albedo * (0.1 + 0.9 * ds.x) + u_ks * ds.y;\n"
    "#endif\n"
    "    o_color = vec4(c, 1.0);\n"
    "}\n";

/* a GL info log as one line of an error message */
static const char *one_line(char *log)
{
    for (char *p = log; *p; p++)
        if (*p == '\n')
            *p = ' ';
    return log;
}

static GLuint compile(GLenum type, int mode, const char *body, struct ref_err *e)
{
    char head[64];
    snprintf(head, sizeof head, "#version 330 core\n#define MODE %d\n", mode);
    const char *src[3] = {head, glsl_light, body};
    GLuint s = glCreateShader(type);
    glShaderSource(s, 3, src, NULL);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[400];
        glGetShaderInfoLog(s, sizeof log, NULL, log);
        fail(e, "glref: shader compile failed: %s", one_line(log));
        glDeleteShader(s);
        return 0;
    }
    return s;
}

static GLuint build_program(int mode, struct ref_err *e)
{
    GLuint vs = compile(GL_VERTEX_SHADER, mode, glsl_vs, e);
    GLuint fs = vs ? compile(GL_FRAGMENT_SHADER, mode, glsl_fs, e) : 0;
    if (!vs || !fs)
        return 0;
    GLuint p = glCreateProgram();
    glAttachShader(p, vs);
    glAttachShader(p, fs);
    glLinkProgram(p);
    GLint ok = 0;
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[400];
        glGetProgramInfoLog(p, sizeof log, NULL, log);
        fail(e, "glref: program link failed: %s", one_line(log));
        return 0;
    }
    return p;
}

/* ---------------------------------------------------------------- textures */

/* Upload with rows flipped: GL row 0 = the image's bottom row, so texture(tex, (u, v)) with
 * OBJ's v = 1 at the top samples the texel the conventions name. */
static GLuint texture_upload(const char *path, int linear, struct ref_err *e)
{
    int w, h, n;
    unsigned char *px = stbi_load(path, &w, &h, &n, 4);
    if (!px)
        return fail(e, "%s: %s", path, stbi_failure_reason()), 0;
    size_t row = (size_t)w * 4;
    unsigned char *flip = malloc(row * (size_t)h);
    if (!flip) {
        stbi_image_free(px);
        return fail(e, "out of memory"), 0;
    }
    for (int y = 0; y < h; y++)
        memcpy(flip + row * (size_t)y, px + row * (size_t)(h - 1 - y), row);
    stbi_image_free(px);
    GLuint t;
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_2D, t);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, flip);
    free(flip);
    GLint f = linear ? GL_LINEAR : GL_NEAREST;
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER,
                    linear == 2 ? GL_LINEAR_MIPMAP_LINEAR : f);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, f);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_BASE_LEVEL, 0);
    if (linear == 2) { /* GL's own box-filtered chain */
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 1000);
        glGenerateMipmap(GL_TEXTURE_2D);
    } else {
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
    }
    return t;
}

/* ---------------------------------------------------------------- output */

static int write_color(const char *path, int w, int h, const unsigned char *rgb, struct ref_err *e)
{
    size_t n = strlen(path);
    if (n > 4 && strcasecmp(path + n - 4, ".png") == 0) {
        if (!stbi_write_png(path, w, h, 3, rgb, w * 3))
            return fail(e, "%s: cannot write PNG", path);
        return 0;
    }
    if (!(n > 4 && strcasecmp(path + n - 4, ".ppm") == 0))
        return fail(e, "%s: use a .ppm or .png file name", path);
    FILE *f = fopen(path, "wb");
    if (!f)
        return fail(e, "%s: %s", path, strerror(errno));
    fprintf(f, "P6\n%d %d\n255\n", w, h);
    fwrite(rgb, 3, (size_t)w * h, f);
    if (fclose(f))
        return fail(e, "%s: write error", path);
    return 0;
}

/* PFM "Pf", little-endian (scale -1), rows bottom-to-top: GL's readback order already. */
static int write_pfm(const char *path, int w, int h, const float *depth, struct ref_err *e)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return fail(e, "%s: %s", path, strerror(errno));
    fprintf(f, "Pf\n%d %d\n-1.0\n", w, h);
    for (size_t i = 0; i < (size_t)w * h; i++) {
        uint32_t u;
        memcpy(&u, &depth[i], 4);
        unsigned char b[4] = {(unsigned char)u, (unsigned char)(u >> 8), (unsigned char)(u >> 16),
                              (unsigned char)(u >> 24)};
        fwrite(b, 1, 4, f);
    }
    if (fclose(f))
        return fail(e, "%s: write error", path);
    return 0;
}

static unsigned char quantize(float c)
{
    c = c < 0 ? 0 : c > 1 ? 1 : c;
    return (unsigned char)floorf(c * 255.0f + 0.5f);
}

/* ---------------------------------------------------------------- render */

static int render(const struct opts *o, const struct objdata *d, struct ref_err *e)
{
    int rc = -1;
    struct vert_buf vb = {0};
    size_t *first = malloc((d->nmat + 1) * sizeof *first);
    unsigned char *osbuf = malloc((size_t)o->w * o->h * 4);
    float *rgba = malloc((size_t)o->w * o->h * 4 * sizeof(float));
    float *depth = malloc((size_t)o->w * o->h * sizeof(float));
    unsigned char *rgb = malloc((size_t)o->w * o->h * 3);
    GLuint *tex = calloc(d->nmat, sizeof *tex), override = 0;
    OSMesaContext ctx = NULL;
    if (!first || !osbuf || !rgba || !depth || !rgb || !tex) {
        fail(e, "out of memory");
        goto out;
    }

    /* matrices in double; clip coordinates on the CPU in double, rounded once to float */
    double view[16], proj[16], mvp[16];
    if (look_at(o->eye, o->target, o->up, view)) {
        fail(e, "glref: eye, target and up are degenerate");
        goto out;
    }
    projection(o, proj);
    mat_mul(proj, view, mvp);
    if (build_vertices(d, mvp, !o->gl_clip, &vb, first)) {
        fail(e, "out of memory");
        goto out;
    }

    const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 0,
                           OSMESA_STENCIL_BITS, 0, OSMESA_ACCUM_BITS, 0,
                           OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION, 3, OSMESA_CONTEXT_MINOR_VERSION, 3, 0};
    ctx = OSMesaCreateContextAttribs(attribs, NULL);
    if (!ctx) {
        fail(e, "glref: OSMesaCreateContextAttribs failed (core profile 3.3)");
        goto out;
    }
    if (!OSMesaMakeCurrent(ctx, osbuf, GL_UNSIGNED_BYTE, o->w, o->h)) {
        fail(e, "glref: OSMesaMakeCurrent failed");
        goto out;
    }
    if (o->verbose)
        fprintf(stderr, "glref: %s / %s; %zu triangles -> %zu drawn\n",
                (const char *)glGetString(GL_RENDERER), (const char *)glGetString(GL_VERSION),
                d->ntri, vb.n / 3);

    /* FBO: float colour so quantisation happens once, on the CPU, exactly as specified */
    GLuint fbo, color, zbuf;
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glGenTextures(1, &color);
    glBindTexture(GL_TEXTURE_2D, color);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, o->w, o->h, 0, GL_RGBA, GL_FLOAT, NULL);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, color, 0);
    glGenTextures(1, &zbuf);
    glBindTexture(GL_TEXTURE_2D, zbuf);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT32F, o->w, o->h, 0, GL_DEPTH_COMPONENT,
                 GL_FLOAT, NULL);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, zbuf, 0);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        fail(e, "glref: framebuffer incomplete");
        goto out;
    }
    glViewport(0, 0, o->w, o->h);
    glDepthRange(0.0, 1.0);

    GLuint prog = build_program(o->shade, e);
    if (!prog)
        goto out;
    glUseProgram(prog);
    float mvpf[16];
    for (int k = 0; k < 16; k++)
        mvpf[k] = (float)mvp[k];
    glUniformMatrix4fv(glGetUniformLocation(prog, "u_mvp"), 1, GL_FALSE, mvpf);
    glUniform1i(glGetUniformLocation(prog, "u_gl_transform"), o->gl_clip);
    double l[3] = {o->light[0], o->light[1], o->light[2]};
    double back[3] = {o->eye[0] - o->target[0], o->eye[1] - o->target[1],
                      o->eye[2] - o->target[2]};
    static const double zplus[3] = {0, 0, 1};
    normalize3(l, zplus);
    normalize3(back, zplus);
    glUniform3f(glGetUniformLocation(prog, "u_eye"), (float)o->eye[0], (float)o->eye[1],
                (float)o->eye[2]);
    glUniform3f(glGetUniformLocation(prog, "u_light"), (float)l[0], (float)l[1], (float)l[2]);
    glUniform3f(glGetUniformLocation(prog, "u_back"), (float)back[0], (float)back[1],
                (float)back[2]);
    glUniform1i(glGetUniformLocation(prog, "u_ortho"), o->ortho_h > 0);
    glUniform1i(glGetUniformLocation(prog, "u_tex"), 0);

    GLuint vao, vbo;
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glGenBuffers(1, &vbo);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(vb.n * sizeof *vb.v), vb.v, GL_STATIC_DRAW);
    static const struct {
        GLint size;
        size_t offset;
    } layout[] = {
        {4, offsetof(struct gpu_vert, clip)},     {2, offsetof(struct gpu_vert, uv)},
        {3, offsetof(struct gpu_vert, wpos)},     {3, offsetof(struct gpu_vert, nrm)},
        {3, offsetof(struct gpu_vert, bary)},     {3, offsetof(struct gpu_vert, tp[0])},
        {3, offsetof(struct gpu_vert, tp[1])},    {3, offsetof(struct gpu_vert, tp[2])},
        {3, offsetof(struct gpu_vert, tn[0])},    {3, offsetof(struct gpu_vert, tn[1])},
        {3, offsetof(struct gpu_vert, tn[2])},
    };
    for (GLuint k = 0; k < sizeof layout / sizeof layout[0]; k++) {
        glVertexAttribPointer(k, layout[k].size, GL_FLOAT, GL_FALSE, sizeof *vb.v,
                              (const void *)layout[k].offset);
        glEnableVertexAttribArray(k);
    }

    glClearColor(o->bg[0] / 255.0f, o->bg[1] / 255.0f, o->bg[2] / 255.0f, 1.0f);
    glClearDepth(1.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glFrontFace(GL_CCW);
    if (o->cull != CULL_OFF) {
        glEnable(GL_CULL_FACE);
        glCullFace(o->cull == CULL_BACK_FACES ? GL_BACK : GL_FRONT);
    }

    /* one draw per material, in material order; --texture replaces every map_Kd */
    if (o->texture && !(override = texture_upload(o->texture, o->linear, e)))
        goto out;
    for (size_t mat = 0; mat < d->nmat; mat++) {
        if (first[mat + 1] == first[mat])
            continue;
        const struct ref_mat *m = &d->mats[mat];
        GLuint t = override;
        if (!t && m->map_kd) {
            if (!tex[mat] && !(tex[mat] = texture_upload(m->map_kd, o->linear, e)))
                goto out;
            t = tex[mat];
        }
        glActiveTexture(GL_TEXTURE0);
        glBindTexture(GL_TEXTURE_2D, t);
        glUniform1i(glGetUniformLocation(prog, "u_has_tex"), t != 0);
        float kd = m->implicit && !t ? 0.8f : 1.0f; /* GL's default material diffuse */
        glUniform3f(glGetUniformLocation(prog, "u_kd"), m->implicit ? kd : m->kd[0],
                    m->implicit ? kd : m->kd[1], m->implicit ? kd : m->kd[2]);
        glUniform3f(glGetUniformLocation(prog, "u_ks"), m->ks[0], m->ks[1], m->ks[2]);
        glUniform1f(glGetUniformLocation(prog, "u_ns"), m->ns);
        glDrawArrays(GL_TRIANGLES, (GLint)first[mat], (GLsizei)(first[mat + 1] - first[mat]));
    }
    glFinish();
    GLenum err = glGetError();
    if (err != GL_NO_ERROR) {
        fail(e, "glref: GL error 0x%x", err);
        goto out;
    }
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glReadPixels(0, 0, o->w, o->h, GL_RGBA, GL_FLOAT, rgba);
    glReadPixels(0, 0, o->w, o->h, GL_DEPTH_COMPONENT, GL_FLOAT, depth);
    if ((err = glGetError()) != GL_NO_ERROR) {
        fail(e, "glref: GL error 0x%x while reading pixels", err);
        goto out;
    }
    for (int y = 0; y < o->h; y++) { /* GL row 0 = bottom; ours = top */
        const float *src = rgba + (size_t)(o->h - 1 - y) * o->w * 4;
        unsigned char *dst = rgb + (size_t)y * o->w * 3;
        for (int x = 0; x < o->w; x++)
            for (int k = 0; k < 3; k++)
                dst[3 * x + k] = quantize(src[4 * x + k]);
    }
    if (write_color(o->out, o->w, o->h, rgb, e))
        goto out;
    if (o->depth_out && write_pfm(o->depth_out, o->w, o->h, depth, e))
        goto out;
    rc = 0;
out:
    if (ctx)
        OSMesaDestroyContext(ctx); /* frees every GL object of the context */
    free(tex);
    free(vb.v);
    free(first);
    free(osbuf);
    free(rgba);
    free(depth);
    free(rgb);
    return rc;
}

int main(int argc, char **argv)
{
    struct opts o;
    struct ref_err e = {{0}};
    if (parse_opts(argc, argv, &o, &e)) {
        fprintf(stderr, "%s\n", e.msg);
        fprintf(stderr, "usage: glref MODEL.obj --out FILE.ppm|.png [--depth-out FILE.pfm] "
                        "[--size WxH] [--eye x,y,z] [--target x,y,z] [--up x,y,z] [--fov DEG] "
                        "[--near N] [--far F] [--ortho H] [--light x,y,z] "
                        "[--shade unlit|flat|gouraud|phong] [--texture FILE] "
                        "[--filter nearest|bilinear|trilinear] [--background r,g,b] "
                        "[--cull back|front|none] [--verbose] [--gl-clip]\n");
        return 2;
    }
    setenv("GALLIUM_DRIVER", "llvmpipe", 0); /* keep a caller's choice (softpipe) */
    struct objdata d;
    int rc = obj_read(o.model, &d, &e);
    if (rc == 0 && d.ntri == 0)
        rc = fail(&e, "%s: no faces", o.model);
    if (rc == 0)
        rc = render(&o, &d, &e);
    obj_free(&d);
    if (rc) {
        fprintf(stderr, "%s\n", e.msg);
        return 1;
    }
    return 0;
}
