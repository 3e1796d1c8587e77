/* test_texfind.c: the texture beside a model without an MTL, by naming habit. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "test.h"
#include "texfind.h"

static char dir[64];

static void touch(const char *name)
{
    char p[256];
    snprintf(p, sizeof p, "%s/%s", dir, name);
    FILE *f = fopen(p, "w");
    if (f)
        fclose(f);
}

static void rm(const char *name)
{
    char p[256];
    snprintf(p, sizeof p, "%s/%s", dir, name);
    unlink(p);
}

/* the file name texfind picks for DIR/model, or "" */
static const char *found(const char *model)
{
    static char out[512];
    char p[256];
    snprintf(p, sizeof p, "%s/%s", dir, model);
    if (texfind_beside(p, out, sizeof out))
        return "";
    const char *slash = strrchr(out, '/');
    return slash ? slash + 1 : out;
}

TEST(textures_are_found_beside_a_model_by_name_in_order)
{
    snprintf(dir, sizeof dir, "/tmp/rastty-texfind-XXXXXX");
    REQUIRE(mkdtemp(dir));
    /* nothing there */
    CHECK(strcmp(found("head.obj"), "") == 0);
    /* texture.* and diffuse.* are the last resort */
    touch("texture.jpg");
    CHECK(strcmp(found("head.obj"), "texture.jpg") == 0);
    /* the stem itself beats them, NAME_texture beats it, NAME_diffuse beats all */
    touch("head.tga");
    CHECK(strcmp(found("head.obj"), "head.tga") == 0);
    touch("head_texture.PNG");
    CHECK(strcmp(found("head.obj"), "head_texture.PNG") == 0);
    touch("head_diffuse.png");
    CHECK(strcmp(found("head.obj"), "head_diffuse.png") == 0);
    /* spot_triangulated.obj: the stem cut at '_' finds spot_texture.png; the longer
     * african_head_eye_inner keeps its own before the shorter stem's */
    touch("spot_texture.png");
    CHECK(strcmp(found("spot_triangulated.obj"), "spot_texture.png") == 0);
    touch("african_head_diffuse.tga");
    touch("african_head_eye_inner_diffuse.tga");
    CHECK(strcmp(found("african_head_eye_inner.obj"), "african_head_eye_inner_diffuse.tga") == 0);
    rm("african_head_eye_inner_diffuse.tga");
    CHECK(strcmp(found("african_head_eye_inner.obj"), "african_head_diffuse.tga") == 0);
    /* other extensions, a path without a directory, no extension */
    touch("notes.txt");
    CHECK(strcmp(found("notes.obj"), "texture.jpg") == 0);
    static const char *const names[] = {"texture.jpg", "head.tga", "head_texture.PNG",
                                        "head_diffuse.png", "spot_texture.png",
                                        "african_head_diffuse.tga", "notes.txt"};
    for (unsigned i = 0; i < sizeof names / sizeof names[0]; i++)
        rm(names[i]);
    rmdir(dir);
}

/* the normal map texfind_normal_beside picks for DIR/model, or "" */
static const char *found_nm(const char *model)
{
    static char out[512];
    char p[256];
    snprintf(p, sizeof p, "%s/%s", dir, model);
    if (texfind_normal_beside(p, out, sizeof out))
        return "";
    const char *slash = strrchr(out, '/');
    return slash ? slash + 1 : out;
}

TEST(normal_maps_are_found_beside_a_model_by_name_in_order)
{
    snprintf(dir, sizeof dir, "/tmp/rastty-texfind-XXXXXX");
    REQUIRE(mkdtemp(dir));
    touch("african_head_diffuse.tga");
    CHECK(strcmp(found_nm("african_head.obj"), "") == 0); /* a diffuse map is not one */
    touch("african_head_normals.png");
    CHECK(strcmp(found_nm("african_head.obj"), "african_head_normals.png") == 0);
    touch("african_head_normal.jpg");
    CHECK(strcmp(found_nm("african_head.obj"), "african_head_normal.jpg") == 0);
    touch("african_head_nm.tga"); /* tinyrenderer's name */
    CHECK(strcmp(found_nm("african_head.obj"), "african_head_nm.tga") == 0);
    touch("african_head_nm_tangent.tga");
    CHECK(strcmp(found_nm("african_head.obj"), "african_head_nm_tangent.tga") == 0);
    /* the stem cut at '_': the eyes' model finds the head's map */
    CHECK(strcmp(found_nm("african_head_eye_inner.obj"), "african_head_nm_tangent.tga") == 0);
    static const char *const names[] = {"african_head_diffuse.tga", "african_head_normals.png",
                                        "african_head_normal.jpg", "african_head_nm.tga",
                                        "african_head_nm_tangent.tga"};
    for (unsigned i = 0; i < sizeof names / sizeof names[0]; i++)
        rm(names[i]);
    rmdir(dir);
}
