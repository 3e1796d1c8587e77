/* scene.c: building scenes from a model or a scene file (see scene.h for the format). */
#include "scene.h"

#include <errno.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cluster.h"
#include "dag.h"
#include "file.h"
#include "lex.h"
#include "lod.h"
#include "material.h"
#include "model.h"

#define MAX_TOKENS 32
#define MAX_PATH 4096

static void set_name(struct scene *s, const char *path)
{
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : strcmp(path, "-") == 0 ? "stdin" : path;
    err_quote(base, strlen(base), sizeof s->name - 4, s->name, sizeof s->name);
}

static void update_bounds(struct scene *s)
{
    vec3 lo = v3(INFINITY, INFINITY, INFINITY), hi = v3(-INFINITY, -INFINITY, -INFINITY);
    for (int i = 0; i < s->n_items; i++) {
        const struct mesh *m = s->items[i].mesh;
        if (m->n_tris == 0)
            continue;
        for (int k = 0; k < 8; k++) { /* the mesh box's corners, placed in the world */
            vec3 p = v3(k & 1 ? m->bbox_max[0] : m->bbox_min[0],
                        k & 2 ? m->bbox_max[1] : m->bbox_min[1],
                        k & 4 ? m->bbox_max[2] : m->bbox_min[2]);
            p = m4_mul_point(s->items[i].model, p);
            lo = v3(fmin(lo.x, p.x), fmin(lo.y, p.y), fmin(lo.z, p.z));
            hi = v3(fmax(hi.x, p.x), fmax(hi.y, p.y), fmax(hi.z, p.z));
        }
    }
    if (!(lo.x <= hi.x))
        lo = v3(-1, -1, -1), hi = v3(1, 1, 1);
    s->bound_lo = lo;
    s->bound_hi = hi;
}

static int load_model(const char *obj_path, const struct model_opts *opts, struct scene *s,
                      struct err *e)
{
    memset(s, 0, sizeof *s);
    if (opts)
        s->load = *opts;
    set_name(s, obj_path);
    if (model_load_with(obj_path, &s->load, &s->textures, &s->warnings, &s->meshes[0], e)) {
        scene_free(s);
        return -1;
    }
    s->n_meshes = 1;
    s->items[0].mesh = &s->meshes[0];
    s->items[0].model = m4_identity();
    s->n_items = 1;
    s->up = s->load.up == MODEL_UP_X   ? 'x'
            : s->load.up == MODEL_UP_Z ? 'z'
            : s->load.up == MODEL_UP_Y ? 'y'
            : s->meshes[0].file_up     ? s->meshes[0].file_up
                                       : 'y';
    update_bounds(s);
    return 0;
}

int scene_load_model(const char *obj_path, struct scene *s, struct err *e)
{
    return load_model(obj_path, NULL, s, e);
}

/* the turn that draws the file's axis a up (mesh_turn_up's): Z-up (x, y, z) -> (x, z, -y),
 * X-up (x, y, z) -> (-y, x, z) */
static mat4 up_turn(char a)
{
    mat4 m = m4_identity();
    if (a == 'z')
        m.m[1][1] = 0, m.m[1][2] = 1, m.m[2][1] = -1, m.m[2][2] = 0;
    else if (a == 'x')
        m.m[0][0] = 0, m.m[0][1] = -1, m.m[1][0] = 1, m.m[1][1] = 0;
    return m;
}

char scene_turn_up(struct scene *s)
{
    char from = s->up ? s->up : 'y', to = from == 'y' ? 'z' : from == 'z' ? 'x' : 'y';
    mat4 undo = up_turn(from), turn;
    for (int r = 0; r < 3; r++) /* a rotation's inverse is its transpose */
        for (int c = r + 1; c < 3; c++) {
            double x = undo.m[r][c];
            undo.m[r][c] = undo.m[c][r];
            undo.m[c][r] = x;
        }
    turn = m4_mul(up_turn(to), undo);
    vec3 c = v3_scale(v3_add(s->bound_lo, s->bound_hi), 0.5);
    mat4 about = m4_mul(m4_translate(c), m4_mul(turn, m4_translate(v3_scale(c, -1))));
    for (int i = 0; i < s->n_items; i++)
        s->items[i].model = m4_mul(about, s->items[i].model);
    s->up = to;
    update_bounds(s);
    return to;
}

int scene_set_texture(struct scene *s, const char *path, struct err *e)
{
    const struct texture *t;
    if (texture_cache_load(&s->textures, path, &t, &s->warnings, e))
        return -1;
    for (int i = 0; i < s->n_items; i++)
        s->items[i].texture_override = t;
    return 0;
}

int scene_set_normal_map(struct scene *s, const char *path, struct err *e)
{
    const struct texture *t;
    if (texture_cache_load(&s->textures, path, &t, &s->warnings, e))
        return -1;
    for (int i = 0; i < s->n_meshes; i++) {
        struct mesh *m = &s->meshes[i];
        struct texture *nt = realloc(m->textures, (m->n_textures + 1) * sizeof *nt);
        if (!nt)
            return err_set(e, "out of memory");
        m->textures = nt;
        struct model_ctx ctx = {.path = path, .cache = &s->textures, .warn = &s->warnings};
        int first = -1;
        for (uint32_t k = 0; k < m->n_materials; k++) {
            struct material *mt = &m->materials[k];
            if (mt->normal_map.tex >= 0)
                continue;
            if (first < 0) {
                if (material_normal_map(m, k, path, path, 0, 1, &ctx, e))
                    return -1;
                first = (int)k;
            } else {
                mt->normal_map = m->materials[first].normal_map;
                mt->normal_space = m->materials[first].normal_space;
                mt->normal_scale = m->materials[first].normal_scale;
                mt->features = true;
            }
        }
        if (first >= 0 && m->materials[first].normal_map.tex >= 0) {
            m->features = true;
            if (m->materials[first].normal_space == MAT_NORMAL_TANGENT && !m->tangents &&
                mesh_tangents(m, false))
                return err_set(e, "out of memory making tangents");
        }
    }
    return 0;
}

/* ---- scene file ---- */

struct parser {
    const char *path; /* quoted for messages */
    int procedural_sky_line; /* 0, or the line of `sky procedural` */
    char dir[MAX_PATH];
    int line;
    char *tok[MAX_TOKENS];
    int n;
    struct err *e;
};

static int perr(struct parser *p, const char *fmt, const char *detail)
{
    char q[96];
    if (detail) {
        err_quote(detail, strlen(detail), 60, q, sizeof q);
        return err_set(p->e, "%s:%d: %s '%s'", p->path, p->line, fmt, q);
    }
    return err_set(p->e, "%s:%d: %s", p->path, p->line, fmt);
}

/* split in place; "quoted strings" may hold spaces; '#' outside quotes ends the line */
static int tokenize(struct parser *p, char *s)
{
    p->n = 0;
    for (;;) {
        while (*s == ' ' || *s == '\t' || *s == '\r')
            s++;
        if (!*s || *s == '#')
            return 0;
        if (p->n == MAX_TOKENS)
            return perr(p, "too many words on one line", NULL);
        if (*s == '"') {
            char *end = strchr(s + 1, '"');
            if (!end)
                return perr(p, "unterminated quote", NULL);
            p->tok[p->n++] = s + 1;
            *end = '\0';
            s = end + 1;
            if (*s && *s != ' ' && *s != '\t' && *s != '\r')
                return perr(p, "expected a space after the closing quote", NULL);
        } else {
            p->tok[p->n++] = s;
            while (*s && *s != ' ' && *s != '\t' && *s != '\r')
                s++;
        }
        if (*s)
            *s++ = '\0';
    }
}

static int num(struct parser *p, int i, double *out)
{
    if (i >= p->n)
        return perr(p, "missing number after", p->tok[i - 1]);
    char *end;
    errno = 0;
    double v = strtod(p->tok[i], &end);
    if (end == p->tok[i] || *end || !isfinite(v))
        return perr(p, "expected a number, got", p->tok[i]);
    *out = v;
    return 0;
}

static int is_number(const char *t)
{
    char *end;
    double v = strtod(t, &end);
    return end != t && *end == '\0' && isfinite(v);
}

static int nums(struct parser *p, int i, int n, double *out)
{
    for (int k = 0; k < n; k++)
        if (num(p, i + k, &out[k]))
            return -1;
    return 0;
}

static int resolve(struct parser *p, const char *rel, char *out)
{
    int n = rel[0] == '/' ? snprintf(out, MAX_PATH, "%s", rel)
                          : snprintf(out, MAX_PATH, "%s%s", p->dir, rel);
    if (n < 0 || n >= MAX_PATH)
        return perr(p, "path too long", NULL);
    return 0;
}

static int prefix_err(struct parser *p)
{
    /* loaders report "file[:line]: ..."; say which scene line asked for the file */
    char inner[sizeof p->e->msg];
    memcpy(inner, p->e->msg, sizeof inner);
    return err_set(p->e, "%s:%d: %s", p->path, p->line, inner);
}

static int st_model(struct parser *p, struct scene *s, char (*names)[MAX_PATH])
{
    if (p->n < 2)
        return perr(p, "model needs a file name", NULL);
    if (s->n_items == SCENE_MAX_ITEMS)
        return perr(p, "too many models (limit 64)", NULL);
    char path[MAX_PATH];
    if (resolve(p, p->tok[1], path))
        return -1;
    int m = -1;
    for (int k = 0; k < s->n_meshes; k++)
        if (strcmp(names[k], path) == 0)
            m = k;
    int item = s->n_items;
    struct draw_item *it = &s->items[item];
    vec3 at = v3(0, 0, 0), rot = v3(0, 0, 0), scale = v3(1, 1, 1);
    const char *tex = NULL;
    for (int i = 2; i < p->n;) {
        const char *kw = p->tok[i];
        double v[3];
        if (strcmp(kw, "at") == 0 || strcmp(kw, "rotate") == 0) {
            if (nums(p, i + 1, 3, v))
                return -1;
            *(kw[0] == 'a' ? &at : &rot) = v3(v[0], v[1], v[2]);
            i += 4;
        } else if (strcmp(kw, "scale") == 0) {
            /* one factor, or three when the next three words are all numbers */
            int three = i + 3 < p->n && is_number(p->tok[i + 2]) && is_number(p->tok[i + 3]);
            if (nums(p, i + 1, three ? 3 : 1, v))
                return -1;
            scale = three ? v3(v[0], v[1], v[2]) : v3(v[0], v[0], v[0]);
            if (scale.x == 0 || scale.y == 0 || scale.z == 0)
                return perr(p, "scale must not be zero", NULL);
            i += three ? 4 : 2;
        } else if (strcmp(kw, "texture") == 0) {
            if (i + 1 >= p->n)
                return perr(p, "texture needs a file name", NULL);
            tex = p->tok[i + 1];
            i += 2;
        } else if (strcmp(kw, "kd") == 0) {
            if (nums(p, i + 1, 3, v))
                return -1;
            for (int k = 0; k < 3; k++) {
                if (!(v[k] >= 0 && v[k] <= 1))
                    return perr(p, "kd components must be in 0..1, got", p->tok[i + 1 + k]);
                s->kd_override[item][k] = (float)v[k];
            }
            it->kd_override = s->kd_override[item];
            i += 4;
        } else {
            return perr(p, "unknown model option", kw);
        }
    }
    if (m < 0) {
        m = s->n_meshes;
        if (model_load_with(path, &s->load, &s->textures, &s->warnings, &s->meshes[m], p->e))
            return prefix_err(p);
        memcpy(names[m], path, MAX_PATH);
        s->n_meshes++;
    }
    if (tex) {
        char tpath[MAX_PATH];
        if (resolve(p, tex, tpath))
            return -1;
        const struct texture *t;
        if (texture_cache_load(&s->textures, tpath, &t, &s->warnings, p->e))
            return prefix_err(p);
        it->texture_override = t;
    }
    it->mesh = &s->meshes[m];
    mat4 r = m4_mul(m4_rotate(v3(0, 0, 1), rot.z),
                    m4_mul(m4_rotate(v3(0, 1, 0), rot.y), m4_rotate(v3(1, 0, 0), rot.x)));
    it->model = m4_mul(m4_translate(at), m4_mul(r, m4_scale(scale)));
    s->n_items++;
    return 0;
}

static int statement(struct parser *p, struct scene *s, char (*names)[MAX_PATH])
{
    const char *kw = p->tok[0];
    double v[6];
    if (strcmp(kw, "model") == 0)
        return st_model(p, s, names);
    if (strcmp(kw, "light") == 0) {
        if (s->n_lights == SCENE_MAX_LIGHTS)
            return perr(p, "too many lights (limit 4)", NULL);
        if (p->n != 4 && p->n != 7)
            return perr(p, "light needs X Y Z [R G B]", NULL);
        if (nums(p, 1, p->n - 1, v))
            return -1;
        struct light *l = &s->lights[s->n_lights];
        l->dir = v3(v[0], v[1], v[2]);
        if (v3_len(l->dir) == 0)
            return perr(p, "light direction must not be zero", NULL);
        l->color = p->n == 7 ? v3(v[3], v[4], v[5]) : v3(1, 1, 1);
        if (l->color.x < 0 || l->color.y < 0 || l->color.z < 0)
            return perr(p, "light colour must not be negative", NULL);
        s->n_lights++;
        return 0;
    }
    if (strcmp(kw, "camera") == 0) {
        camera_default(&s->camera);
        if (nums(p, 1, 3, v))
            return -1;
        s->camera.eye = v3(v[0], v[1], v[2]);
        for (int i = 4; i < p->n;) {
            if (strcmp(p->tok[i], "target") == 0) {
                if (nums(p, i + 1, 3, v))
                    return -1;
                s->camera.target = v3(v[0], v[1], v[2]);
                i += 4;
            } else if (strcmp(p->tok[i], "fov") == 0) {
                if (num(p, i + 1, &v[0]))
                    return -1;
                if (!(v[0] > 0 && v[0] < 180))
                    return perr(p, "fov must be between 0 and 180 degrees", NULL);
                s->camera.fov_deg = v[0];
                i += 2;
            } else {
                return perr(p, "unknown camera option", p->tok[i]);
            }
        }
        vec3 d = v3_sub(s->camera.target, s->camera.eye);
        if (v3_len(d) == 0 || v3_len(v3_cross(d, s->camera.up)) == 0)
            return perr(p, "camera must not look straight up/down or at itself", NULL);
        s->has_camera = true;
        return 0;
    }
    if (strcmp(kw, "background") == 0) {
        if (p->n != 4 || nums(p, 1, 3, v))
            return p->n != 4 ? perr(p, "background needs R G B (0..255)", NULL) : -1;
        for (int k = 0; k < 3; k++) {
            if (!(v[k] >= 0 && v[k] <= 255))
                return perr(p, "background components must be in 0..255, got", p->tok[1 + k]);
            s->background[k] = (uint8_t)(v[k] + 0.5);
        }
        s->has_background = true;
        return 0;
    }
    if (strcmp(kw, "sky") == 0) {
        if (s->has_sky)
            return perr(p, "only one sky per scene", NULL);
        if (p->n == 2 && strcmp(p->tok[1], "procedural") == 0) {
            p->procedural_sky_line = p->line; /* built at the end: the sun follows the first
                                                 light, wherever it is declared */
        } else if (p->n == 7) {
            char paths[6][MAX_PATH];
            const char *pp[6];
            for (int k = 0; k < 6; k++) {
                if (resolve(p, p->tok[1 + k], paths[k]))
                    return -1;
                pp[k] = paths[k];
            }
            if (skybox_load(&s->sky, pp, &s->warnings, p->e))
                return prefix_err(p);
        } else {
            return perr(p, "sky needs 'procedural' or six files POSX NEGX POSY NEGY POSZ NEGZ",
                        NULL);
        }
        s->has_sky = true;
        return 0;
    }
    return perr(p, "unknown statement", kw);
}

static int load_file(const char *path, const struct model_opts *opts, struct scene *s,
                     struct err *e)
{
    memset(s, 0, sizeof *s);
    if (opts)
        s->load = *opts;
    set_name(s, path);
    char qpath[200];
    err_quote(path, strlen(path), 160, qpath, sizeof qpath);
    struct parser p = {.path = qpath, .e = e};
    const char *slash = strrchr(path, '/');
    size_t dl = slash ? (size_t)(slash - path + 1) : 0;
    if (dl >= sizeof p.dir)
        return err_set(e, "%s: path too long", qpath);
    memcpy(p.dir, path, dl);
    p.dir[dl] = '\0';
    char *text;
    size_t len;
    int err_no = file_read(path, FILE_MAX_TEXT, &text, &len);
    if (err_no)
        return err_set(e, "%s: cannot open scene: %s", qpath, file_strerror(err_no));
    char(*names)[MAX_PATH] = calloc(SCENE_MAX_ITEMS, MAX_PATH); /* resolved OBJ path per mesh */
    if (!names) {
        free(text);
        return err_set(e, "out of memory");
    }
    int rc = 0;
    for (char *line = (char *)lex_skip_bom(text, text + len), *end = text + len;
         rc == 0 && line < end;) {
        char *eol = (char *)lex_line_end(line, end);
        p.line++;
        if (memchr(line, '\0', (size_t)(eol - line))) {
            rc = perr(&p, "binary data in scene file", NULL);
            break;
        }
        *eol = '\0'; /* the buffer is ours: lines become C strings in place */
        if (tokenize(&p, line)) {
            rc = -1;
            break;
        }
        if (p.n)
            rc = statement(&p, s, names);
        line = eol + 1;
    }
    free(text);
    free(names);
    if (rc == 0 && p.procedural_sky_line) {
        p.line = p.procedural_sky_line;
        vec3 sun = s->n_lights ? s->lights[0].dir : v3(1, 1, 1);
        if (skybox_procedural(&s->sky, sun, e))
            rc = prefix_err(&p);
    }
    if (rc == 0 && s->n_items == 0)
        rc = err_set(e, "%s: no model statements: nothing to draw", qpath);
    if (rc) {
        scene_free(s);
        return -1;
    }
    update_bounds(s);
    return 0;
}

int scene_load_file(const char *path, struct scene *s, struct err *e)
{
    return load_file(path, NULL, s, e);
}

int scene_load_with(const char *path, const struct model_opts *opts, struct scene *s,
                    struct err *e)
{
    size_t n = strlen(path);
    if (n > 4 && strcmp(path + n - 4, ".rsc") == 0)
        return load_file(path, opts, s, e);
    return load_model(path, opts, s, e);
}

int scene_load(const char *path, struct scene *s, struct err *e)
{
    return scene_load_with(path, NULL, s, e);
}

/* the build ended, the meshes share their hierarchies' arrays (dag_settle), and what they
 * held goes back to the system: glibc keeps freed heap pages (the viewer's 1M sphere under
 * clusters: 258 MB resident without the trim, 217 with it) */
static void settle_meshes(struct scene *s)
{
    lod_finish(s->lod_job, false); /* (waits for the builder, or joins the finished one:
                                      nothing else reads the meshes then) */
    s->lod_job = NULL;
    bool any = false;
    for (int i = 0; i < s->n_meshes; i++) {
        const struct mesh_dag *d = s->meshes[i].dag;
        dag_settle(&s->meshes[i]);
        any |= d && (d->shared & ~DAG_SETTLED) != 0;
    }
#ifdef __GLIBC__
    if (any)
        malloc_trim(0);
#else
    (void)any;
#endif
}

int scene_build_lod(struct scene *s, bool wait, bool clusters, struct err *e)
{
    if (s->lod_job)
        return 0;
    if (lod_start(s->meshes, s->n_meshes, clusters, &s->lod_job, e))
        return -1;
    if (wait)
        settle_meshes(s);
    return 0;
}

void scene_lod_settle(struct scene *s)
{
    if (s->lod_job && lod_done(s->lod_job))
        settle_meshes(s);
}

int scene_build_clusters(struct scene *s, struct err *e)
{
    for (int i = 0; i < s->n_meshes; i++)
        if (!s->meshes[i].clusters && cluster_build(&s->meshes[i]))
            return err_set(e, "out of memory for the clusters of %u triangles",
                           (unsigned)s->meshes[i].n_tris);
    return 0;
}

bool scene_lod_done(const struct scene *s)
{
    return lod_done(s->lod_job);
}

void scene_free(struct scene *s)
{
    lod_finish(s->lod_job, true); /* before the meshes it builds levels for */
    for (int i = 0; i < SCENE_MAX_ITEMS; i++) {
        lod_free(&s->meshes[i]);
        mesh_free(&s->meshes[i]);
    }
    texture_cache_free(&s->textures); /* after the meshes: they borrow from it */
    skybox_free(&s->sky);
    memset(s, 0, sizeof *s);
}
