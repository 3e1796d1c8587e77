/* test_mtl.c: MTL parsing, map_Kd options and error messages (numbers: test_lex.c). */
#include <math.h>
#include <string.h>

#include "mtl.h"
#include "test.h"

static int parse(const char *text, const char *path, struct mtl_lib *lib, struct err *e)
{
    return mtl_parse(text, strlen(text), path, lib, NULL, e);
}

static int parse_warn(const char *text, const char *path, struct mtl_lib *lib,
                      struct warnings *w, struct err *e)
{
    memset(w, 0, sizeof *w);
    return mtl_parse(text, strlen(text), path, lib, w, e);
}

static void check_rgb(struct test *t, const float *got, double r, double g, double b, int line)
{
    if (!(fabs(got[0] - r) <= 1e-6 && fabs(got[1] - g) <= 1e-6 && fabs(got[2] - b) <= 1e-6))
        test_fail(t, __FILE__, line, "(%.9g, %.9g, %.9g) != (%.9g, %.9g, %.9g)", got[0], got[1],
                  got[2], r, g, b);
}
#define CHECK_RGB(got, r, g, b) check_rgb(t, (got), (r), (g), (b), __LINE__)

static void check_str(struct test *t, const char *got, const char *want, int line)
{
    if (!got || strcmp(got, want) != 0)
        test_fail(t, __FILE__, line, "\"%s\" != \"%s\"", got ? got : "(null)", want);
}
#define CHECK_STR(got, want) check_str(t, (got), (want), __LINE__)

TEST(mtl_values_and_defaults)
{
    struct mtl_lib L;
    struct err e;
    REQUIRE(parse("newmtl plain\n"
                  "newmtl shiny\nKd 0.25 0.5 0.75\nKs 1 0.5 0\nNs 64\n"
                  "newmtl grey\nKd 0.5\n",
                  NULL, &L, &e) == 0);
    REQUIRE(L.n == 3);
    CHECK_STR(L.materials[0].name, "plain");
    CHECK_RGB(L.materials[0].kd, 1, 1, 1);
    CHECK_RGB(L.materials[0].ks, 0.5, 0.5, 0.5);
    CHECK_NEAR(L.materials[0].ns, 32, 0);
    CHECK_EQ_INT(L.materials[0].texture, -1);
    CHECK(L.texture_paths[0] == NULL);
    CHECK_RGB(L.materials[1].kd, 0.25, 0.5, 0.75);
    CHECK_RGB(L.materials[1].ks, 1, 0.5, 0);
    CHECK_NEAR(L.materials[1].ns, 64, 0);
    CHECK_RGB(L.materials[2].kd, 0.5, 0.5, 0.5); /* "Kd r" means r r r */
    mtl_free(&L);
}

TEST(trailing_comments_crlf_and_indentation)
{
    struct mtl_lib L;
    struct err e;
    /* as in cornell_box/CornellBox-Original.mtl */
    REQUIRE(parse("# header\r\n\r\nnewmtl leftWall\r\n  Ns 10.0000\r\n  Ni 1.5000\r\n"
                  "  Ka 0.63 0.065 0.05 # Red\r\n  Kd 0.63 0.065 0.05# glued\r\n"
                  "\tKs 0 0 0 \r\n  \r\n",
                  NULL, &L, &e) == 0);
    REQUIRE(L.n == 1);
    CHECK_STR(L.names[0], "leftWall");
    CHECK_RGB(L.materials[0].kd, 0.63, 0.065, 0.05);
    CHECK_RGB(L.materials[0].ks, 0, 0, 0);
    CHECK_NEAR(L.materials[0].ns, 10, 0);
    mtl_free(&L);
}

TEST(unused_statements_ignored_even_when_malformed)
{
    struct mtl_lib L;
    struct err e;
    /* sportsCar.mtl:336 really says "Ka 0.0000 0.0000 0.0000c" */
    REQUIRE(parse("Wavefront OBJ material file\nKd junk before any newmtl\n"
                  "newmtl a\nKa 0.0000 0.0000 0.0000c\nillum 2\nd 1\nTr 0\nNi 1.5\nKe 5 5 5\n"
                  "Tf 1 1 1\nmap_Ks spec.png\nmap_Bump -bm 1 n.png\nmap_d a.png\n",
                  NULL, &L, &e) == 0);
    CHECK_EQ_INT(L.n, 1);
    CHECK(L.texture_paths[0] == NULL);
    mtl_free(&L);
}

TEST(names_trimmed_sanitised_and_kept_whole)
{
    struct mtl_lib L;
    struct err e;
    char text[300];
    char longname[101];
    memset(longname, 'n', 100);
    longname[100] = '\0';
    snprintf(text, sizeof text, "newmtl  RearLights \r\nnewmtl caf\xc3\xa9 au lait\nnewmtl %s\n",
             longname);
    REQUIRE(parse(text, NULL, &L, &e) == 0);
    REQUIRE(L.n == 3);
    CHECK_STR(L.names[0], "RearLights");
    CHECK_STR(L.materials[0].name, "RearLights");
    CHECK_STR(L.names[1], "caf\xc3\xa9 au lait"); /* usemtl matches the bytes */
    CHECK_STR(L.materials[1].name, "caf?? au lait"); /* shown as printable ASCII */
    CHECK_STR(L.names[2], longname);
    CHECK_EQ_INT(strlen(L.materials[2].name), MESH_NAME_MAX - 2); /* 59 + "..." */
    CHECK(strcmp(L.materials[2].name + MESH_NAME_MAX - 5, "...") == 0);
    mtl_free(&L);
}

TEST(map_kd_options_skipped)
{
    static const struct {
        const char *line, *want;
    } cases[] = {
        {"map_Kd tex.png", "tex.png"},
        {"map_Kd -mm 0 1 tex.png", "tex.png"},
        {"map_Kd -o 0.5 tex.png", "tex.png"},
        {"map_Kd -o 0.5 0.5 tex.png", "tex.png"},
        {"map_Kd -s 1 2 3 -t 0 0 0 tex.png", "tex.png"},
        {"map_Kd -blendu on -blendv off -cc on -clamp on tex.png", "tex.png"},
        {"map_Kd -bm 0.5 -boost 2 -texres 512 -imfchan r -type sphere tex.png", "tex.png"},
        {"map_Kd\t-clamp\ton\tmy texture file.png  \r", "my texture file.png"},
        {"map_Kd -s 2 2 tex#1.png", "tex#1.png"},
        {"map_Kd tex.png # a comment", "tex.png"},
        {"map_Kd 1.png", "1.png"},
        {"map_Kd -o 1 2 3 4.png", "4.png"},
        {"map_Kd -5.png", "-5.png"}, /* a number is no option */
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char text[200];
        struct mtl_lib L;
        struct err e;
        struct warnings w;
        snprintf(text, sizeof text, "newmtl m\n%s\n", cases[i].line);
        if (parse_warn(text, NULL, &L, &w, &e)) {
            test_fail(t, __FILE__, __LINE__, "case %zu: %s", i, e.msg);
            continue;
        }
        CHECK_STR(L.texture_paths[0], cases[i].want);
        CHECK_EQ_INT(L.texture_lines[0], 2);
        CHECK_EQ_INT(w.n, 0);
        mtl_free(&L);
    }
}

TEST(map_kd_unknown_options_skipped_with_a_warning)
{
    static const struct {
        const char *line, *want, *warning;
    } cases[] = {
        /* real exporters write -colorspace; it is no MTL option and no part of the name */
        {"map_Kd -colorspace sRGB SpiderTex.jpg", "SpiderTex.jpg",
         "lib.mtl:2: unknown map_Kd option '-colorspace' skipped with its value"},
        {"map_Kd -clamp on -colorspace sRGB -o 1 my tex.png", "my tex.png",
         "lib.mtl:2: unknown map_Kd option '-colorspace' skipped with its value"},
        {"map_Kd -unknown x.png", "x.png", "lib.mtl:2: unknown map_Kd option '-unknown' skipped"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char text[200];
        struct mtl_lib L;
        struct err e;
        struct warnings w;
        snprintf(text, sizeof text, "newmtl m\n%s\n", cases[i].line);
        if (parse_warn(text, "lib.mtl", &L, &w, &e)) {
            test_fail(t, __FILE__, __LINE__, "case %zu: %s", i, e.msg);
            continue;
        }
        CHECK_STR(L.texture_paths[0], cases[i].want);
        CHECK_EQ_INT(w.n, 1);
        CHECK_STR(w.msg[0], cases[i].warning);
        mtl_free(&L);
    }
}

TEST(empty_newmtl_name_and_bom_are_not_errors)
{
    struct mtl_lib L;
    struct err e;
    struct warnings w;
    /* a UTF-8 byte-order mark; an empty name still owns its Kd (not the material before) */
    REQUIRE(parse_warn("\xef\xbb\xbfnewmtl a\nKd 1 0 0\nnewmtl\nKd 0 1 0\nnewmtl # c\n",
                       "lib.mtl", &L, &w, &e) == 0);
    REQUIRE(L.n == 3);
    CHECK_STR(L.names[0], "a");
    CHECK_RGB(L.materials[0].kd, 1, 0, 0);
    CHECK_STR(L.names[1], "");
    CHECK_RGB(L.materials[1].kd, 0, 1, 0);
    CHECK_EQ_INT(w.n, 2);
    CHECK_STR(w.msg[0], "lib.mtl:3: newmtl without a name (no usemtl can use it)");
    CHECK_STR(w.msg[1], "lib.mtl:5: newmtl without a name (no usemtl can use it)");
    mtl_free(&L);
}

TEST(map_kd_relative_to_the_mtl_directory)
{
    struct mtl_lib L;
    struct err e;
    REQUIRE(parse("newmtl a\nmap_Kd sub/a.png\nnewmtl b\nmap_Kd /abs/b.png\n"
                  "newmtl c\nmap_Kd first.png\nmap_Kd second.png\n",
                  "models/car/car.mtl", &L, &e) == 0);
    REQUIRE(L.n == 3);
    CHECK_STR(L.texture_paths[0], "models/car/sub/a.png");
    CHECK_STR(L.texture_paths[1], "/abs/b.png");
    CHECK_STR(L.texture_paths[2], "models/car/second.png"); /* the last map_Kd counts */
    CHECK_EQ_INT(L.texture_lines[2], 7);
    CHECK_STR(L.path, "models/car/car.mtl");
    mtl_free(&L);
    REQUIRE(parse("newmtl a\nmap_Kd a.png\n", "lib.mtl", &L, &e) == 0);
    CHECK_STR(L.texture_paths[0], "a.png");
    mtl_free(&L);
}

TEST(negative_ns_clamped_to_zero)
{
    struct mtl_lib L;
    struct err e;
    REQUIRE(parse("newmtl a\nNs -5\n", NULL, &L, &e) == 0);
    CHECK_NEAR(L.materials[0].ns, 0, 0);
    mtl_free(&L);
}

TEST(mtl_error_names_file_and_line)
{
    static const struct {
        const char *text, *msg;
    } cases[] = {
        {"newmtl a\nKd 1 x 0\n", "lib.mtl:2: bad number 'x'"},
        {"newmtl a\r\nKs 1 1\r\n", "lib.mtl:2: 'Ks' needs 3 numbers, got 2"},
        {"newmtl a\nKd\n", "lib.mtl:2: 'Kd' needs 3 numbers, got 0"},
        {"newmtl a\n\nNs\n", "lib.mtl:3: 'Ns' needs a number"},
        {"newmtl a\nNs 1e99\n", "lib.mtl:2: number out of range '1e99'"},
        {"newmtl a\nmap_Kd\n", "lib.mtl:2: map_Kd needs a file name"},
        {"newmtl a\nmap_Kd -clamp on  \n", "lib.mtl:2: map_Kd needs a file name"},
        {"newmtl a\nmap_Kd -mm 1\n", "lib.mtl:2: map_Kd option '-mm' needs a value"},
        {"newmtl a\nKd 1 \x1b[2J 1\n", "lib.mtl:2: bad number '?[2J'"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        struct mtl_lib L;
        struct err e = {{0}};
        CHECK_EQ_INT(parse(cases[i].text, "lib.mtl", &L, &e), -1);
        if (strcmp(e.msg, cases[i].msg) != 0)
            test_fail(t, __FILE__, __LINE__, "case %zu: got \"%s\", want \"%s\"", i, e.msg,
                      cases[i].msg);
        CHECK(L.n == 0 && L.materials == NULL); /* left empty */
    }
    struct mtl_lib L;
    struct err e;
    CHECK_EQ_INT(mtl_load("tests/data/obj/no_such.mtl", &L, NULL, &e), -1);
    CHECK_STR(e.msg, "tests/data/obj/no_such.mtl: cannot open material library: No such file "
                     "or directory");
}

TEST(sports_car_mtl_loads)
{
    const char *dir = test_models_dir();
    if (!dir) {
        test_skip(t, "no shared models");
        return;
    }
    char path[4200];
    struct mtl_lib L;
    struct err e;
    snprintf(path, sizeof path, "%s/sports_car/sportsCar.mtl", dir);
    if (mtl_load(path, &L, NULL, &e)) {
        test_fail(t, __FILE__, __LINE__, "%s", e.msg);
        return;
    }
    CHECK_EQ_INT(L.n, 38);
    CHECK_STR(L.names[0], "SmallHeadLights");
    CHECK_RGB(L.materials[0].ks, 0.9, 0.9, 0.9);
    CHECK_STR(L.names[1], "RearLights");
    mtl_free(&L);
}

TEST(maps_not_drawn_are_named_once)
{
    /* holodeck.mtl's map_Ks and map_Ke: each a warning naming it, once per file */
    struct mtl_lib L;
    struct err e;
    struct warnings w;
    REQUIRE(parse_warn("newmtl a\nmap_Ks s.png\nmap_Ke e.png\nnewmtl b\nmap_Ks s.png\n"
                       "illum 2\nNi 1.5\n",
                       "h.mtl", &L, &w, &e) == 0);
    CHECK_EQ_INT(w.n, 2);
    CHECK(w.n == 2 && strstr(w.msg[0], "h.mtl:2: map_Ks is not drawn") &&
          strstr(w.msg[1], "h.mtl:3: map_Ke is not drawn"));
    mtl_free(&L);
}
