/* termcaps.c: colour-mode detection (see termcaps.h for the rules). */
#include "termcaps.h"

#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

#include <curses.h>
#include <term.h>

extern char **environ;

/* Value of NAME in envp, or NULL; the first definition wins, as with glibc's getenv. */
static const char *env_get(const char *const *envp, const char *name)
{
    size_t n = strlen(name);
    for (; envp && *envp; envp++)
        if (strncmp(*envp, name, n) == 0 && (*envp)[n] == '=')
            return *envp + n + 1;
    return NULL;
}

static bool set_nonempty(const char *v)
{
    return v && *v;
}

static bool str_starts(const char *s, const char *prefix)
{
    return strncmp(s, prefix, strlen(prefix)) == 0;
}

/* Environment traces of terminals known to do 24-bit colour. NULL value = any non-empty. */
static const struct {
    const char *name, *value;
} TRUECOLOR_HINTS[] = {
    {"TERM_PROGRAM", "iTerm.app"},   {"TERM_PROGRAM", "WezTerm"},
    {"TERM_PROGRAM", "vscode"},      {"TERM_PROGRAM", "ghostty"},
    {"TERM_PROGRAM", "Hyper"},       {"TERM_PROGRAM", "Tabby"},
    {"LC_TERMINAL", "iTerm2"},       {"KITTY_WINDOW_ID", NULL},
    {"WEZTERM_PANE", NULL},          {"WEZTERM_EXECUTABLE", NULL},
    {"ALACRITTY_SOCKET", NULL},      {"ALACRITTY_WINDOW_ID", NULL},
    {"ALACRITTY_LOG", NULL},         {"KONSOLE_VERSION", NULL},
    {"WT_SESSION", NULL},            {"TERMINAL_EMULATOR", "JetBrains-JediTerm"},
    {"GHOSTTY_RESOURCES_DIR", NULL},
};

/* TERM values (prefixes) of terminals that do 24-bit colour. */
static const char *const TRUECOLOR_TERMS[] = {
    "xterm-kitty", "xterm-ghostty", "alacritty", "wezterm", "foot", "contour",
};

static const char *truecolor_hint(const char *const *envp, const char *term)
{
    for (size_t i = 0; i < sizeof TRUECOLOR_HINTS / sizeof TRUECOLOR_HINTS[0]; i++) {
        const char *v = env_get(envp, TRUECOLOR_HINTS[i].name);
        if (set_nonempty(v) && (!TRUECOLOR_HINTS[i].value || strcmp(v, TRUECOLOR_HINTS[i].value) == 0))
            return TRUECOLOR_HINTS[i].name;
    }
    /* VTE (GNOME Terminal, Tilix, ...) has 24-bit colour since 0.36, VTE_VERSION 3600. */
    const char *vte = env_get(envp, "VTE_VERSION");
    if (set_nonempty(vte) && atoi(vte) >= 3600)
        return "VTE_VERSION";
    for (size_t i = 0; i < sizeof TRUECOLOR_TERMS / sizeof TRUECOLOR_TERMS[0]; i++)
        if (str_starts(term, TRUECOLOR_TERMS[i]))
            return "TERM";
    return NULL;
}

static enum palette_mode decide(const char **why, const char *reason, enum palette_mode m)
{
    *why = reason;
    return m;
}

enum palette_mode termcaps_detect(const char *const *envp, const struct termcaps_terminfo *ti,
                                  const char **why_out)
{
    const char *why_dummy;
    const char **why = why_out ? why_out : &why_dummy;
    static const struct termcaps_terminfo none_known = {false, false, -1};
    if (!ti)
        ti = &none_known;

    const char *term = env_get(envp, "TERM");
    const char *colorterm = env_get(envp, "COLORTERM");
    bool in_tmux = set_nonempty(env_get(envp, "TMUX"));
    bool in_screen = !in_tmux && set_nonempty(env_get(envp, "STY"));

    if (set_nonempty(env_get(envp, "NO_COLOR")))
        return decide(why, "NO_COLOR is set", PALETTE_NONE);
    if (!set_nonempty(term) || strcmp(term, "dumb") == 0)
        return decide(why, "TERM is unset or dumb", PALETTE_NONE);
    if (colorterm && (strcasecmp(colorterm, "truecolor") == 0 || strcasecmp(colorterm, "24bit") == 0))
        return decide(why, "COLORTERM", PALETTE_TRUECOLOR);
    if (strstr(term, "-direct"))
        return decide(why, "TERM is a -direct entry", PALETTE_TRUECOLOR);
    if (ti->found && ti->rgb)
        return decide(why, "terminfo RGB/Tc", PALETTE_TRUECOLOR);

    bool has_256 = strstr(term, "256color") || ti->colors >= 256 || in_tmux;
    const char *hint = truecolor_hint(envp, term);
    if (hint && (has_256 || strcmp(hint, "TERM") == 0) && !in_screen)
        return decide(why, "known truecolor terminal", PALETTE_TRUECOLOR);
    if (has_256)
        return decide(why, in_tmux ? "inside tmux" : "256 colours", PALETTE_256);
    if (ti->found && ti->colors < 8)
        return decide(why, "terminfo: fewer than 8 colours", PALETTE_NONE);
    return decide(why, "colour terminal", PALETTE_16);
}

int termcaps_terminfo(const char *term, struct termcaps_terminfo *ti_out)
{
    *ti_out = (struct termcaps_terminfo){false, false, -1};
    if (!term || !*term)
        return -1;
    /* setupterm records the fd as the terminal's output; /dev/null makes certain that
     * nothing (not even a size query's side effects) reaches the user's terminal. With a
     * non-NULL errret it prints no diagnostics either. */
    int fd = open("/dev/null", O_WRONLY | O_CLOEXEC);
    if (fd < 0)
        return -1;
    TERMINAL *saved = cur_term;
    int errret = 0;
    int ok = setupterm((char *)term, fd, &errret) == OK && errret == 1;
    if (ok) {
        TERMINAL *mine = cur_term;
        int flag_rgb = tigetflag("RGB"), flag_tc = tigetflag("Tc"), num_rgb = tigetnum("RGB");
        const char *str_rgb = tigetstr("RGB");
        ti_out->found = true;
        ti_out->rgb = flag_rgb > 0 || flag_tc > 0 || num_rgb > 0 ||
                      (str_rgb && str_rgb != (const char *)-1);
        int colors = tigetnum("colors");
        ti_out->colors = colors >= 0 ? colors : -1;
        del_curterm(mine);
    }
    set_curterm(saved);
    close(fd);
    return ok ? 0 : -1;
}

enum palette_mode termcaps_detect_env(const char **why_out)
{
    struct termcaps_terminfo ti;
    termcaps_terminfo(getenv("TERM"), &ti);
    return termcaps_detect((const char *const *)environ, &ti, why_out);
}
