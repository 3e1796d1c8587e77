/* test_cell.c: the cell geometry — glyph tables against Unicode's charts, the decoder's shapes
 * against the encoder's patterns, the grid a shape needs, and a disk that stays round in every
 * glyph set (the projection uses the cells' physical aspect, not the pixel count). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cell.h"
#include "obj.h"
#include "pipeline.h"
#include "test.h"

TEST(geometries_and_pixel_shapes)
{
    static const struct {
        enum cell_glyphs g;
        int w, h;
        double aspect;
        const char *name;
    } want[] = {
        {CELL_HALF, 1, 2, 1.0, "half"},       {CELL_QUADRANT, 2, 2, 0.5, "quadrant"},
        {CELL_SEXTANT, 2, 3, 0.75, "sextant"}, {CELL_BRAILLE, 2, 4, 1.0, "braille"},
        {CELL_ASCII, 1, 1, 0.5, "ascii"},
    };
    for (unsigned i = 0; i < sizeof want / sizeof want[0]; i++) {
        struct cell_geom g = cell_geom(want[i].g);
        CHECK_EQ_INT(g.px_w, want[i].w);
        CHECK_EQ_INT(g.px_h, want[i].h);
        CHECK(fabs(cell_pixel_aspect(&g) - want[i].aspect) < 1e-12);
        CHECK(g.fg_only == (want[i].g == CELL_BRAILLE));
        CHECK(strcmp(cell_glyphs_name(want[i].g), want[i].name) == 0);
        CHECK_EQ_INT(cell_glyphs_parse(want[i].name), want[i].g);
        /* 80 x 24 cells: the picture is 80 wide and 48 tall in half-cell units */
        CHECK(fabs(cell_fb_w(&g, 80) * cell_pixel_aspect(&g) / cell_fb_h(&g, 24) - 80.0 / 48) < 1e-12);
    }
    CHECK_EQ_INT(cell_glyphs_parse("hexagon"), -1);
}

/* Code points from the Unicode charts (Block Elements, Symbols for Legacy Computing, Braille
 * Patterns), pixel i = (i % px_w, i / px_w) */
TEST(glyph_code_points_follow_the_unicode_charts)
{
    CHECK_EQ_INT(cell_glyph_cp(CELL_HALF, 1), 0x2580);     /* upper half */
    CHECK_EQ_INT(cell_glyph_cp(CELL_HALF, 2), 0x2584);     /* lower half */
    CHECK_EQ_INT(cell_glyph_cp(CELL_HALF, 0), ' ');
    CHECK_EQ_INT(cell_glyph_cp(CELL_QUADRANT, 1), 0x2598); /* upper left */
    CHECK_EQ_INT(cell_glyph_cp(CELL_QUADRANT, 8), 0x2597); /* lower right */
    CHECK_EQ_INT(cell_glyph_cp(CELL_QUADRANT, 9), 0x259A); /* upper left and lower right */
    CHECK_EQ_INT(cell_glyph_cp(CELL_QUADRANT, 5), 0x258C); /* left half */
    CHECK_EQ_INT(cell_glyph_cp(CELL_QUADRANT, 14), 0x259F);
    CHECK_EQ_INT(cell_glyph_cp(CELL_SEXTANT, 1), 0x1FB00);  /* BLOCK SEXTANT-1 */
    CHECK_EQ_INT(cell_glyph_cp(CELL_SEXTANT, 20), 0x1FB13); /* SEXTANT-35 */
    CHECK_EQ_INT(cell_glyph_cp(CELL_SEXTANT, 21), 0x258C);  /* 1-3-5: the left half */
    CHECK_EQ_INT(cell_glyph_cp(CELL_SEXTANT, 22), 0x1FB14); /* SEXTANT-235 */
    CHECK_EQ_INT(cell_glyph_cp(CELL_SEXTANT, 42), 0x2590);  /* 2-4-6: the right half */
    CHECK_EQ_INT(cell_glyph_cp(CELL_SEXTANT, 62), 0x1FB3B); /* SEXTANT-23456 */
    CHECK_EQ_INT(cell_glyph_cp(CELL_SEXTANT, 63), 0x2588);
    CHECK_EQ_INT(cell_glyph_cp(CELL_BRAILLE, 1), 0x2801);       /* dot 1 */
    CHECK_EQ_INT(cell_glyph_cp(CELL_BRAILLE, 1u << 2), 0x2802); /* (0,1): dot 2 */
    CHECK_EQ_INT(cell_glyph_cp(CELL_BRAILLE, 1u << 1), 0x2808); /* (1,0): dot 4 */
    CHECK_EQ_INT(cell_glyph_cp(CELL_BRAILLE, 1u << 6), 0x2840); /* (0,3): dot 7 */
    CHECK_EQ_INT(cell_glyph_cp(CELL_BRAILLE, 1u << 7), 0x2880); /* (1,3): dot 8 */
    CHECK_EQ_INT(cell_glyph_cp(CELL_BRAILLE, 0xff), 0x28FF);
    char u[4];
    CHECK_EQ_INT(cell_utf8(0x1FB00, u), 4);
    CHECK(memcmp(u, "\xf0\x9f\xac\x80", 4) == 0);
    CHECK_EQ_INT(cell_utf8(0x2580, u), 3);
    CHECK(memcmp(u, "\xe2\x96\x80", 3) == 0);
}

/* The decoder's shape of every glyph the encoder emits shows exactly its pattern. */
TEST(every_pattern_decodes_to_itself)
{
    for (int k = 0; k < CELL_ASCII; k++) {
        struct cell_geom g = cell_geom((enum cell_glyphs)k);
        unsigned n = 1u << cell_px(&g);
        for (unsigned m = 0; m < n; m++) {
            uint32_t shape;
            REQUIRE(cell_shape(cell_glyph_cp(g.glyphs, m), &shape) == 0);
            unsigned back = 0;
            for (int y = 0; y < CELL_MASTER_H; y++)
                for (int x = 0; x < CELL_MASTER_W; x++) {
                    int i = (y * g.px_h / CELL_MASTER_H) * g.px_w + x * g.px_w / CELL_MASTER_W;
                    bool set = shape >> (y * CELL_MASTER_W + x) & 1;
                    if (set)
                        back |= 1u << i;
                    CHECK(set == (bool)(m >> i & 1)); /* every master cell of the pixel agrees */
                }
            CHECK_EQ_INT(back, m);
            int w, h;
            cell_shape_grid(shape, &w, &h); /* the grid it needs divides its own */
            CHECK(g.px_w % w == 0 && g.px_h % h == 0);
        }
    }
    uint32_t shape;
    CHECK(cell_shape(0x2581, &shape) == -1); /* lower one eighth: not ours */
    CHECK(cell_shape('#', &shape) == -1);
    int w, h;
    cell_shape(0x2580, &shape);
    cell_shape_grid(shape, &w, &h);
    CHECK(w == 1 && h == 2);
    cell_shape(0x258C, &shape);
    cell_shape_grid(shape, &w, &h);
    CHECK(w == 2 && h == 1);
    cell_shape(0x1FB00, &shape);
    cell_shape_grid(shape, &w, &h);
    CHECK(w == 2 && h == 3);
    cell_shape(0x2840, &shape);
    cell_shape_grid(shape, &w, &h);
    CHECK(w == 2 && h == 4);
}

/* A disk of radius 0.8 facing the default camera, drawn at 60 x 20 cells in every glyph
 * set: its bounding box, in cell widths (a cell is CELL_ASPECT as wide as tall), is as wide
 * as it is tall to within a pixel, so a sphere stays a sphere. */
TEST(a_disk_stays_round_in_every_glyph_set)
{
    char obj[4096];
    int len = 0;
    enum { N = 48 };
    for (int i = 0; i < N; i++)
        len += snprintf(obj + len, sizeof obj - (size_t)len, "v %.9f %.9f 0\n",
                        0.8 * cos(2 * M_PI * i / N), 0.8 * sin(2 * M_PI * i / N));
    len += snprintf(obj + len, sizeof obj - (size_t)len, "f");
    for (int i = 1; i <= N; i++)
        len += snprintf(obj + len, sizeof obj - (size_t)len, " %d", i);
    len += snprintf(obj + len, sizeof obj - (size_t)len, "\n");
    struct mesh m;
    REQUIRE(obj_parse(obj, (size_t)len, NULL, &m, NULL) == 0);
    struct draw_item item = {.mesh = &m, .model = m4_identity()};
    struct camera cam;
    camera_default(&cam);
    struct render_opts o;
    render_opts_default(&o);
    o.shade = SHADE_UNLIT;
    o.threads = 1;
    struct pipeline *p = pipeline_new();
    REQUIRE(p != NULL);
    for (int k = 0; k < CELL_GLYPHS_COUNT; k++) {
        struct cell_geom g = cell_geom((enum cell_glyphs)k);
        struct fb fb;
        REQUIRE(fb_init(&fb, cell_fb_w(&g, 60), cell_fb_h(&g, 20), false, NULL) == 0);
        fb.pixel_aspect = cell_pixel_aspect(&g);
        struct frame_stats st;
        REQUIRE(pipeline_draw(p, &item, 1, NULL, &cam, &o, &fb, &st, NULL) == 0);
        int x0 = fb.w, x1 = -1, y0 = fb.h, y1 = -1;
        for (int y = 0; y < fb.h; y++)
            for (int x = 0; x < fb.w; x++)
                if (fb_covered(&fb, (size_t)y * fb.w + x)) {
                    x0 = x < x0 ? x : x0, x1 = x > x1 ? x : x1;
                    y0 = y < y0 ? y : y0, y1 = y > y1 ? y : y1;
                }
        /* in cell widths; one pixel of slack on each side */
        double wide = (x1 - x0 + 1.0) / g.px_w, tall = (y1 - y0 + 1.0) / g.px_h / CELL_ASPECT;
        double slack = 2.0 / g.px_w + 2.0 / g.px_h / CELL_ASPECT;
        if (fabs(wide - tall) > slack)
            fprintf(stderr, "    %s: %.2f cell widths wide, %.2f tall\n", cell_glyphs_name(g.glyphs),
                    wide, tall);
        CHECK(fabs(wide - tall) <= slack);
        CHECK(wide > 15); /* and it is a disk of some size, not a dot */
        fb_free(&fb);
    }
    pipeline_destroy(p);
    mesh_free(&m);
}

/* issue 25 item 8: a cell's height / width from the window's pixels (TIOCGWINSZ) or one
 * cell's (ESC[16t), and a pixel's shape for it: a 1:2.2 font keeps circles round */
TEST(cell_aspect_from_the_terminals_pixels)
{
    CHECK_NEAR(cell_aspect_of(800, 528, 80, 24), 2.2, 1e-12); /* 10x22 cells */
    CHECK_NEAR(cell_aspect_of(10, 22, 1, 1), 2.2, 1e-12);
    CHECK_NEAR(cell_aspect_of(640, 384, 80, 24), 2.0, 1e-12);
    CHECK(cell_aspect_of(0, 0, 80, 24) == 0);                  /* not told (ssh, tmux) */
    CHECK(cell_aspect_of(800, 24, 80, 24) == 0);               /* nonsense: 1x10 px cells */
    CHECK(cell_aspect_of(800, 528, 0, 24) == 0);
    struct cell_geom half = cell_geom(CELL_HALF), quad = cell_geom(CELL_QUADRANT);
    CHECK_NEAR(cell_pixel_aspect_r(&half, 2), 1, 1e-12); /* square on 1:2 */
    CHECK_NEAR(cell_pixel_aspect_r(&half, 2.2), 1 / 1.1, 1e-12);
    CHECK_NEAR(cell_pixel_aspect_r(&quad, 2.2), 1 / 2.2, 1e-12); /* 2x2 a cell: tall pixels */
    CHECK_NEAR(cell_pixel_aspect(&half), cell_pixel_aspect_r(&half, 2), 1e-12);
    /* a fb of 80x24 cells of 1:2.2 is 80 / (2.2 * 24) as wide as tall on the screen */
    struct fb fb = {.w = 80, .h = 48, .pixel_aspect = cell_pixel_aspect_r(&half, 2.2)};
    CHECK_NEAR(fb_aspect(&fb), 80 / (2.2 * 24), 1e-12);
}
