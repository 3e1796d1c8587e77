/* draco.c: Draco meshes through the decoder in a child process (see draco.h), and raw .drc
 * files as a model format. */
#include "draco.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "file.h"
#include "model.h"
#include "mtl.h"
#include "sandbox.h"

/* draco_shim.cc */
int draco_shim_decode(const uint8_t *data, size_t len, const int ids[DRACO_ATTR_COUNT],
                      struct draco_mesh *out, char msg[200]);

int draco_is(const void *data, size_t len)
{
    return len >= 5 && memcmp(data, "DRACO", 5) == 0;
}

void draco_mesh_free(struct draco_mesh *m)
{
    free(m->faces);
    for (int a = 0; a < DRACO_ATTR_COUNT; a++)
        free(m->attr[a]);
    memset(m, 0, sizeof *m);
}

struct job {
    const uint8_t *data;
    size_t len;
    const int *ids;
};

/* the child: decode, then the reply: n_points, n_faces, comps[], faces, each attribute */
static int job(void *arg, struct sandbox_blob *r, char msg[220])
{
    const struct job *j = arg;
    struct draco_mesh m;
    char why[200] = "";
    if (draco_shim_decode(j->data, j->len, j->ids, &m, why)) {
        snprintf(msg, 220, "%s", why);
        draco_mesh_free(&m);
        return -1;
    }
    sandbox_put_u32(r, m.n_points);
    sandbox_put_u32(r, m.n_faces);
    for (int a = 0; a < DRACO_ATTR_COUNT; a++)
        sandbox_put_u32(r, m.attr[a] ? (uint32_t)m.comps[a] : 0);
    sandbox_put(r, m.faces, (size_t)m.n_faces * 12);
    for (int a = 0; a < DRACO_ATTR_COUNT; a++)
        if (m.attr[a])
            sandbox_put(r, m.attr[a], (size_t)m.n_points * (size_t)m.comps[a] * 4);
    draco_mesh_free(&m);
    return 0;
}

int draco_decode(const uint8_t *data, size_t len, const int ids[DRACO_ATTR_COUNT],
                 struct draco_mesh *out, struct err *e)
{
    memset(out, 0, sizeof *out);
    struct job j = {data, len, ids};
    uint8_t *reply;
    size_t n;
    struct err se;
    if (sandbox_run(job, &j, "Draco", "Draco decoder", &reply, &n, &se)) {
        /* (sandbox_run names the job; the caller names the file) */
        const char *why = strncmp(se.msg, "Draco: ", 7) == 0 ? se.msg + 7 : se.msg;
        return err_set(e, "%s", why);
    }
    size_t at = 0;
    uint32_t head[2 + DRACO_ATTR_COUNT];
    int rc = -1;
    if (n < sizeof head)
        goto bad;
    memcpy(head, reply, sizeof head);
    at = sizeof head;
    out->n_points = head[0];
    out->n_faces = head[1];
    if ((uint64_t)out->n_faces * 12 > n - at)
        goto bad;
    out->faces = malloc((size_t)out->n_faces * 12 + 1);
    if (!out->faces)
        goto oom;
    memcpy(out->faces, reply + at, (size_t)out->n_faces * 12);
    at += (size_t)out->n_faces * 12;
    for (int a = 0; a < DRACO_ATTR_COUNT; a++) {
        uint32_t c = head[2 + a];
        if (!c)
            continue;
        if (c > 16 || (uint64_t)out->n_points * c * 4 > n - at)
            goto bad;
        size_t bytes = (size_t)out->n_points * c * 4;
        if (!(out->attr[a] = malloc(bytes + 1)))
            goto oom;
        memcpy(out->attr[a], reply + at, bytes);
        out->comps[a] = (int)c;
        at += bytes;
        for (size_t k = 0; k < bytes / 4; k++)
            if (!isfinite(out->attr[a][k]))
                out->attr[a][k] = 0;
    }
    for (size_t k = 0; k < (size_t)out->n_faces * 3; k++)
        if (out->faces[k] >= out->n_points) {
            rc = err_set(e, "a Draco face names point %u of %u", out->faces[k], out->n_points);
            goto done;
        }
    rc = 0;
    goto done;
bad:
    rc = err_set(e, "a bad reply from the Draco decoder");
    goto done;
oom:
    rc = err_set(e, "out of memory");
done:
    free(reply);
    if (rc)
        draco_mesh_free(out);
    return rc;
}

int draco_read(const char *data, size_t len, const struct model_ctx *ctx, struct mesh *out,
               struct err *e)
{
    memset(out, 0, sizeof *out);
    char where[FILE_QUOTE_SIZE];
    file_quote(ctx->path ? ctx->path : "<memory>", where, sizeof where);
    int ids[DRACO_ATTR_COUNT];
    for (int a = 0; a < DRACO_ATTR_COUNT; a++)
        ids[a] = a <= DRACO_COLOR ? DRACO_BY_KIND : -1;
    struct draco_mesh dm;
    struct err de;
    if (draco_decode((const uint8_t *)data, len, ids, &dm, &de))
        return err_set(e, "%s: %s", where, de.msg);
    int rc = -1;
    struct mesh_corner *corners = malloc((size_t)dm.n_faces * 3 * sizeof *corners);
    uint8_t *rgba = NULL;
    out->materials = malloc(sizeof *out->materials);
    if (!corners || !out->materials) {
        err_set(e, "%s: out of memory", where);
        goto done;
    }
    bool nrm = dm.attr[DRACO_NORMAL] && dm.comps[DRACO_NORMAL] == 3;
    bool uv = dm.attr[DRACO_UV0] && dm.comps[DRACO_UV0] == 2;
    for (size_t k = 0; k < (size_t)dm.n_faces * 3; k++) {
        uint32_t p = dm.faces[k];
        corners[k] = (struct mesh_corner){p, uv ? p : MESH_NONE, nrm ? p : MESH_NONE};
    }
    int cc = dm.comps[DRACO_COLOR];
    if (dm.attr[DRACO_COLOR] && (cc == 3 || cc == 4)) { /* display values, as PLY's */
        rgba = malloc((size_t)dm.n_points * 4);
        if (!rgba) {
            err_set(e, "%s: out of memory", where);
            goto done;
        }
        float mx = 0;
        for (size_t k = 0; k < (size_t)dm.n_points * cc; k++)
            mx = dm.attr[DRACO_COLOR][k] > mx ? dm.attr[DRACO_COLOR][k] : mx;
        float s = mx > 1.0001f ? (mx > 255.5f ? 255.0f / 65535 : 1) : 255;
        for (size_t p = 0; p < dm.n_points; p++)
            for (int c = 0; c < 4; c++) {
                float v = c < cc ? dm.attr[DRACO_COLOR][p * cc + c] * s : 255;
                rgba[p * 4 + c] = (uint8_t)(v < 0 ? 0 : v > 255 ? 255 : v + 0.5f);
            }
    }
    mtl_default(&out->materials[0], "default");
    out->materials[0].implicit = true;
    out->n_materials = 1;
    struct mesh_source src = {.pos = dm.attr[DRACO_POSITION], .n_pos = dm.n_points,
                              .nrm = nrm ? dm.attr[DRACO_NORMAL] : NULL,
                              .n_nrm = nrm ? dm.n_points : 0,
                              .uv = uv ? dm.attr[DRACO_UV0] : NULL, .n_uv = uv ? dm.n_points : 0,
                              .rgba = rgba, .corners = corners, .n_tris = dm.n_faces};
    src.crease_set = true;
    src.crease_deg = model_opts_of(ctx)->crease_set ? model_opts_of(ctx)->crease_deg
                                                    : MESH_CREASE_DEFAULT;
    struct err be;
    if (mesh_build(&src, out, &be)) {
        err_set(e, "%s: %s", where, be.msg);
        goto done;
    }
    rc = 0;
done:
    free(corners);
    free(rgba);
    draco_mesh_free(&dm);
    if (rc)
        mesh_free(out);
    return rc;
}
