/* import.c: FBX, COLLADA, 3DS and the other formats assimp reads, as a loader behind
 * model.h (glTF has rastty's own reader, gltf.c: assimp's C API could not give its
 * materials, samplers, extensions and cameras).
 *
 * Why assimp (Debian's libassimp-dev): a dozen formats people download, maintained and
 * fuzzed upstream. OBJ, STL, PLY and glTF stay on rastty's own parsers (verified against
 * the oracle, with file:line or byte-offset errors).
 *
 * Isolation: assimp is a large C++ library and malformed files have crashed it before. It
 * runs in a child process with limits (sandbox.h: CPU time, address space, no terminal)
 * that sends the flattened mesh back through a pipe. A crash, a hang or an allocation
 * storm in the importer becomes one error line ("x.dae: the importer crashed on this file
 * (killed by signal 11)"), never a dead viewer or a full machine; assimp's own messages
 * are quoted after the file name. Files the model names are opened through the same rules
 * as everything else (file.h: regular files only, with size limits); a model read from
 * memory may name none.
 *
 * What is used: triangles (points and lines dropped), positions, normals when given (else
 * creased ones, mesh.h), the first uv channel, every node's transform (meshes placed by
 * their node chain, instanced as often as nodes name them; a mirroring transform keeps
 * normals outward and reverses the winding), FBX's axis settings, per material the base
 * colour factor or diffuse colour as Kd and the base colour / diffuse texture (a file
 * beside the model or in a textures/ folder there, or an image embedded in it) through
 * material.h. Cameras, lights, animations and skins are not drawn: each is a warning naming
 * how many the file has. uv: assimp flips v so
 * that v = 0 is the bottom row, as in OBJ. */
#include <errno.h>
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <assimp/cfileio.h>
#include <assimp/cimport.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include "file.h"
#include "import.h"
#include "material.h"
#include "model.h"
#include "mtl.h"
#include "sandbox.h"

#define IMPORT_MAX_TRIS 50000000u   /* after instancing */
#define IMPORT_MAX_DEPTH 256        /* node nesting */
#define IMPORT_MAX_MATERIALS 65535


/* ---- the flattened result (what crosses the pipe: sandbox.h's reply) ---- */

#define put sandbox_put
#define put_u32 sandbox_put_u32

/* ---- in the child: assimp with our file rules ---- */

struct io_file {
    char *data;
    size_t len, pos;
};

struct io_ctx {
    const char *main_name; /* served from main_data */
    const char *main_data;
    size_t main_len;
    bool others; /* may other files be opened? */
};

static size_t io_read(struct aiFile *f, char *buf, size_t size, size_t count)
{
    struct io_file *h = (struct io_file *)f->UserData;
    if (size == 0)
        return 0;
    size_t n = count, left = h->len - h->pos;
    if (n > left / size)
        n = left / size;
    memcpy(buf, h->data + h->pos, n * size);
    h->pos += n * size;
    return n;
}

static size_t io_write(struct aiFile *f, const char *buf, size_t size, size_t count)
{
    (void)f, (void)buf, (void)size, (void)count;
    return 0;
}

static size_t io_tell(struct aiFile *f)
{
    return ((struct io_file *)f->UserData)->pos;
}

static size_t io_size(struct aiFile *f)
{
    return ((struct io_file *)f->UserData)->len;
}

static enum aiReturn io_seek(struct aiFile *f, size_t off, enum aiOrigin how)
{
    struct io_file *h = (struct io_file *)f->UserData;
    size_t base = how == aiOrigin_SET ? 0 : how == aiOrigin_CUR ? h->pos : h->len;
    if (off > h->len || base > h->len - off)
        return aiReturn_FAILURE;
    h->pos = base + off;
    return aiReturn_SUCCESS;
}

static void io_flush(struct aiFile *f)
{
    (void)f;
}

static struct aiFile *io_open(struct aiFileIO *io, const char *name, const char *mode)
{
    struct io_ctx *c = (struct io_ctx *)io->UserData;
    if (!mode || strchr(mode, 'w') || strchr(mode, 'a'))
        return NULL; /* importers only read */
    struct io_file *h = calloc(1, sizeof *h);
    struct aiFile *f = calloc(1, sizeof *f);
    if (!h || !f)
        goto fail;
    if (strcmp(name, c->main_name) == 0) {
        if (!(h->data = malloc(c->main_len + 1)))
            goto fail;
        memcpy(h->data, c->main_data, c->main_len);
        h->len = c->main_len;
    } else if (!c->others || file_read(name, FILE_MAX_MODEL, &h->data, &h->len) != 0) {
        goto fail;
    }
    f->ReadProc = io_read;
    f->WriteProc = io_write;
    f->TellProc = io_tell;
    f->FileSizeProc = io_size;
    f->SeekProc = io_seek;
    f->FlushProc = io_flush;
    f->UserData = (aiUserData)h;
    return f;
fail:
    if (h)
        free(h->data);
    free(h);
    free(f);
    return NULL;
}

static void io_close(struct aiFileIO *io, struct aiFile *f)
{
    (void)io;
    struct io_file *h = (struct io_file *)f->UserData;
    free(h->data);
    free(h);
    free(f);
}

struct walk {
    const struct aiScene *sc;
    struct sandbox_blob pos, nrm, uv, corners, mats;
    uint32_t n_pos, n_tris;
    bool any_nrm, any_uv, too_big;
    unsigned long visits;
};

typedef struct {
    double m[4][4];
} m44;

static m44 m44_mul(const m44 *a, const struct aiMatrix4x4 *b)
{
    const double bb[4][4] = {{b->a1, b->a2, b->a3, b->a4},
                             {b->b1, b->b2, b->b3, b->b4},
                             {b->c1, b->c2, b->c3, b->c4},
                             {b->d1, b->d2, b->d3, b->d4}};
    m44 r;
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) {
            double s = 0;
            for (int k = 0; k < 4; k++)
                s += a->m[i][k] * bb[k][j];
            r.m[i][j] = s;
        }
    return r;
}

/* inverse transpose of the upper 3x3 (for normals; scale does not matter, mesh_build
 * normalises) */
static void normal_matrix(const m44 *a, double n[3][3])
{
    const double(*m)[4] = a->m;
    n[0][0] = m[1][1] * m[2][2] - m[1][2] * m[2][1];
    n[0][1] = m[1][2] * m[2][0] - m[1][0] * m[2][2];
    n[0][2] = m[1][0] * m[2][1] - m[1][1] * m[2][0];
    n[1][0] = m[0][2] * m[2][1] - m[0][1] * m[2][2];
    n[1][1] = m[0][0] * m[2][2] - m[0][2] * m[2][0];
    n[1][2] = m[0][1] * m[2][0] - m[0][0] * m[2][1];
    n[2][0] = m[0][1] * m[1][2] - m[0][2] * m[1][1];
    n[2][1] = m[0][2] * m[1][0] - m[0][0] * m[1][2];
    n[2][2] = m[0][0] * m[1][1] - m[0][1] * m[1][0];
}

static int finite3(const float *v)
{
    return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
}

/* the determinant of the upper 3x3: negative for a mirroring transform */
static double det3(const m44 *a)
{
    const double(*m)[4] = a->m;
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

static void add_mesh(struct walk *W, const struct aiMesh *am, const m44 *xf)
{
    if (!(am->mPrimitiveTypes & aiPrimitiveType_TRIANGLE) || !am->mVertices ||
        am->mNumVertices == 0)
        return;
    uint32_t nf = 0;
    for (unsigned i = 0; i < am->mNumFaces; i++)
        nf += am->mFaces[i].mNumIndices == 3;
    if ((uint64_t)W->n_tris + nf > IMPORT_MAX_TRIS ||
        (uint64_t)W->n_pos + am->mNumVertices > IMPORT_MAX_TRIS) {
        W->too_big = true;
        return;
    }
    double nm[3][3];
    normal_matrix(xf, nm); /* det(M) (M^-1)^T: under a mirror it points the normals inward */
    const bool mirrored = det3(xf) < 0;
    if (mirrored)
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++)
                nm[r][c] = -nm[r][c];
    const struct aiVector3D *uvs = am->mTextureCoords[0];
    uint32_t base = W->n_pos;
    for (unsigned i = 0; i < am->mNumVertices; i++) {
        const struct aiVector3D *v = &am->mVertices[i];
        float p[3], n[3] = {0, 0, 0}, t[2] = {0, 0};
        for (int k = 0; k < 3; k++)
            p[k] = (float)(xf->m[k][0] * v->x + xf->m[k][1] * v->y + xf->m[k][2] * v->z +
                           xf->m[k][3]);
        if (!finite3(p))
            p[0] = p[1] = p[2] = 0;
        if (am->mNormals) {
            const struct aiVector3D *a = &am->mNormals[i];
            for (int k = 0; k < 3; k++)
                n[k] = (float)(nm[k][0] * a->x + nm[k][1] * a->y + nm[k][2] * a->z);
            if (!finite3(n))
                n[0] = n[1] = n[2] = 0;
        }
        if (uvs) {
            t[0] = isfinite(uvs[i].x) ? uvs[i].x : 0;
            t[1] = isfinite(uvs[i].y) ? uvs[i].y : 0;
        }
        put(&W->pos, p, sizeof p);
        put(&W->nrm, n, sizeof n);
        put(&W->uv, t, sizeof t);
    }
    W->n_pos += am->mNumVertices;
    W->any_nrm |= am->mNormals != NULL;
    W->any_uv |= uvs != NULL;
    uint32_t mat = am->mMaterialIndex < W->sc->mNumMaterials &&
                           am->mMaterialIndex < IMPORT_MAX_MATERIALS
                       ? am->mMaterialIndex + 1 /* 0 = the default material */
                       : 0;
    for (unsigned i = 0; i < am->mNumFaces; i++) {
        const struct aiFace *f = &am->mFaces[i];
        if (f->mNumIndices != 3)
            continue;
        bool ok = true;
        for (int k = 0; k < 3; k++)
            ok &= f->mIndices[k] < am->mNumVertices;
        if (!ok)
            continue;
        for (int k = 0; k < 3; k++) { /* a mirror turns the winding: the corners back */
            uint32_t v = base + f->mIndices[mirrored && k ? 3 - k : k];
            uint32_t c[3] = {v, uvs ? v : MESH_NONE, am->mNormals ? v : MESH_NONE};
            put(&W->corners, c, sizeof c);
        }
        put_u32(&W->mats, mat);
        W->n_tris++;
    }
}

static void walk_node(struct walk *W, const struct aiNode *node, m44 xf, int depth)
{
    if (!node || depth > IMPORT_MAX_DEPTH || W->too_big || ++W->visits > 10000000)
        return;
    xf = m44_mul(&xf, &node->mTransformation);
    for (unsigned i = 0; i < node->mNumMeshes; i++)
        if (node->mMeshes[i] < W->sc->mNumMeshes)
            add_mesh(W, W->sc->mMeshes[node->mMeshes[i]], &xf);
    for (unsigned i = 0; i < node->mNumChildren; i++)
        walk_node(W, node->mChildren[i], xf, depth + 1);
}

/* an int32 entry of the scene's metadata; 0 when it has none */
static int meta_int(const struct aiScene *sc, const char *key, int32_t *out)
{
    const struct aiMetadata *md = sc->mMetaData;
    for (unsigned i = 0; md && i < md->mNumProperties; i++)
        if (md->mKeys[i].length == strlen(key) && memcmp(md->mKeys[i].data, key, md->mKeys[i].length) == 0 &&
            md->mValues[i].mType == AI_INT32 && md->mValues[i].mData) {
            memcpy(out, md->mValues[i].mData, sizeof *out);
            return 1;
        }
    return 0;
}

/* FBX's axis settings (assimp keeps them as metadata and leaves the coordinates as the
 * file has them): the file's right, up and front axes with their signs become x, y and z.
 * Maya's Y-up (up 1, front 2, coord 0) is the identity, 3ds Max's Z-up (up 2, front 1 with
 * sign -1) turns (x, y, z) to (x, z, -y), as mesh_turn_up does for STL. COLLADA's up_axis
 * assimp applies itself. */
static void file_axes(const struct aiScene *sc, m44 *xf)
{
    int32_t up, up_s, front, front_s, coord, coord_s;
    if (!meta_int(sc, "UpAxis", &up) || !meta_int(sc, "UpAxisSign", &up_s) ||
        !meta_int(sc, "FrontAxis", &front) || !meta_int(sc, "FrontAxisSign", &front_s) ||
        !meta_int(sc, "CoordAxis", &coord) || !meta_int(sc, "CoordAxisSign", &coord_s))
        return;
    if (up < 0 || up > 2 || front < 0 || front > 2 || coord < 0 || coord > 2 || up == front ||
        up == coord || front == coord)
        return;
    m44 m = {{{0}}};
    m.m[0][coord] = coord_s < 0 ? -1 : 1;
    m.m[1][up] = up_s < 0 ? -1 : 1;
    m.m[2][front] = front_s < 0 ? -1 : 1;
    m.m[3][3] = 1;
    if (det3(&m) < 0) /* FBX's front sign is "parity": keep the basis right-handed */
        m.m[2][front] = -m.m[2][front];
    *xf = m;
}

/* materials: kd, then a texture reference: 0 none, 1 file (path follows), 2 embedded
 * (compressed bytes follow) */
static void put_materials(struct sandbox_blob *b, const struct aiScene *sc)
{
    uint32_t n = sc->mNumMaterials < IMPORT_MAX_MATERIALS ? sc->mNumMaterials
                                                            : IMPORT_MAX_MATERIALS;
    put_u32(b, n);
    for (uint32_t i = 0; i < n; i++) {
        const struct aiMaterial *m = sc->mMaterials[i];
        struct aiColor4D c = {1, 1, 1, 1};
        if (aiGetMaterialColor(m, AI_MATKEY_BASE_COLOR, &c) != aiReturn_SUCCESS &&
            aiGetMaterialColor(m, AI_MATKEY_COLOR_DIFFUSE, &c) != aiReturn_SUCCESS)
            c = (struct aiColor4D){1, 1, 1, 1};
        float kd[3] = {c.r, c.g, c.b};
        for (int k = 0; k < 3; k++)
            kd[k] = isfinite(kd[k]) ? (kd[k] < 0 ? 0 : kd[k] > 1 ? 1 : kd[k]) : 1;
        put(b, kd, sizeof kd);
        struct aiString path;
        path.length = 0;
        if (aiGetMaterialTexture(m, aiTextureType_BASE_COLOR, 0, &path, NULL, NULL, NULL, NULL,
                                 NULL, NULL) != aiReturn_SUCCESS &&
            aiGetMaterialTexture(m, aiTextureType_DIFFUSE, 0, &path, NULL, NULL, NULL, NULL,
                                 NULL, NULL) != aiReturn_SUCCESS)
            path.length = 0;
        size_t len = path.length < MAXLEN ? path.length : 0;
        if (len == 0) {
            put_u32(b, 0);
            continue;
        }
        const struct aiTexture *t = NULL;
        if (path.data[0] == '*') {
            long k = strtol(path.data + 1, NULL, 10);
            if (k >= 0 && (unsigned long)k < sc->mNumTextures)
                t = sc->mTextures[k];
        }
        if (t && t->mHeight == 0 && t->pcData && t->mWidth > 0) { /* compressed image */
            put_u32(b, 2);
            put_u32(b, t->mWidth);
            put(b, t->pcData, t->mWidth);
        } else if (!t && path.data[0] != '*') {
            put_u32(b, 1);
            put_u32(b, (uint32_t)len);
            put(b, path.data, len);
        } else {
            put_u32(b, 0); /* uncompressed embedded texels: rare, not supported */
        }
    }
}

int import_flatten(const char *data, size_t len, const char *name, bool others,
                   struct import_result *r)
{
    memset(r, 0, sizeof *r);
    struct io_ctx ioc = {name, data, len, others};
    struct aiFileIO io = {io_open, io_close, (aiUserData)&ioc};
    struct aiPropertyStore *props = aiCreatePropertyStore();
    aiSetImportPropertyInteger(props, AI_CONFIG_PP_SBP_REMOVE,
                               aiPrimitiveType_POINT | aiPrimitiveType_LINE);
    /* a file without surfaces gets no stand-in: assimp's COLLADA and ASE readers (and
     * others) would build pyramids of its node tree, 8 degenerate triangles for one node,
     * and 'empty.dae' read as 'none of its 8 triangles has an area' */
    aiSetImportPropertyInteger(props, AI_CONFIG_IMPORT_NO_SKELETON_MESHES, 1);
    const struct aiScene *sc = aiImportFileExWithProperties(
        name,
        aiProcess_Triangulate | aiProcess_SortByPType | aiProcess_ValidateDataStructure,
        &io, props);
    aiReleasePropertyStore(props);
    if (!sc) {
        const char *why = aiGetErrorString();
        err_quote(why ? why : "unknown error", why ? strlen(why) : 13, 200, r->msg,
                  sizeof r->msg);
        return -1;
    }
    struct walk W = {.sc = sc};
    m44 id = {{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}};
    file_axes(sc, &id);
    walk_node(&W, sc->mRootNode, id, 0);
    struct sandbox_blob mats = {0};
    put_materials(&mats, sc);
    /* what the file has that is not drawn: animations, cameras, lights, skinned meshes */
    uint32_t skinned = 0;
    for (uint32_t i = 0; i < sc->mNumMeshes; i++)
        skinned += sc->mMeshes[i] && sc->mMeshes[i]->mNumBones > 0;
    uint32_t ignored[4] = {sc->mNumAnimations, sc->mNumCameras, sc->mNumLights, skinned};
    put(&mats, ignored, sizeof ignored);
    aiReleaseImport(sc);
    int rc = 0;
    if (W.too_big) {
        snprintf(r->msg, sizeof r->msg, "more than %u triangles or vertices after instancing",
                 IMPORT_MAX_TRIS);
        rc = -1;
    } else if (W.pos.failed || W.nrm.failed || W.uv.failed || W.corners.failed ||
               W.mats.failed || mats.failed) {
        snprintf(r->msg, sizeof r->msg, "out of memory");
        rc = -1;
    }
    /* one reply: counts, then the arrays */
    struct sandbox_blob *out = &r->reply;
    uint32_t head[4] = {W.n_pos, W.n_tris, W.any_nrm, W.any_uv};
    if (rc == 0) {
        put(out, head, sizeof head);
        put(out, W.pos.p, W.pos.n);
        put(out, W.nrm.p, W.nrm.n);
        put(out, W.uv.p, W.uv.n);
        put(out, W.corners.p, W.corners.n);
        put(out, W.mats.p, W.mats.n);
        put(out, mats.p, mats.n);
        if (out->failed) {
            snprintf(r->msg, sizeof r->msg, "out of memory");
            rc = -1;
        }
    }
    free(W.pos.p);
    free(W.nrm.p);
    free(W.uv.p);
    free(W.corners.p);
    free(W.mats.p);
    free(mats.p);
    return rc;
}

void import_result_free(struct import_result *r)
{
    free(r->reply.p);
    memset(r, 0, sizeof *r);
}

/* ---- in the parent: the reply back into a mesh ---- */

struct reader {
    const uint8_t *p, *end;
    bool bad;
};

static const void *take(struct reader *R, size_t n)
{
    if (R->bad || (size_t)(R->end - R->p) < n) {
        R->bad = true;
        return NULL;
    }
    const void *at = R->p;
    R->p += n;
    return at;
}

static uint32_t take_u32(struct reader *R)
{
    const void *p = take(R, 4);
    uint32_t v = 0;
    if (p)
        memcpy(&v, p, 4);
    return v;
}

int import_build(const uint8_t *reply, size_t n, const struct model_ctx *ctx,
                 const char *where, struct mesh *out, struct err *e)
{
    struct reader R = {reply, reply + n, false};
    uint32_t n_pos = take_u32(&R), n_tris = take_u32(&R);
    bool any_nrm = take_u32(&R) != 0, any_uv = take_u32(&R) != 0;
    if (R.bad || (size_t)n_pos > n / 12 || (size_t)n_tris > n / 36)
        return err_set(e, "%s: bad reply from the importer", where);
    if (n_tris == 0)
        return err_set(e, "%s: no triangles (the file has no surfaces rastty can draw)", where);
    const float *pos = take(&R, (size_t)n_pos * 12);
    const float *nrm = take(&R, (size_t)n_pos * 12);
    const float *uv = take(&R, (size_t)n_pos * 8);
    const struct mesh_corner *corners = take(&R, (size_t)n_tris * 36);
    const uint32_t *tmat = take(&R, (size_t)n_tris * 4);
    uint32_t n_mats = take_u32(&R);
    if (R.bad || n_mats > IMPORT_MAX_MATERIALS)
        return err_set(e, "%s: bad reply from the importer", where);
    out->materials = calloc((size_t)n_mats + 1, sizeof *out->materials);
    uint16_t *tri_material = malloc((size_t)n_tris * sizeof *tri_material);
    /* copies: the reply is not aligned for floats in general */
    float *apos = malloc((size_t)n_pos * 12 + 1), *anrm = malloc((size_t)n_pos * 12 + 1);
    float *auv = malloc((size_t)n_pos * 8 + 1);
    struct mesh_corner *ac = malloc((size_t)n_tris * 36);
    int rc = -1;
    if (!out->materials || !tri_material || !apos || !anrm || !auv || !ac) {
        err_set(e, "%s: out of memory", where);
        goto done;
    }
    memcpy(apos, pos, (size_t)n_pos * 12);
    memcpy(anrm, nrm, (size_t)n_pos * 12);
    memcpy(auv, uv, (size_t)n_pos * 8);
    memcpy(ac, corners, (size_t)n_tris * 36);
    /* a file the importer took for its format without being one (random bytes named .ase
     * give 8 triangles all at the origin): no triangle with an area is no model */
    bool any_area = false;
    for (uint32_t t = 0; t < n_tris && !any_area; t++) {
        const struct mesh_corner *c = &ac[3 * t];
        if (c[0].pos >= n_pos || c[1].pos >= n_pos || c[2].pos >= n_pos)
            continue;
        const float *a = apos + 3 * c[0].pos, *b = apos + 3 * c[1].pos, *d = apos + 3 * c[2].pos;
        float u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
        float v[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
        float x = u[1] * v[2] - u[2] * v[1], y = u[2] * v[0] - u[0] * v[2],
              z = u[0] * v[1] - u[1] * v[0];
        any_area = x != 0 || y != 0 || z != 0;
    }
    if (!any_area) {
        err_set(e, "%s: none of its %u triangles has an area: not a model the importer could "
                   "read",
                where, n_tris);
        goto done;
    }
    for (uint32_t t = 0; t < n_tris; t++) {
        uint32_t m;
        memcpy(&m, &tmat[t], 4);
        tri_material[t] = (uint16_t)(m <= n_mats ? m : 0);
    }
    mtl_default(&out->materials[0], "default");
    out->materials[0].implicit = true; /* meshes without a material */
    out->n_materials = n_mats + 1;
    /* material i+1: kd and a texture reference (kept until textures are loaded) */
    struct texref {
        uint32_t kind, len;
        const uint8_t *p;
    } *refs = calloc((size_t)n_mats + 1, sizeof *refs);
    if (!refs) {
        err_set(e, "%s: out of memory", where);
        goto done;
    }
    for (uint32_t i = 1; i <= n_mats; i++) {
        struct material *m = &out->materials[i];
        char name[32];
        snprintf(name, sizeof name, "material%u", i - 1);
        mtl_default(m, name);
        const float *kd = take(&R, 12);
        if (kd)
            memcpy(m->kd, kd, 12);
        refs[i].kind = take_u32(&R);
        if (refs[i].kind == 1 || refs[i].kind == 2) {
            refs[i].len = take_u32(&R);
            refs[i].p = take(&R, refs[i].len);
        }
        for (int k = 0; k < 3; k++)
            if (!(m->kd[k] >= 0 && m->kd[k] <= 1))
                m->kd[k] = 1;
    }
    uint32_t ign[4];
    for (int k = 0; k < 4; k++)
        ign[k] = take_u32(&R);
    if (R.bad) {
        free(refs);
        err_set(e, "%s: bad reply from the importer", where);
        goto done;
    }
    /* what changes the picture and is not drawn: said, once each */
    static const char *const ign_what[4] = {
        "animations are not played: drawn in the file's rest pose",
        "cameras are ignored: rastty frames the model itself",
        "lights are ignored: drawn in rastty's light",
        "skinned meshes are drawn in their bind pose (skins are not applied)"};
    for (int k = 0; k < 4; k++)
        if (ign[k])
            warn_add(ctx->warn, "%s: %u %s", where, ign[k], ign_what[k]);
    struct mesh_source src = {.pos = apos, .nrm = any_nrm ? anrm : NULL,
                              .uv = any_uv ? auv : NULL, .n_pos = n_pos,
                              .n_nrm = any_nrm ? n_pos : 0, .n_uv = any_uv ? n_pos : 0,
                              .corners = ac, .tri_material = tri_material, .n_tris = n_tris};
    src.crease_set = true;
    src.crease_deg = model_opts_of(ctx)->crease_set ? model_opts_of(ctx)->crease_deg : MESH_CREASE_DEFAULT;
    for (size_t i = 0; i < (size_t)n_tris * 3; i++) {
        if (!any_nrm)
            ac[i].nrm = MESH_NONE;
        if (!any_uv)
            ac[i].uv = MESH_NONE;
    }
    struct err be;
    if (mesh_build(&src, out, &be)) {
        free(refs);
        err_set(e, "%s: %s", where, be.msg);
        goto done;
    }
    if (material_reserve_textures(out, e)) {
        free(refs);
        goto done;
    }
    rc = 0;
    for (uint32_t i = 1; i <= n_mats && rc == 0; i++) {
        if (refs[i].kind == 1 && ctx->path && !memchr(refs[i].p, '\0', refs[i].len)) {
            char *path = material_path_beside(ctx->path, (const char *)refs[i].p, refs[i].len);
            /* glTF URIs escape spaces and the like as %20: undo the common case */
            if (path)
                for (char *c = path; (c = strstr(c, "%20"));)
                    memmove(c + 1, c + 3, strlen(c + 3) + 1), *c = ' ';
            rc = path ? material_texture_file(out, i, path, where, 0, ctx, e)
                      : err_set(e, "%s: out of memory", where);
            free(path);
        } else if (refs[i].kind == 2) {
            char name[FILE_QUOTE_SIZE + 32];
            snprintf(name, sizeof name, "%s: embedded image %u", where, i - 1);
            rc = material_texture_bytes(out, i, refs[i].p, refs[i].len, name, ctx, e);
        }
    }
    free(refs);
done:
    free(tri_material);
    free(apos);
    free(anrm);
    free(auv);
    free(ac);
    return rc;
}

/* ---- the child process (sandbox.h) ---- */

struct import_job {
    const char *data;
    size_t len;
    const char *name;
    bool others;
};

static int import_job(void *arg, struct sandbox_blob *reply, char msg[220])
{
    const struct import_job *j = arg;
    struct import_result r;
    if (import_flatten(j->data, j->len, j->name, j->others, &r)) {
        snprintf(msg, 220, "%s", r.msg);
        import_result_free(&r);
        return -1;
    }
    *reply = r.reply;
    return 0;
}

static uint32_t le32(const char *p)
{
    const uint8_t *u = (const uint8_t *)p;
    return (uint32_t)u[0] | (uint32_t)u[1] << 8 | (uint32_t)u[2] << 16 | (uint32_t)u[3] << 24;
}

/* A GLB's header and chunk lengths must agree with the file: assimp would otherwise
 * allocate what a 20-byte file claims (2 GB). */
static int check_glb(const char *d, size_t len, const char *where, struct err *e)
{
    if (len < 20)
        return err_set(e, "%s: byte 0: GLB too short for its header", where);
    if (le32(d + 4) != 2)
        return err_set(e, "%s: byte 4: GLB version %u (only glTF 2.0)", where, le32(d + 4));
    if (le32(d + 8) != len)
        return err_set(e, "%s: byte 8: GLB says %u bytes, the file has %zu", where, le32(d + 8),
                       len);
    for (size_t off = 12; off < len;) {
        if (len - off < 8)
            return err_set(e, "%s: byte %zu: truncated GLB chunk header", where, off);
        uint32_t n = le32(d + off);
        if (n > len - off - 8)
            return err_set(e, "%s: byte %zu: GLB chunk of %u bytes, %zu left in the file", where,
                           off, n, len - off - 8);
        off += 8 + (size_t)n;
    }
    return 0;
}

int import_read(const char *data, size_t len, const struct model_ctx *ctx, struct mesh *out,
                struct err *e)
{
    memset(out, 0, sizeof *out);
    char where[FILE_QUOTE_SIZE];
    file_quote(ctx->path ? ctx->path : "<memory>", where, sizeof where);
    if (len >= 4 && memcmp(data, "glTF", 4) == 0 && check_glb(data, len, where, e))
        return -1;
    char name[64];
    const char *iname = ctx->path;
    bool in = iname && strcmp(iname, MODEL_STDIN_NAME) == 0;
    if (!iname || in) { /* assimp picks importers by name: give it one that fits the bytes
                           (standard input's others are found in the current folder) */
        snprintf(name, sizeof name, "%s.%s", in ? "stdin" : "memory",
                 import_guess_ext(data, len));
        iname = name;
    }
    struct import_job job = {data, len, iname, ctx->path != NULL};
    uint8_t *reply;
    size_t n;
    if (sandbox_run(import_job, &job, where, "importer", &reply, &n, e))
        return -1;
    int rc = import_build(reply, n, ctx, where, out, e);
    free(reply);
    if (rc)
        mesh_free(out);
    return rc;
}

const char *import_guess_ext(const char *data, size_t len)
{
    if (len >= 4 && memcmp(data, "glTF", 4) == 0)
        return "glb";
    if (len >= 18 && memcmp(data, "Kaydara FBX Binary", 18) == 0)
        return "fbx";
    for (size_t i = 0; i < len && i < 4096; i++) {
        if (data[i] == '{')
            return "gltf";
        if (data[i] == '<')
            return "dae";
        if (data[i] == ';')
            return "fbx";
        if (data[i] != ' ' && data[i] != '\t' && data[i] != '\r' && data[i] != '\n' &&
            (unsigned char)data[i] != 0xef && (unsigned char)data[i] != 0xbb &&
            (unsigned char)data[i] != 0xbf)
            break;
    }
    return "3ds";
}
