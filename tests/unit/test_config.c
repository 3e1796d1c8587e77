/* test_config.c: the config file and RASTTY_COLORS (config.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "config.h"
#include "test.h"

static struct config fresh(void)
{
    return (struct config){.spin = -1, .spin_timeout = -1};
}

TEST(config_file_settings_parse)
{
    struct config c = fresh();
    struct err e;
    const char *text = "# my defaults\n"
                       "colors = 256   # banding is fine\n"
                       "\n"
                       "light=world\r\n"
                       "  spin = off\n"
                       "spin-timeout = 30\n"
                       "bandwidth = 1Mbit\n"
                       "glyphs = sextant\n";
    REQUIRE(config_parse("cfg", text, &c, &e) == 0);
    CHECK(strcmp(c.colors, "256") == 0);
    CHECK_EQ_INT(c.light, CONFIG_LIGHT_WORLD);
    CHECK_EQ_INT(c.spin, 0);
    CHECK(c.spin_timeout == 30 && c.bandwidth == 125000);
    CHECK_EQ_INT(c.glyphs, CELL_SEXTANT);
    REQUIRE(config_parse("cfg", "light = 1,2,-3\ncolors = auto\n", &c, &e) == 0);
    CHECK(c.light == CONFIG_LIGHT_DIR && c.light_dir.z == -3 && c.colors[0] == '\0');
    /* applied under what the command line said */
    struct options o;
    char *argv[] = {"rastty", "--no-spin", "--colors", "16"};
    REQUIRE(options_parse(4, argv, &o, &e) == 0);
    struct config d = fresh();
    REQUIRE(config_parse("cfg", "colors = none\nspin = on\nspin-timeout = 5\nlight = camera\n"
                                "glyphs = braille\n", &d, &e) == 0);
    config_apply(&d, &o);
    CHECK(strcmp(o.colors, "16") == 0 && o.spin == 0 && o.spin_timeout == 5 && o.light_camera);
    CHECK_EQ_INT(o.glyphs, CELL_BRAILLE);
    char *argv2[] = {"rastty", "--glyphs", "quadrant"}; /* the command line wins */
    REQUIRE(options_parse(3, argv2, &o, &e) == 0);
    config_apply(&d, &o);
    CHECK_EQ_INT(o.glyphs, CELL_QUADRANT);
}

TEST(config_file_errors_name_the_line)
{
    static const struct {
        const char *text, *want;
    } rows[] = {
        {"colors = 24\n", "cfg:1: colors: expected auto, truecolor, 256, 16 or none, got '24'"},
        {"\nlight = sideways\n", "cfg:2: light: expected camera, world or X,Y,Z"},
        {"light = 0,0,0\n", "cfg:1: light:"},
        {"spin = maybe\n", "cfg:1: spin: expected on or off"},
        {"spin-timeout = -1\n", "cfg:1: spin-timeout"},
        {"bandwidth = fast\n", "cfg:1: bandwidth"},
        {"glyphs = hexagon\n", "cfg:1: glyphs: expected half, quadrant, sextant, braille or ascii"},
        {"colour = 256\n", "cfg:1: unknown key"},
        {"colors 256\n", "cfg:1: expected key = value"},
        {"colors = \033[31m\n", "got '?[31m'"},
    };
    for (size_t i = 0; i < sizeof rows / sizeof rows[0]; i++) {
        struct config c = fresh();
        struct err e = {""};
        CHECK(config_parse("cfg", rows[i].text, &c, &e) == -1);
        CHECK_STR_CONTAINS(e.msg, rows[i].want);
    }
}

TEST(rastty_colors_beats_the_file_and_a_missing_file_is_fine)
{
    char dir[] = "/tmp/rastty-config-XXXXXX", path[128];
    REQUIRE(mkdtemp(dir));
    struct config c;
    struct err e;
    REQUIRE(config_load(dir, "/nonexistent", "16", &c, &e) == 0); /* no file yet */
    CHECK(strcmp(c.colors, "16") == 0);
    snprintf(path, sizeof path, "%s/rastty", dir);
    mkdir(path, 0700);
    snprintf(path, sizeof path, "%s/rastty/config", dir);
    FILE *f = fopen(path, "w");
    REQUIRE(f);
    fputs("colors = none\nspin = on\n", f);
    fclose(f);
    REQUIRE(config_load(dir, NULL, "16", &c, &e) == 0);
    CHECK(strcmp(c.colors, "16") == 0 && c.spin == 1);
    REQUIRE(config_load(dir, NULL, NULL, &c, &e) == 0);
    CHECK(strcmp(c.colors, "none") == 0);
    REQUIRE(config_load("", dir, "", &c, &e) == 0); /* $HOME/.config/rastty: none there */
    CHECK(c.colors[0] == '\0' && c.spin == -1);
    CHECK(config_load(dir, NULL, "lots", &c, &e) == -1);
    CHECK_STR_CONTAINS(e.msg, "RASTTY_COLORS");
    unlink(path);
    snprintf(path, sizeof path, "%s/rastty", dir);
    rmdir(path);
    rmdir(dir);
}
