/* glbench.c: Mesa's time for the workloads `make bench` times rastty on (benchmarks only).
 *
 *   glbench MODEL.obj|MODEL.ply [--texture FILE] [--size WxH] [--shade gouraud|phong] [--cull back|none]
 *           [--eye x,y,z] [--target x,y,z] [--fov DEG] [--near N] [--far F] [--frames N]
 *           [--warmup N] [--float]
 *
 * The model is drawn the way an ordinary OpenGL program would: OSMesa (llvmpipe; set
 * LP_NUM_THREADS=0 for one thread), an RGBA8 framebuffer with a 24-bit depth buffer, one
 * vertex buffer, GLSL 3.30 shaders implementing rastty's lighting conventions (Gouraud:
 * lit per vertex; phong: per pixel), nearest texture sampling, depth test LESS, back faces
 * culled on request (--float: into an RGBA32F colour and 32F depth framebuffer object, as
 * the Mesa oracle renders, which is slower). Each frame is glClear + glDrawArrays + glFinish;
 * prints
 * "median_ms=X min_ms=Y" over N frames after the warm-up. A tiny OBJ reader (v, vt, vn, f
 * with fans) is enough for the benchmark models; normals missing from the file are the
 * area-weighted vertex normals rastty computes too. A PLY is read if it is the binary one
 * build/bench/gensphere writes (load_ply), and drawn indexed (glDrawElements: one vertex
 * per position, as an OpenGL program draws a mesh with shared vertices); OBJ with
 * glDrawArrays, three vertices a triangle. --out FILE.ppm writes the last frame (to check
 * that both renderers see the same picture). */
#define GL_GLEXT_PROTOTYPES 1
#include <GL/osmesa.h>
#include <GL/gl.h>
#include <GL/glext.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <stb_image.h>

struct vtx {
    float p[3], t[2], n[3];
};

struct model {
    float *p, *t, *n;
    size_t np, nt, nn, cp, ct, cn;
    struct vtx *v;
    size_t nv, cv;
    uint32_t *idx; /* PLY: v holds one vertex per position, idx the triangles' corners */
    size_t ni;
};

static void *grow(void *a, size_t *cap, size_t need, size_t sz)
{
    if (need <= *cap)
        return a;
    size_t c = *cap ? *cap * 2 : 1024;
    while (c < need)
        c *= 2;
    void *b = realloc(a, c * sz);
    if (!b) {
        fprintf(stderr, "glbench: out of memory\n");
        exit(1);
    }
    *cap = c;
    return b;
}

/* "i", "i/j", "i//k", "i/j/k" -> 0-based indices (-1 absent) */
static void corner(const char *s, size_t np, size_t nt, size_t nn, long out[3])
{
    long v[3] = {0, 0, 0};
    char *e;
    v[0] = strtol(s, &e, 10);
    if (*e == '/') {
        s = e + 1;
        if (*s != '/')
            v[1] = strtol(s, &e, 10);
        else
            e = (char *)s;
        if (*e == '/')
            v[2] = strtol(e + 1, &e, 10);
    }
    size_t n[3] = {np, nt, nn};
    for (int k = 0; k < 3; k++)
        out[k] = v[k] > 0 ? v[k] - 1 : v[k] < 0 ? (long)n[k] + v[k] : -1;
}

static int load_ply(FILE *f, struct model *m);

/* the triangle's unnormalized normal (its length twice the area: summed, area-weighted) */
static void tri_normal(const float a[3], const float b[3], const float c[3], float out[3])
{
    float e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    float e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    out[0] = e1[1] * e2[2] - e1[2] * e2[1];
    out[1] = e1[2] * e2[0] - e1[0] * e2[2];
    out[2] = e1[0] * e2[1] - e1[1] * e2[0];
}

static int load(const char *path, struct model *m)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return -1;
    char line[4096];
    if (fgets(line, sizeof line, f) && !strncmp(line, "ply", 3)) {
        int r = load_ply(f, m);
        fclose(f);
        return r;
    }
    rewind(f);
    long (*face)[3] = NULL;
    size_t cap_face = 0;
    while (fgets(line, sizeof line, f)) {
        if (line[0] == 'v' && line[1] == ' ') {
            m->p = grow(m->p, &m->cp, 3 * (m->np + 1), sizeof *m->p);
            sscanf(line + 2, "%f %f %f", &m->p[3 * m->np], &m->p[3 * m->np + 1],
                   &m->p[3 * m->np + 2]);
            m->np++;
        } else if (line[0] == 'v' && line[1] == 't') {
            m->t = grow(m->t, &m->ct, 2 * (m->nt + 1), sizeof *m->t);
            m->t[2 * m->nt] = m->t[2 * m->nt + 1] = 0;
            sscanf(line + 3, "%f %f", &m->t[2 * m->nt], &m->t[2 * m->nt + 1]);
            m->nt++;
        } else if (line[0] == 'v' && line[1] == 'n') {
            m->n = grow(m->n, &m->cn, 3 * (m->nn + 1), sizeof *m->n);
            sscanf(line + 3, "%f %f %f", &m->n[3 * m->nn], &m->n[3 * m->nn + 1],
                   &m->n[3 * m->nn + 2]);
            m->nn++;
        } else if (line[0] == 'f' && line[1] == ' ') {
            size_t k = 0;
            for (char *tok = strtok(line + 2, " \t\r\n"); tok; tok = strtok(NULL, " \t\r\n")) {
                face = grow(face, &cap_face, k + 1, sizeof *face);
                corner(tok, m->np, m->nt, m->nn, face[k++]);
            }
            for (size_t i = 1; i + 1 < k; i++) {
                long *c[3] = {face[0], face[i], face[i + 1]};
                m->v = grow(m->v, &m->cv, m->nv + 3, sizeof *m->v);
                for (int j = 0; j < 3; j++) {
                    struct vtx *o = &m->v[m->nv++];
                    memset(o, 0, sizeof *o);
                    if (c[j][0] >= 0 && (size_t)c[j][0] < m->np)
                        memcpy(o->p, &m->p[3 * c[j][0]], sizeof o->p);
                    if (c[j][1] >= 0 && (size_t)c[j][1] < m->nt)
                        memcpy(o->t, &m->t[2 * c[j][1]], sizeof o->t);
                    if (c[j][2] >= 0 && (size_t)c[j][2] < m->nn)
                        memcpy(o->n, &m->n[3 * c[j][2]], sizeof o->n);
                }
            }
        }
    }
    free(face);
    fclose(f);
    return m->nv ? 0 : -1;
}

/* The binary little-endian PLY that build/bench/gensphere writes (tests/bench_scale.sh's
 * spheres): a vertex element of float properties (x, y, z among them) and a face element
 * of one list (uchar count, int or uint indices), fanned. The file has no normals: each
 * corner gets its position's area-weighted smooth normal (what rastty draws it with). */
static int load_ply(FILE *f, struct model *m)
{
    char line[256];
    long nv = -1, nf = -1, ix = -1, iy = -1, iz = -1, nprop = 0;
    int in_vertex = 0, fmt_ok = 0, list_ok = 0;
    while (fgets(line, sizeof line, f) && strncmp(line, "end_header", 10)) {
        char a[64], b[64], c[64], d[64], e[64];
        if (sscanf(line, "format %63s", a) == 1)
            fmt_ok = !strcmp(a, "binary_little_endian");
        else if (sscanf(line, "element %63s %63s", a, b) == 2) {
            in_vertex = !strcmp(a, "vertex");
            if (in_vertex)
                nv = atol(b);
            else if (!strcmp(a, "face"))
                nf = atol(b);
        } else if (sscanf(line, "property list %63s %63s %63s", a, b, c) == 3)
            list_ok = !strcmp(a, "uchar") && (!strcmp(b, "uint") || !strcmp(b, "int"));
        else if (in_vertex && sscanf(line, "property %63s %63s", d, e) == 2) {
            if (strcmp(d, "float"))
                return -1;
            if (!strcmp(e, "x"))
                ix = nprop;
            else if (!strcmp(e, "y"))
                iy = nprop;
            else if (!strcmp(e, "z"))
                iz = nprop;
            nprop++;
        }
    }
    if (!fmt_ok || !list_ok || nv < 1 || nf < 1 || ix < 0 || iy < 0 || iz < 0) {
        fprintf(stderr, "glbench: PLY: only binary little-endian float x,y,z and uchar/uint "
                        "faces (gensphere's)\n");
        return -1;
    }
    float *rec = malloc((size_t)nprop * sizeof *rec);
    m->np = (size_t)nv;
    m->p = malloc(3 * m->np * sizeof *m->p);
    float *n = calloc(3 * m->np, sizeof *n);
    if (!rec || !m->p || !n)
        return -1;
    for (size_t i = 0; i < m->np; i++) {
        if (fread(rec, sizeof *rec, (size_t)nprop, f) != (size_t)nprop)
            return -1;
        m->p[3 * i] = rec[ix], m->p[3 * i + 1] = rec[iy], m->p[3 * i + 2] = rec[iz];
    }
    free(rec);
    uint32_t *idx = NULL;
    size_t ni = 0, cap_i = 0;
    for (long k = 0; k < nf; k++) {
        unsigned char cnt;
        uint32_t c[256];
        if (fread(&cnt, 1, 1, f) != 1 || fread(c, sizeof *c, cnt, f) != cnt)
            return -1;
        for (unsigned j = 0; j < cnt; j++)
            if (c[j] >= m->np)
                return -1;
        for (unsigned j = 1; j + 1 < cnt; j++) {
            idx = grow(idx, &cap_i, ni + 3, sizeof *idx);
            idx[ni++] = c[0], idx[ni++] = c[j], idx[ni++] = c[j + 1];
        }
    }
    for (size_t i = 0; i + 2 < ni; i += 3) {
        float x[3];
        tri_normal(&m->p[3 * idx[i]], &m->p[3 * idx[i + 1]], &m->p[3 * idx[i + 2]], x);
        for (int j = 0; j < 3; j++)
            for (int q = 0; q < 3; q++)
                n[3 * idx[i + j] + q] += x[q];
    }
    m->v = calloc(m->np, sizeof *m->v);
    if (!m->v)
        return -1;
    for (size_t i = 0; i < m->np; i++) {
        memcpy(m->v[i].p, &m->p[3 * i], sizeof m->v[i].p);
        memcpy(m->v[i].n, &n[3 * i], sizeof m->v[i].n); /* the shaders normalize */
    }
    m->nv = m->cv = m->np;
    m->nn = m->np; /* normals made: main's flat fallback is for OBJ */
    m->idx = idx, m->ni = ni;
    free(n);
    return ni ? 0 : -1;
}

static const char *vs_gouraud =
    "#version 330 core\n"
    "layout(location=0) in vec3 p; layout(location=1) in vec2 t; layout(location=2) in vec3 n;\n"
    "uniform mat4 mvp; uniform vec3 eye, light;\n"
    "out vec2 uv; out vec3 d; out vec3 s;\n"
    "void main() {\n"
    "  gl_Position = mvp * vec4(p, 1.0); uv = t;\n"
    "  vec3 N = normalize(n), V = normalize(eye - p), H = normalize(light + V);\n"
    "  d = vec3(0.1 + 0.9 * max(dot(N, light), 0.0)); float x = max(dot(N, H), 0.0);\n"
    "  x *= x; x *= x; x *= x; x *= x; s = vec3(x * x);\n"
    "}\n";
static const char *fs_gouraud =
    "#version 330 core\n"
    "in vec2 uv; in vec3 d; in vec3 s; uniform sampler2D tex; out vec4 c;\n"
    "void main() { c = vec4(texture(tex, uv).rgb * d + 0.5 * s, 1.0); }\n";
static const char *vs_phong =
    "#version 330 core\n"
    "layout(location=0) in vec3 p; layout(location=1) in vec2 t; layout(location=2) in vec3 n;\n"
    "uniform mat4 mvp; out vec2 uv; out vec3 wp; out vec3 wn;\n"
    "void main() { gl_Position = mvp * vec4(p, 1.0); uv = t; wp = p; wn = n; }\n";
static const char *fs_phong =
    "#version 330 core\n"
    "in vec2 uv; in vec3 wp; in vec3 wn; uniform sampler2D tex; uniform vec3 eye, light;\n"
    "out vec4 c;\n"
    "void main() {\n"
    "  vec3 N = normalize(wn), V = normalize(eye - wp), H = normalize(light + V);\n"
    "  float x = max(dot(N, H), 0.0); x *= x; x *= x; x *= x; x *= x;\n"
    "  c = vec4(texture(tex, uv).rgb * (0.1 + 0.9 * max(dot(N, light), 0.0)) + 0.5 * x * x, 1.0);\n"
    "}\n";

static GLuint shader(GLenum kind, const char *src)
{
    GLuint s = glCreateShader(kind);
    glShaderSource(s, 1, &src, NULL);
    glCompileShader(s);
    GLint ok;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[1024];
        glGetShaderInfoLog(s, sizeof log, NULL, log);
        fprintf(stderr, "glbench: shader: %s\n", log);
        exit(1);
    }
    return s;
}

static void parse3(const char *s, float v[3])
{
    if (sscanf(s, "%f,%f,%f", &v[0], &v[1], &v[2]) != 3) {
        fprintf(stderr, "glbench: expected x,y,z, got %s\n", s);
        exit(2);
    }
}

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* column-major perspective * lookAt */
static void mvp_matrix(const float eye[3], const float target[3], float fov_deg, float aspect,
                       float n, float fa, float out[16])
{
    float f[3] = {target[0] - eye[0], target[1] - eye[1], target[2] - eye[2]};
    float l = sqrtf(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    for (int k = 0; k < 3; k++)
        f[k] /= l;
    float up[3] = {0, 1, 0};
    float s[3] = {f[1] * up[2] - f[2] * up[1], f[2] * up[0] - f[0] * up[2], f[0] * up[1] - f[1] * up[0]};
    l = sqrtf(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
    for (int k = 0; k < 3; k++)
        s[k] /= l;
    float u[3] = {s[1] * f[2] - s[2] * f[1], s[2] * f[0] - s[0] * f[2], s[0] * f[1] - s[1] * f[0]};
    float v[16] = {s[0], u[0], -f[0], 0, s[1], u[1], -f[1], 0, s[2], u[2], -f[2], 0,
                   -(s[0] * eye[0] + s[1] * eye[1] + s[2] * eye[2]),
                   -(u[0] * eye[0] + u[1] * eye[1] + u[2] * eye[2]),
                   f[0] * eye[0] + f[1] * eye[1] + f[2] * eye[2], 1};
    float t = 1.0f / tanf(fov_deg * 3.14159265f / 360.0f);
    float p[16] = {t / aspect, 0, 0, 0, 0, t, 0, 0, 0, 0, (fa + n) / (n - fa), -1,
                   0, 0, 2 * fa * n / (n - fa), 0};
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++) {
            float a = 0;
            for (int k = 0; k < 4; k++)
                a += p[k * 4 + r] * v[c * 4 + k];
            out[c * 4 + r] = a;
        }
}

int main(int argc, char **argv)
{
    const char *model = NULL, *texture = NULL, *out = NULL;
    int w = 160, h = 96, frames = 100, warmup = 10, phong = 0, cull = 1, fbo_float = 0;
    float eye[3] = {0, 0, 3}, target[3] = {0, 0, 0}, fov = 50, znear = 0.1f, zfar = 100;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : "";
        if (a[0] != '-') {
            model = a;
            continue;
        }
        if (!strcmp(a, "--float")) {
            fbo_float = 1;
            continue;
        }
        i++;
        if (!strcmp(a, "--texture"))
            texture = v;
        else if (!strcmp(a, "--size"))
            sscanf(v, "%dx%d", &w, &h);
        else if (!strcmp(a, "--shade"))
            phong = !strcmp(v, "phong");
        else if (!strcmp(a, "--cull"))
            cull = !strcmp(v, "back");
        else if (!strcmp(a, "--eye"))
            parse3(v, eye);
        else if (!strcmp(a, "--target"))
            parse3(v, target);
        else if (!strcmp(a, "--fov"))
            fov = (float)atof(v);
        else if (!strcmp(a, "--near"))
            znear = (float)atof(v);
        else if (!strcmp(a, "--far"))
            zfar = (float)atof(v);
        else if (!strcmp(a, "--up"))
            ; /* +Y: the only up rastty's framing produces */
        else if (!strcmp(a, "--frames"))
            frames = atoi(v);
        else if (!strcmp(a, "--out"))
            out = v;
        else if (!strcmp(a, "--warmup"))
            warmup = atoi(v);
        else {
            fprintf(stderr, "glbench: unknown option %s\n", a);
            return 2;
        }
    }
    struct model m = {0};
    if (!model || frames < 1 || load(model, &m)) {
        fprintf(stderr, "usage: glbench MODEL.obj|MODEL.ply [options] (see the source)\n");
        return 2;
    }
    if (!m.nn) { /* area-weighted smooth normals by position */
        for (size_t i = 0; i + 2 < m.nv; i += 3) {
            float n[3];
            tri_normal(m.v[i].p, m.v[i + 1].p, m.v[i + 2].p, n);
            for (int j = 0; j < 3; j++)
                for (int k = 0; k < 3; k++)
                    m.v[i + j].n[k] = n[k];
        }
    }
    OSMesaContext ctx = OSMesaCreateContextAttribs(
        (const int[]){OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24, OSMESA_PROFILE,
                      OSMESA_CORE_PROFILE, OSMESA_CONTEXT_MAJOR_VERSION, 3,
                      OSMESA_CONTEXT_MINOR_VERSION, 3, 0},
        NULL);
    unsigned char *buf = malloc((size_t)w * h * 4);
    if (!ctx || !buf || !OSMesaMakeCurrent(ctx, buf, GL_UNSIGNED_BYTE, w, h)) {
        fprintf(stderr, "glbench: no OSMesa context\n");
        return 1;
    }
    if (fbo_float) {
        GLuint fbo, color, depth;
        glGenFramebuffers(1, &fbo);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo);
        glGenTextures(1, &color);
        glBindTexture(GL_TEXTURE_2D, color);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, w, h, 0, GL_RGBA, GL_FLOAT, NULL);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, color, 0);
        glGenTextures(1, &depth);
        glBindTexture(GL_TEXTURE_2D, depth);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT32F, w, h, 0, GL_DEPTH_COMPONENT,
                     GL_FLOAT, NULL);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, depth, 0);
        if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
            fprintf(stderr, "glbench: float framebuffer incomplete\n");
            return 1;
        }
        glViewport(0, 0, w, h);
    }
    GLuint prog = glCreateProgram();
    glAttachShader(prog, shader(GL_VERTEX_SHADER, phong ? vs_phong : vs_gouraud));
    glAttachShader(prog, shader(GL_FRAGMENT_SHADER, phong ? fs_phong : fs_gouraud));
    glLinkProgram(prog);
    glUseProgram(prog);
    float mvp[16], light[3] = {0.57735f, 0.57735f, 0.57735f};
    mvp_matrix(eye, target, fov, (float)w / h, znear, zfar, mvp);
    glUniformMatrix4fv(glGetUniformLocation(prog, "mvp"), 1, GL_FALSE, mvp);
    glUniform3fv(glGetUniformLocation(prog, "eye"), 1, eye);
    glUniform3fv(glGetUniformLocation(prog, "light"), 1, light);
    GLuint tex;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    int tw = 1, th = 1, tn;
    stbi_set_flip_vertically_on_load(1); /* GL's t = 0 is the image's bottom row */
    unsigned char white[4] = {255, 255, 255, 255};
    unsigned char *px = texture ? stbi_load(texture, &tw, &th, &tn, 4) : NULL;
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, tw, th, 0, GL_RGBA, GL_UNSIGNED_BYTE, px ? px : white);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    GLuint vao, vbo;
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glGenBuffers(1, &vbo);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(m.nv * sizeof *m.v), m.v, GL_STATIC_DRAW);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof *m.v, (void *)0);
    glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, sizeof *m.v, (void *)(3 * sizeof(float)));
    glVertexAttribPointer(2, 3, GL_FLOAT, GL_FALSE, sizeof *m.v, (void *)(5 * sizeof(float)));
    for (int k = 0; k < 3; k++)
        glEnableVertexAttribArray((GLuint)k);
    if (m.idx) {
        GLuint ebo;
        glGenBuffers(1, &ebo);
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo);
        glBufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(m.ni * sizeof *m.idx), m.idx,
                     GL_STATIC_DRAW);
    }
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    if (cull) {
        glEnable(GL_CULL_FACE);
        glCullFace(GL_BACK);
    }
    glClearColor(0, 0, 0, 1);
    double *ms = malloc((size_t)frames * sizeof *ms);
    for (int i = 0; i < warmup + frames; i++) {
        double t0 = now_ms();
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        if (m.idx)
            glDrawElements(GL_TRIANGLES, (GLsizei)m.ni, GL_UNSIGNED_INT, (void *)0);
        else
            glDrawArrays(GL_TRIANGLES, 0, (GLsizei)m.nv);
        glFinish();
        if (i >= warmup)
            ms[i - warmup] = now_ms() - t0;
    }
    qsort(ms, (size_t)frames, sizeof *ms, cmp);
    printf("frames=%d median_ms=%.4f min_ms=%.4f\n", frames, ms[frames / 2], ms[0]);
    if (out && !fbo_float) { /* GL's row 0 is the bottom one */
        FILE *o = fopen(out, "wb");
        if (!o) {
            perror(out);
            return 1;
        }
        fprintf(o, "P6\n%d %d\n255\n", w, h);
        for (int y = h - 1; y >= 0; y--)
            for (int x = 0; x < w; x++)
                fwrite(&buf[4 * ((size_t)y * w + x)], 3, 1, o);
        fclose(o);
    }
    OSMesaDestroyContext(ctx);
    return 0;
}
