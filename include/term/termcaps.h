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
 *     wezterm, foot, st, ...), xterm says it is patch 331 or later (XTERM_VERSION, with a
 *     TERM starting with xterm), or the terminal handles 256 colours (rule 7) and the environment
 *     has TERM_PROGRAM (iTerm.app, WezTerm, vscode, ghostty, ...), LC_TERMINAL=iTerm2,
 *     KITTY_WINDOW_ID, WEZTERM_PANE, ALACRITTY_*, KONSOLE_VERSION, VTE_VERSION >= 3600,
 *     WT_SESSION, TERMINAL_EMULATOR=JetBrains-JediTerm or GHOSTTY_RESOURCES_DIR -> truecolor.
 *     This catches truecolor terminals seen through tmux (TERM=tmux-256color/screen, COLORTERM
 *     lost when the client attached from elsewhere) or ssh (LC_* is forwarded, COLORTERM is
 *     not). Never inside GNU screen (STY set, no TMUX): screen 4 cannot pass 24-bit colour.
 *  7. TERM contains "256color", terminfo colors >= 256, inside tmux (TMUX set: tmux parses
 *     38;5 itself whatever TERM says), or an older xterm (XTERM_VERSION: 256 colours since
 *     patch 111; its default TERM=xterm says 8)          -> 256
 *  8. terminfo known and colors < 8 (vt100, ...)           -> none
 *  9. otherwise (linux, xterm, screen, unknown entries)    -> 16
 * 16 colours are a last resort: they match only xterm's and st's default palettes (a theme
 * changes them), so every rule that can show 256 is there is tried first.
 *
 * Asking the terminal itself (the viewer, when the environment says 256 or 16 and no
 * --colors, RASTTY_COLORS or config file decided): inside tmux, tmux's own record of the
 * attached client, #{client_termfeatures}, says whether it passes 24-bit colour on (RGB);
 * with no client attached, or elsewhere (ssh does not forward COLORTERM), TERMCAPS_QUERY goes
 * to the terminal followed by TTY_PROBE (DSR, CPR, DA1), whose answers end the wait
 * (tty_query, short timeout):
 *   XTVERSION  ESC[>0q            -> DCS >|NAME ST: tmux (which converts 24-bit colour for a
 *                                    client that lacks it), XTerm(N >= 331), kitty,
 *                                    WezTerm, foot, contour, iTerm2, ghostty -> truecolor
 *   DECRQSS    set 48;2;1;2;3, ask DCS $q m ST -> DCS 1$r ... 48:2::1:2:3 m ST: the colour
 *                                    came back as RGB -> truecolor
 *   XTGETTCAP  DCS +q 524742 ST   -> DCS 1+r 524742 ST: terminfo RGB is set -> truecolor
 * Terminals that answer none of these (urxvt, whose 24-bit colour is only approximated;
 * GNU screen) keep the environment's answer. */
#ifndef RASTTY_TERMCAPS_H
#define RASTTY_TERMCAPS_H

#include <stdbool.h>
#include <stddef.h>

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

#define TERMCAPS_QUERY "\033[>0q\033[48;2;1;2;3m\033P$qm\033\\\033[0m\033P+q524742\033\\"
/* XTWINOPS 16: the cell's size in pixels, asked with the start's probe when TIOCGWINSZ's
 * pixel fields are zero (ssh, many terminals). */
#define TERMCAPS_CELL_QUERY "\033[16t"
/* The answer ESC[6;H;Wt in reply (NUL-terminated): 0 with the cell's height and width in
 * pixels, or -1 when there is none (or a zero). Pure. */
int termcaps_cell_pixels(const char *reply, int *h_out, int *w_out);
/* The mode the terminal's answers to TERMCAPS_QUERY (reply, NUL-terminated) say, given the
 * environment's answer env: truecolor if one of them says so, else env. why_out as above. */
enum palette_mode termcaps_from_reply(enum palette_mode env, const char *reply,
                                      const char **why_out);
/* tmux's #{client_termfeatures} for the attached client ("256,RGB,title,..."): 1 if it has
 * RGB, 0 if not, -1 if there is no client (empty). */
int termcaps_tmux_rgb(const char *features);
/* Runs `tmux display-message -p '#{client_termfeatures}'` (the server from $TMUX) into out;
 * 0, or -1 (not in tmux, no tmux, no answer within a second). */
int termcaps_tmux_features(char *out, size_t n);

#endif
