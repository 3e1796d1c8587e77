/* test_view.c: the viewer's keys, mouse, spin rules, status line and screenshot command,
 * as pure functions of (state, event, time) — no terminal. */
#include <curses.h>
#include <math.h>
#include <string.h>

#include "input.h"
#include "options.h"
#include "test.h"
#include "view_hud.h"
#include "view_shot.h"
#include "view_state.h"

static void start(struct view_state *s, bool spin)
{
    struct camera c;
    camera_default(&c);
    struct render_opts ro;
    render_opts_default(&ro);
    view_state_init(s, &c, &ro, spin, true, 60, 0);
    view_state_scene(s, &c, &ro, 2);
    s->dirty = s->hud_dirty = false;
}

/* the camera's yaw around the target, degrees (0 = looking down -Z from +Z) */
static double yaw(const struct view_state *s)
{
    return atan2(s->cam.eye.x - s->cam.target.x, s->cam.eye.z - s->cam.target.z) * 180 / M_PI;
}

TEST(a_tap_turns_for_tap_s_from_the_press_however_long_the_idle)
{
    struct view_state s;
    start(&s, false);
    view_key(&s, IN_YAW_LEFT, 100.0); /* the last frame was long ago */
    view_advance(&s, 0, 100.05);
    view_advance(&s, 100.05, 101);
    CHECK_NEAR(yaw(&s), -VIEW_TURN_DEG_S * VIEW_TAP_S, 1e-6); /* orbit: the eye moves right */
    CHECK(s.dirty);
    /* auto-repeat (presses closer than REPEAT_GAP) keeps it moving, each for REPEAT_HOLD */
    start(&s, false);
    view_key(&s, IN_YAW_RIGHT, 10.0);
    view_key(&s, IN_YAW_RIGHT, 10.1);
    view_key(&s, IN_YAW_RIGHT, 10.2);
    view_advance(&s, 9, 12);
    CHECK_NEAR(yaw(&s), VIEW_TURN_DEG_S * (10.2 + VIEW_REPEAT_HOLD_S - 10.0), 1e-6);
}

TEST(camera_keys_stop_the_spin_and_space_starts_it_again)
{
    struct view_state s;
    start(&s, true);
    CHECK(view_animating(&s, 1));
    view_key(&s, IN_PAUSE, 1);
    CHECK(!view_animating(&s, 1.1));
    view_key(&s, IN_PAUSE, 2);
    CHECK(view_animating(&s, 2.1)); /* Space resumes a paused spin */
    view_advance(&s, 2, 3);
    CHECK_NEAR(yaw(&s), -VIEW_SPIN_DEG_S, 1e-6);
    view_key(&s, IN_FORWARD, 4); /* a camera key */
    CHECK(!s.spin);
    view_advance(&s, 4, 10);
    CHECK(!view_animating(&s, 10));
    view_key(&s, IN_PAUSE, 11); /* Space starts it again (issue 25: not a flag to quit for) */
    CHECK(view_animating(&s, 11));
    CHECK(s.spin && !s.paused);
    CHECK_STR_CONTAINS(s.message, "auto-rotation on");
    view_key(&s, IN_PAUSE, 12); /* and pauses it */
    CHECK(!view_animating(&s, 12.1));
    /* fov, reset and the mouse are camera keys too; o, m, f are not */
    static const enum input_cmd stops[] = {IN_FOV_IN, IN_FOV_OUT, IN_RESET};
    for (int i = 0; i < 3; i++) {
        start(&s, true);
        view_key(&s, stops[i], 1);
        CHECK(!s.spin);
    }
    static const enum input_cmd keeps[] = {IN_ORBIT, IN_SHADE, IN_FILTER, IN_LIGHT, IN_HELP};
    for (int i = 0; i < 5; i++) {
        start(&s, true);
        view_key(&s, keeps[i], 1);
        CHECK(s.spin);
    }
    start(&s, true);
    struct tty_event wheel = {.kind = TTY_MOUSE, .button = 4, .pressed = true};
    view_mouse(&s, &wheel, 1);
    CHECK(!s.spin);
}

TEST(an_untouched_spin_pauses_after_the_timeout)
{
    struct view_state s;
    start(&s, true); /* timeout 60 s, last input at 0 */
    CHECK(view_animating(&s, 59));
    CHECK(!view_animating(&s, 61));
    CHECK(s.paused && s.spin);
    CHECK_STR_CONTAINS(s.message, "Space resumes");
    view_key(&s, IN_PAUSE, 70);
    CHECK(view_animating(&s, 71));
    CHECK(view_animating(&s, 129)); /* the key restarted the clock */
    CHECK(!view_animating(&s, 131));
}

TEST(mouse_wheel_zooms_and_a_drag_orbits)
{
    struct view_state s;
    start(&s, false);
    double d0 = camera_distance(&s.cam);
    struct tty_event ev = {.kind = TTY_MOUSE, .button = 4, .pressed = true};
    view_mouse(&s, &ev, 1);
    CHECK_NEAR(camera_distance(&s.cam), 0.9 * d0, 1e-9);
    ev = (struct tty_event){.kind = TTY_MOUSE, .button = 0, .mx = 30, .my = 10};
    view_mouse(&s, &ev, 1); /* motion without a press: nothing */
    CHECK_NEAR(yaw(&s), 0, 1e-9);
    ev = (struct tty_event){.kind = TTY_MOUSE, .button = 1, .pressed = true, .mx = 10, .my = 10};
    view_mouse(&s, &ev, 1);
    ev = (struct tty_event){.kind = TTY_MOUSE, .button = 1, .released = true, .mx = 20, .my = 10};
    view_mouse(&s, &ev, 1);
    CHECK_NEAR(yaw(&s), 10 * 1.5, 1e-6); /* dragged right: the eye moves left around */
    CHECK(!s.dragging);
}

TEST(q_and_esc_close_the_help_before_they_quit)
{
    struct view_state s;
    start(&s, false);
    CHECK_EQ_INT(view_key(&s, IN_HELP, 1), VIEW_HELP_OPENED);
    CHECK_EQ_INT(view_key(&s, IN_QUIT, 2), VIEW_HELP_CLOSED);
    CHECK(!s.help);
    CHECK_EQ_INT(view_key(&s, IN_QUIT, 3), VIEW_QUIT);
    CHECK_EQ_INT(view_key(&s, IN_SCREENSHOT, 4), VIEW_SCREENSHOT);
    CHECK_EQ_INT(view_key(&s, IN_NEXT_SCENE, 4), VIEW_NEXT_SCENE);
}

TEST(render_option_keys_cycle_through_every_value)
{
    struct view_state s;
    start(&s, false);
    CHECK_STR_CONTAINS(view_shade_name(&s), "textured");
    static const char *const names[] = {"wire", "flat", "gouraud", "phong", "textured"};
    for (int i = 0; i < 5; i++) {
        view_key(&s, IN_SHADE, 1);
        CHECK_STR_CONTAINS(view_shade_name(&s), names[i]);
    }
    CHECK(s.ro.shade == SHADE_PHONG && s.ro.textures);
    for (int i = 0; i < TEX_FILTER_COUNT; i++) /* round from the default, trilinear */
        view_key(&s, IN_FILTER, 1);
    CHECK_EQ_INT(s.ro.filter, TEX_TRILINEAR);
    view_key(&s, IN_FILTER, 1);
    CHECK_EQ_INT(s.ro.filter, TEX_NEAREST);
    view_key(&s, IN_CULL, 1); /* from the default, auto (as the model says) */
    CHECK_EQ_INT(s.ro.cull, CULL_NONE);
    view_key(&s, IN_CULL, 1);
    CHECK_EQ_INT(s.ro.cull, CULL_BACK);
    for (int i = 1; i < VIEW_COUNT; i++)
        view_key(&s, IN_VIEW, 1);
    CHECK_EQ_INT(s.ro.view, VIEW_COUNT - 1);
    view_key(&s, IN_VIEW, 1);
    CHECK_EQ_INT(s.ro.view, VIEW_COLOR);
    /* the methods: each key cycles its axis and says which one is on */
    view_key(&s, IN_RASTER, 1);
    CHECK_EQ_INT(s.ro.raster, RASTER_SCANLINE);
    CHECK_STR_CONTAINS(s.message, "rasterizer: scanline  (edge scanline tiled)");
    for (int i = 1; i < PERSP_COUNT; i++)
        view_key(&s, IN_PERSPECTIVE, 1);
    CHECK_EQ_INT(s.ro.persp, PERSP_COUNT - 1);
    view_key(&s, IN_PERSPECTIVE, 1);
    CHECK_EQ_INT(s.ro.persp, PERSP_CORRECT);
    view_key(&s, IN_DEPTH, 1);
    CHECK_STR_CONTAINS(s.message, "depth buffer: w");
    /* L: the level of detail cycles off -> auto -> clusters -> off (a RATIO goes to auto) */
    CHECK_EQ_INT(s.ro.lod, LOD_OFF);
    view_key(&s, IN_LOD, 1);
    CHECK_EQ_INT(s.ro.lod, LOD_AUTO);
    CHECK_STR_CONTAINS(s.message, "level of detail: auto  (L: clusters)");
    view_key(&s, IN_LOD, 1);
    CHECK_EQ_INT(s.ro.lod, LOD_CLUSTERS);
    CHECK_STR_CONTAINS(s.message, "level of detail: clusters  (L: off)");
    view_key(&s, IN_LOD, 1);
    CHECK_EQ_INT(s.ro.lod, LOD_OFF);
    CHECK_STR_CONTAINS(s.message, "level of detail: off  (L: auto)");
    s.ro.lod = LOD_RATIO;
    view_key(&s, IN_LOD, 1);
    CHECK_EQ_INT(s.ro.lod, LOD_AUTO);
    view_key(&s, IN_GLYPHS, 1);
    CHECK_EQ_INT(s.glyphs, CELL_QUADRANT);
    CHECK_STR_CONTAINS(s.message, "glyphs: quadrant  (half quadrant sextant braille ascii)");
    /* a new scene keeps the methods, the level of detail and the glyphs chosen with keys */
    struct render_opts ro;
    render_opts_default(&ro);
    view_state_scene(&s, &s.home, &ro, 1);
    CHECK(s.ro.raster == RASTER_SCANLINE && s.ro.depth == (enum depth_mode)1);
    CHECK_EQ_INT(s.ro.lod, LOD_AUTO);
    CHECK_EQ_INT(s.glyphs, CELL_QUADRANT);
}

TEST(l_switches_between_the_headlight_and_the_world_lights)
{
    struct view_state s;
    start(&s, false);
    s.cam.eye = v3(-3, 0, 0);
    struct render_opts ro;
    view_frame_opts(&s, &ro);
    CHECK_NEAR(ro.lights[0].dir.x, -1.0, 1e-9);
    CHECK(ro.ambient_sky.x > 0.1);
    view_key(&s, IN_LIGHT, 1);
    view_frame_opts(&s, &ro);
    CHECK(ro.lights[0].dir.x == 1 && ro.lights[0].dir.y == 1 && ro.lights[0].dir.z == 1);
    CHECK(ro.ambient_sky.x == 0.1 && ro.ambient_ground.x == 0.1);
}

static void hud_frames(const struct view_state *s, int width, unsigned long frames, char *out,
                       size_t n)
{
    struct frame_stats st = {.tris_drawn = 2464, .tris_clipped = 3, .tris_culled = 7,
                             .tris_in = 1246, .tris_full = 2492, .lod_min = 1, .lod_max = 1};
    struct view_hud_info in = {.scene = "african_head.obj", .scene_i = 0, .n_scenes = 1,
                               .texture = "african_head_diffuse.tga", .mode = PALETTE_TRUECOLOR,
                               .fps = 59.6, .render_ms = 2.1, .encode_ms = 0.12, .bytes = 10240,
                               .st = &st, .pacing = "link 125KB/s: 8fps tol 14",
                               .frames = frames};
    view_hud_compose(s, &in, width, 0, out, n);
}

static void hud(const struct view_state *s, int width, char *out, size_t n)
{
    hud_frames(s, width, 0, out, n);
}

TEST(the_status_line_keeps_the_essentials_first_at_80_columns)
{
    struct view_state s;
    start(&s, false);
    char line[512];
    hud(&s, 80, line, sizeof line);
    CHECK((int)strlen(line) <= 79);
    const char *want = " african_head.obj [1/1] | textured trilinear | truecolor | 60 fps";
    CHECK(strncmp(line, want, strlen(want)) == 0);
    CHECK(!strstr(line, "tris")); /* dropped whole, least important first */
    if (t->failures)
        fprintf(stderr, "    80: \"%s\"\n", line);
    hud(&s, 300, line, sizeof line);
    CHECK_STR_CONTAINS(line, "| link 125KB/s: 8fps tol 14 |");
    CHECK_STR_CONTAINS(line, "| tex:african_head_diffuse.tga |");
    CHECK_STR_CONTAINS(line, "| light:camera |");
    CHECK_STR_CONTAINS(line, "| lod off L1 1.2k/2.5k |");
    CHECK_STR_CONTAINS(line, "| tris 2464 clip 3 cull 7");
    /* every width: only whole fields (each kept field is one of the full set) */
    char full[512];
    strcpy(full, line);
    for (int w = 10; w < 300; w += 7) {
        hud(&s, w, line, sizeof line);
        char *save, *f = strtok_r(line, "|", &save);
        for (; f; f = strtok_r(NULL, "|", &save))
            CHECK(strstr(full, f) != NULL);
    }
    /* what `i` adds, and a message replaces the line while it lasts */
    view_key(&s, IN_INFO, 0);
    hud(&s, 250, line, sizeof line);
    CHECK_STR_CONTAINS(line, "eye 0.00,0.00,3.00 target 0.00,0.00,0.00 fov 50");
    view_message(&s, "hello", 0);
    hud(&s, 250, line, sizeof line);
    CHECK_STR_CONTAINS(line, " hello ");
}

/* "#N" (frames written in full) once the picture stands still: right after the frame rate,
 * kept at 80 columns, and after a message too; nothing while it moves (frames 0) */
TEST(the_status_line_counts_frames_when_the_picture_stands_still)
{
    struct view_state s;
    start(&s, false);
    char line[512];
    hud_frames(&s, 80, 1234567, line, sizeof line);
    CHECK((int)strlen(line) <= 79);
    const char *want = " african_head.obj [1/1] | textured trilinear | truecolor | 60 fps | #1234567";
    CHECK(strncmp(line, want, strlen(want)) == 0);
    hud_frames(&s, 300, 7, line, sizeof line);
    CHECK_STR_CONTAINS(line, "| 60 fps | #7 | link 125KB/s");
    hud(&s, 300, line, sizeof line);
    CHECK(!strchr(line, '#'));
    view_message(&s, "hello", 0);
    hud_frames(&s, 80, 8, line, sizeof line);
    CHECK(strcmp(line, " hello | #8 ") == 0);
    hud(&s, 80, line, sizeof line);
    CHECK(strcmp(line, " hello ") == 0);
    /* a message too long for the line gives way to the count */
    view_message(&s, "saved rastty-001.png and rastty-001.ans", 0);
    hud_frames(&s, 30, 12, line, sizeof line);
    CHECK(strcmp(line, " saved rastty-001.png  | #12 ") == 0); /* 29 characters */
    if (t->failures)
        fprintf(stderr, "    \"%s\"\n", line);
}

TEST(the_screenshot_command_reproduces_the_camera_and_methods_exactly)
{
    struct view_state s;
    start(&s, false);
    s.cam.eye = v3(0.1234567890123, -2.5e-7, 3.3333333333333335);
    s.cam.target = v3(0.2, 0.3, -0.1);
    s.cam.fov_deg = 47.123456789;
    s.cam.near = 0.0123;
    s.cam.far = 77.7;
    view_key(&s, IN_SHADE, 0); /* wire */
    view_key(&s, IN_SHADE, 0); /* flat, untextured */
    view_key(&s, IN_FILTER, 0);
    view_key(&s, IN_CULL, 0);
    view_key(&s, IN_VIEW, 0);
    view_key(&s, IN_RASTER, 0);
    view_key(&s, IN_RASTER, 0);
    view_key(&s, IN_PERSPECTIVE, 0);
    view_key(&s, IN_DEPTH, 0);
    view_key(&s, IN_LOD, 0); /* auto */
    s.ro.lod_px = 0.3f;
    s.ro.wire = WIRE_OUTLINE; /* --wire given to the viewer */
    char cmd[VIEW_SHOT_MAX];
    const uint8_t bg[3] = {1, 2, 3};
    struct view_shot_info in = {.model = "models/it's here.obj", .width = 160, .height = 94,
                                .out = "rastty-001.png", .background_set = true,
                                .background = bg, .sky = true, .up_axis = 'x'};
    view_shot_command(&s, &in, cmd, sizeof cmd);
    CHECK_STR_CONTAINS(cmd, "rastty render 'models/it'\\''s here.obj' --size 160x94");
    /* split like sh (the one quoted word by hand) and parse it back */
    char buf[VIEW_SHOT_MAX];
    strcpy(buf, strstr(cmd, "' --size") + 2);
    char *argv[64] = {"rastty", "render", "models/it's here.obj"};
    int argc = 3;
    char *save, *w = strtok_r(buf, " ", &save);
    for (; w && argc < 64; w = strtok_r(NULL, " ", &save))
        argv[argc++] = w;
    struct options o;
    struct err e;
    REQUIRE(options_parse(argc, argv, &o, &e) == 0);
    CHECK(memcmp(&o.camera.eye, &s.cam.eye, sizeof(vec3)) == 0);
    CHECK(memcmp(&o.camera.target, &s.cam.target, sizeof(vec3)) == 0);
    CHECK(memcmp(&o.camera.up, &s.cam.up, sizeof(vec3)) == 0);
    CHECK(o.camera.fov_deg == s.cam.fov_deg && o.camera.near == s.cam.near &&
          o.camera.far == s.cam.far);
    CHECK(o.render.shade == SHADE_FLAT && !o.render.textures);
    CHECK(o.render.filter == s.ro.filter && o.render.cull == s.ro.cull &&
          o.render.view == s.ro.view);
    CHECK(o.render.raster == RASTER_TILED && o.render.persp == s.ro.persp &&
          o.render.depth == s.ro.depth && s.ro.persp != PERSP_CORRECT);
    CHECK(o.render.lod == LOD_AUTO && o.render.lod_px == s.ro.lod_px);
    CHECK(o.render.wire == WIRE_OUTLINE);
    CHECK(o.light_camera && o.sky_procedural && o.background_set);
    CHECK(o.width == 160 && o.height == 94);
    CHECK(strcmp(o.out, "rastty-001.png") == 0);
    CHECK(o.model.up == MODEL_UP_X); /* the u key's turn */
}

TEST(u_turns_the_model_to_its_next_axis)
{
    struct view_state s;
    start(&s, true);
    CHECK_EQ_INT(view_key(&s, IN_TURN_UP, 1), VIEW_TURN_UP);
    CHECK(!s.spin); /* a camera key: the framing changes */
}

/* issue 25: what a new user's status line says about a small untextured model, and "?: help"
 * at every width a line of essentials fits */
TEST(the_status_line_tells_an_untextured_model_and_keeps_the_help_key)
{
    struct view_state s;
    start(&s, false);
    struct frame_stats st = {.tris_in = 36, .tris_full = 36, .lod_min = 0, .lod_max = 0};
    struct view_hud_info in = {.scene = "cube.obj", .n_scenes = 1, .mode = PALETTE_TRUECOLOR,
                               .fps = 30, .st = &st};
    char line[512];
    view_hud_compose(&s, &in, 300, 0, line, sizeof line);
    CHECK(strncmp(line, " cube.obj [1/1] | phong | truecolor | 30 fps | ?: help |", 56) == 0);
    CHECK(!strstr(line, "trilinear"));     /* no texture: no filter */
    CHECK_STR_CONTAINS(line, " 36/36 |");   /* not 0.0k/0.0k */
    CHECK_STR_CONTAINS(line, "| untextured |");
    for (int w = 60; w <= 161; w++) {
        view_hud_compose(&s, &in, w, 0, line, sizeof line);
        CHECK_STR_CONTAINS(line, "?: help");
    }
    in.texture = "MTL"; /* textured: the filter is named */
    view_hud_compose(&s, &in, 300, 0, line, sizeof line);
    CHECK_STR_CONTAINS(line, "| textured trilinear |");
    if (t->failures)
        fprintf(stderr, "    \"%s\"\n", line);
}

/* issue 25: at 80x24 (a 80x23 picture) the help box lost its last three lines; every help
 * line now starts on the screen, and the box fits the picture */
TEST(the_help_fits_an_80x24_terminal)
{
    static const int sizes[][2] = {{80, 23}, {100, 29}, {200, 60}, {60, 20}};
    for (int k = 0; k < 4; k++) {
        struct view_hud_rect r = view_hud_help_rect(sizes[k][0], sizes[k][1]);
        CHECK(r.col + r.cols <= sizes[k][0] && r.row + r.rows <= sizes[k][1]);
        char all[8192] = "";
        for (int i = 0; i < r.rows; i++) {
            char row[512];
            view_hud_help_text(&r, i, row, sizeof row);
            CHECK((int)strlen(row) >= r.cols);
            row[r.cols] = '\0'; /* what the viewer writes: clipped to the box */
            strcat(all, row);
            strcat(all, "\n");
        }
        for (int i = 0; input_help_line(i); i++) { /* every key, at its line's start */
            char key[12];
            snprintf(key, sizeof key, "%.10s", input_help_line(i));
            CHECK_STR_CONTAINS(all, key);
        }
        CHECK_STR_CONTAINS(all, "q Esc      quit");
        if (t->failures) {
            fprintf(stderr, "    %dx%d:\n%s", sizes[k][0], sizes[k][1], all);
            return;
        }
    }
}

TEST(shift_c_cycles_the_model_files_cameras)
{
    struct view_state s;
    start(&s, true);
    CHECK_EQ_INT(input_command('C'), IN_NEXT_CAMERA);
    CHECK_EQ_INT(view_key(&s, IN_NEXT_CAMERA, 1), VIEW_NEXT_CAMERA);
    CHECK(!s.spin); /* a camera key: the view changes */
}

/* issue 25 item 8: vi's hjkl turn as the arrows do; so the help moved to ? (and F1) and the
 * light to b; H shows and hides the status line; the shifted arrows pan. No key has two
 * commands, and the help names them. */
TEST(hjkl_turn_as_the_arrows_and_the_keys_they_displaced_moved)
{
    CHECK_EQ_INT(input_command('h'), input_command(KEY_LEFT));
    CHECK_EQ_INT(input_command('j'), input_command(KEY_DOWN));
    CHECK_EQ_INT(input_command('k'), input_command(KEY_UP));
    CHECK_EQ_INT(input_command('l'), input_command(KEY_RIGHT));
    CHECK_EQ_INT(input_command('h'), IN_YAW_LEFT);
    CHECK_EQ_INT(input_command('?'), IN_HELP);
    CHECK_EQ_INT(input_command(KEY_F(1)), IN_HELP);
    CHECK_EQ_INT(input_command('b'), IN_LIGHT);
    CHECK_EQ_INT(input_command('H'), IN_HUD);
    CHECK_EQ_INT(input_command(KEY_SLEFT), IN_PAN_LEFT);
    CHECK_EQ_INT(input_command(KEY_SRIGHT), IN_PAN_RIGHT);
    CHECK_EQ_INT(input_command(KEY_SR), IN_PAN_UP);
    CHECK_EQ_INT(input_command(KEY_SF), IN_PAN_DOWN);
    bool hjkl = false, help = false, hud = false, pan = false, light = false;
    for (int i = 0; input_help_line(i); i++) {
        const char *l = input_help_line(i);
        hjkl |= strstr(l, "h j k l") != NULL;
        help |= strncmp(l, "? F1 ", 5) == 0;
        hud |= strncmp(l, "H ", 2) == 0 && strstr(l, "status line");
        pan |= strncmp(l, "S-arrows ", 9) == 0 && strstr(l, "pan");
        light |= strncmp(l, "b ", 2) == 0 && strstr(l, "light");
    }
    CHECK(hjkl && help && hud && pan && light);
    struct view_state s;
    start(&s, false);
    view_key(&s, IN_LIGHT, 1);
    CHECK_STR_CONTAINS(s.message, "(b: follows the camera)");
}

TEST(h_shift_hides_and_shows_the_status_line)
{
    struct view_state s;
    start(&s, true);
    CHECK(!s.hud_hidden);
    CHECK_EQ_INT(view_key(&s, IN_HUD, 1), VIEW_HUD_TOGGLED);
    CHECK(s.hud_hidden);
    CHECK(s.spin); /* not a camera key */
    CHECK_EQ_INT(view_key(&s, IN_HUD, 2), VIEW_HUD_TOGGLED);
    CHECK(!s.hud_hidden);
}

/* pan: eye and target move together, across the view (the picture's right and up), the
 * distance and the direction kept; a plain drag still orbits (the target stays) */
TEST(pan_keys_and_a_shift_or_middle_drag_move_eye_and_target_together)
{
    struct view_state s;
    start(&s, false);
    camera_turn(&s.cam, 30, 20, 1); /* a view that is not along an axis */
    struct camera c0 = s.cam;
    vec3 f = v3_norm(v3_sub(c0.target, c0.eye));
    vec3 r = v3_norm(v3_cross(f, c0.up)), u = v3_cross(r, f);
    view_key(&s, IN_PAN_RIGHT, 1);
    view_advance(&s, 1, 2);
    vec3 de = v3_sub(s.cam.eye, c0.eye), dt = v3_sub(s.cam.target, c0.target);
    CHECK(v3_len(de) > 0.01);
    CHECK_NEAR(v3_len(v3_sub(de, dt)), 0, 1e-9);
    CHECK_NEAR(v3_dot(v3_norm(de), r), 1, 1e-9); /* to the right */
    CHECK(!s.spin);
    start(&s, false);
    camera_turn(&s.cam, 30, 20, 1);
    view_key(&s, IN_PAN_UP, 1);
    view_advance(&s, 1, 2);
    de = v3_sub(s.cam.eye, c0.eye);
    CHECK_NEAR(v3_dot(v3_norm(de), u), 1, 1e-9); /* the picture's up, not the world's */
    CHECK_NEAR(v3_len(v3_sub(de, v3_sub(s.cam.target, c0.target))), 0, 1e-9);
    /* a shift-drag 10 columns right: the camera goes left, the model follows the mouse */
    for (int middle = 0; middle < 2; middle++) {
        start(&s, false);
        camera_turn(&s.cam, 30, 20, 1);
        s.rows = 24;
        struct tty_event ev = {.kind = TTY_MOUSE, .button = 1, .pressed = true, .mx = 10,
                               .my = 10, .pan = true};
        view_mouse(&s, &ev, 1);
        ev = (struct tty_event){.kind = TTY_MOUSE, .button = 0, .mx = 20, .my = 10,
                                .pan = !middle}; /* ncurses: no modifier on the motion */
        view_mouse(&s, &ev, 1.1);
        de = v3_sub(s.cam.eye, c0.eye);
        dt = v3_sub(s.cam.target, c0.target);
        CHECK_NEAR(v3_len(v3_sub(de, dt)), 0, 1e-9);
        CHECK(v3_dot(de, r) < 0);
        /* 10 columns of 24 rows at 1:2: 10/48 of the view's height at the target */
        double h = 2 * camera_distance(&c0) * tan(c0.fov_deg * M_PI / 360);
        CHECK_NEAR(v3_len(de), h * 10 * 0.5 / 24, 1e-9);
        CHECK(s.dirty && !s.spin);
    }
    start(&s, false);
    struct tty_event ev = {.kind = TTY_MOUSE, .button = 1, .pressed = true, .mx = 10, .my = 10};
    view_mouse(&s, &ev, 1);
    ev = (struct tty_event){.kind = TTY_MOUSE, .button = 0, .mx = 20, .my = 10};
    vec3 t0 = s.cam.target;
    view_mouse(&s, &ev, 1.1);
    CHECK_NEAR(v3_len(v3_sub(s.cam.target, t0)), 0, 1e-12); /* orbit: the target stays */
}
