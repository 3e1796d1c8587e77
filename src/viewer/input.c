/* input.c: the key table (see input.h). */
#include "input.h"

#include <curses.h>

static const struct input_binding bindings[] = {
    {'w', IN_FORWARD},     {'W', IN_FORWARD},    {'s', IN_BACK},
    {'a', IN_LEFT},        {'A', IN_LEFT},       {'d', IN_RIGHT},       {'D', IN_RIGHT},
    {'Q', IN_DOWN},        {'z', IN_DOWN},       {'Z', IN_DEPTH},       {'e', IN_UP},
    {'E', IN_UP},          {'x', IN_UP},         {'X', IN_UP},          {KEY_LEFT, IN_YAW_LEFT},
    {KEY_RIGHT, IN_YAW_RIGHT}, {KEY_UP, IN_PITCH_UP}, {KEY_DOWN, IN_PITCH_DOWN},
    {'h', IN_YAW_LEFT},    {'l', IN_YAW_RIGHT},  {'k', IN_PITCH_UP},    {'j', IN_PITCH_DOWN},
    {KEY_SLEFT, IN_PAN_LEFT}, {KEY_SRIGHT, IN_PAN_RIGHT}, {KEY_SR, IN_PAN_UP},
    {KEY_SF, IN_PAN_DOWN},
    {'o', IN_ORBIT},       {'+', IN_FOV_IN},     {'=', IN_FOV_IN},      {'-', IN_FOV_OUT},
    {'[', IN_SLOWER},      {']', IN_FASTER},     {'r', IN_RESET},       {'\t', IN_NEXT_SCENE},
    {KEY_BTAB, IN_PREV_SCENE}, {'m', IN_SHADE},  {'f', IN_FILTER},      {'c', IN_CULL},
    {'b', IN_LIGHT},       {'v', IN_VIEW},       {'p', IN_PERSPECTIVE}, {' ', IN_PAUSE},
    {'R', IN_RASTER},      {'i', IN_INFO},       {'S', IN_SCREENSHOT},  {'L', IN_LOD},
    {'g', IN_GLYPHS},      {'u', IN_TURN_UP},    {'C', IN_NEXT_CAMERA}, {'H', IN_HUD},
    {'?', IN_HELP},        {KEY_F(1), IN_HELP},  {'q', IN_QUIT},        {27, IN_QUIT},
};

static const char *const help[] = {
    "w s        forward / back (orbit: zoom)",
    "a d        strafe left / right",
    "Q e / z x  down / up",
    "arrows     turn (yaw, pitch); h j k l too",
    "S-arrows   pan: the view slides (eye and target)",
    "mouse      drag: orbit, wheel: zoom, S-/middle-drag: pan",
    "o          orbit around target / fly",
    "+ -        narrower / wider field of view",
    "[ ]        slower / faster movement",
    "r          reset camera",
    "u          turn the model: its next axis up (y z x)",
    "C          the model file's cameras, then rastty's framing",
    "Tab S-Tab  next / previous scene",
    "m          shading: wire flat gouraud phong textured",
    "f          texture filter nearest / bilinear / trilinear",
    "c          culling none / back / front / auto (as the model says)",
    "b          light: follows the camera / fixed in the world",
    "v          view: colour depth normals overdraw wireframe",
    "R          rasterizer: edge scanline tiled",
    "p          interpolation: correct affine span8 span16 span32",
    "Z          depth buffer: z w z16 rz",
    "L          mesh level of detail: auto / off",
    "g          glyphs: half quadrant sextant braille ascii",
    "Space      pause / resume the auto-rotation",
    "i          camera position in the status line",
    "H          status line: hide / show",
    "S          screenshot: PNG + ANSI, and the render command",
    "? F1       this help (q Esc close it)",
    "q Esc      quit",
    0,
};

enum input_cmd input_command(int key)
{
    for (unsigned i = 0; i < sizeof bindings / sizeof bindings[0]; i++)
        if (bindings[i].key == key)
            return bindings[i].cmd;
    return IN_NONE;
}

const char *input_help_line(int i)
{
    return i >= 0 && i < (int)(sizeof help / sizeof help[0]) ? help[i] : 0;
}
