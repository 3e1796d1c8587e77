/* termcaps.h: which colour mode the terminal understands, from the environment and terminfo.
 *
 * termcaps_detect is pure: it takes the environment as "NAME=value" strings and the terminfo
 * facts as a struct, so tests feed it tables. termcaps_detect_env is the thin wrapper that
 * reads `environ` and the terminfo database (without touching the terminal).
 * A --colors flag always wins; the caller applies it before calling us, and also when
 * NO_COLOR is set (NO_COLOR only changes the default, https://no-color.org).
 *
 * Rules, first match wins:
 *  1. NO_COLOR set and not empty                          -> none
 *  2. TERM unset, empty or "dumb"                         -> none
 *  3. COLORTERM is truecolor or 24bit                      -> truecolor
 *  4. TERM contains "-direct" (xterm-direct, ...)          -> truecolor
 *  5. terminfo RGB (ncurses) or Tc (tmux's extension)      -> truecolor
 *  6. a known truecolor terminal leaves a trace: TERM names one (xterm-kitty, alacritty,
 *     wezterm, foot, ...), or the terminal handles 256 colours (rule 7) and the environment
 *     has TERM_PROGRAM (iTerm.app, WezTerm, vscode, ghostty, ...), LC_TERMINAL=iTerm2,
 *     KITTY_WINDOW_ID, WEZTERM_PANE, ALACRITTY_*, KONSOLE_VERSION, VTE_VERSION >= 3600,
 *     WT_SESSION, TERMINAL_EMULATOR=JetBrains-JediTerm or GHOSTTY_RESOURCES_DIR -> truecolor.
 *     This catches truecolor terminals seen through tmux (TERM=tmux-256color/screen, COLORTERM
 *     lost when the client attached from elsewhere) or ssh (LC_* is forwarded, COLORTERM is
 *     not). Never inside GNU screen (STY set, no TMUX): screen 4 cannot pass 24-bit colour.
 *  7. TERM contains "256color", terminfo colors >= 256, or inside tmux (TMUX set: tmux parses
 *     38;5 itself whatever TERM says)                    -> 256
 *  8. terminfo known and colors < 8 (vt100, ...)           -> none
 *  9. otherwise (linux, xterm, screen, unknown entries)    -> 16 */
#ifndef RASTTY_TERMCAPS_H
#define RASTTY_TERMCAPS_H

#include <stdbool.h>

#include "palette.h"

struct termcaps_terminfo {
    bool found;  /* the terminfo entry for TERM exists */
    bool rgb;    /* RGB (boolean or number > 0) or Tc */
    int colors;  /* "colors", -1 when absent */
};

/* envp: NULL-terminated "NAME=value" strings (environ). ti may be NULL (no terminfo facts).
 * why_out (may be NULL) receives a constant string naming the rule that decided. */
enum palette_mode termcaps_detect(const char *const *envp, const struct termcaps_terminfo *ti,
                                  const char **why_out);

/* Look TERM up in terminfo via ncurses' setupterm on /dev/null: nothing is written to any
 * terminal and ncurses' current terminal is restored afterwards. Returns 0, or -1 (and
 * ti_out->found = false) when there is no entry. */
int termcaps_terminfo(const char *term, struct termcaps_terminfo *ti_out);

/* termcaps_detect(environ, terminfo for $TERM, why_out). */
enum palette_mode termcaps_detect_env(const char **why_out);

#endif
