/* input.h: keys -> viewer commands, from one constant table (also the source of the help
 * overlay and the man page's KEYS section, so they cannot disagree).
 *
 * Movement and turning commands are "held" commands: the viewer moves while a key keeps
 * repeating, scaled by elapsed time (see view_state.c). Lowercase q quits (or closes the
 * help); Shift-Q moves down. hjkl turn as the arrows do (vi's left, down, up, right), so
 * the help is ? (and F1) and the light b; H shows and hides the status line; the shifted
 * arrows pan. */
#ifndef RASTTY_INPUT_H
#define RASTTY_INPUT_H

enum input_cmd {
    IN_NONE,
    /* held: continuous while the key repeats */
    IN_FORWARD, IN_BACK, IN_LEFT, IN_RIGHT, IN_DOWN, IN_UP,
    IN_YAW_LEFT, IN_YAW_RIGHT, IN_PITCH_UP, IN_PITCH_DOWN,
    IN_PAN_LEFT, IN_PAN_RIGHT, IN_PAN_UP, IN_PAN_DOWN, /* eye and target together, in the view plane */
    IN_HELD_COUNT,
    /* one-shot */
    IN_ORBIT = IN_HELD_COUNT, IN_FOV_IN, IN_FOV_OUT, IN_SLOWER, IN_FASTER, IN_RESET,
    IN_NEXT_SCENE, IN_PREV_SCENE, IN_SHADE, IN_FILTER, IN_CULL, IN_LIGHT, IN_VIEW,
    IN_RASTER, IN_PERSPECTIVE, IN_DEPTH, IN_LOD, IN_GLYPHS, IN_PAUSE, IN_INFO, IN_SCREENSHOT,
    IN_TURN_UP, IN_NEXT_CAMERA, IN_HUD,
    IN_HELP,
    IN_QUIT,
    IN_COUNT
};

struct input_binding {
    int key;               /* ncurses key code */
    enum input_cmd cmd;
};

/* Command for a key, IN_NONE if unbound. */
enum input_cmd input_command(int key);
/* Help lines: "keys  description", one per command that has keys; NULL after the last. */
const char *input_help_line(int i);

#endif
