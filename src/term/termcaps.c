/* termcaps.c: colour-mode detection (see termcaps.h for the rules). */
#include "termcaps.h"

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/select.h>
#include <sys/wait.h>
#include <unistd.h>

#include <curses.h>
#include <term.h>

#include "timing.h"
#include "workers.h"

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
    if (strcmp(term, "st") == 0 || str_starts(term, "st-")) /* suckless st: 24-bit */
        return "TERM";
    return NULL;
}

/* xterm's patch level from XTERM_VERSION ("XTerm(379)"), 0 if none. */
static int xterm_patch(const char *const *envp)
{
    const char *v = env_get(envp, "XTERM_VERSION");
    const char *p = v ? strchr(v, '(') : NULL;
    return p ? atoi(p + 1) : 0;
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

    /* xterm sets XTERM_VERSION; its default TERM=xterm claims 8 colours: 24-bit colour since
     * patch 331, 256 since patch 111 */
    int xterm = str_starts(term, "xterm") && !in_screen ? xterm_patch(envp) : 0;
    if (xterm >= 331 && !in_tmux)
        return decide(why, "XTERM_VERSION (patch 331+)", PALETTE_TRUECOLOR);
    bool has_256 = strstr(term, "256color") || ti->colors >= 256 || in_tmux || xterm > 0;
    const char *hint = truecolor_hint(envp, term);
    if (hint && (has_256 || strcmp(hint, "TERM") == 0) && !in_screen)
        return decide(why, "known truecolor terminal", PALETTE_TRUECOLOR);
    if (has_256)
        return decide(why, in_tmux ? "inside tmux" : "256 colours", PALETTE_256);
    if (ti->found && ti->colors < 8)
        return decide(why, "terminfo: fewer than 8 colours", PALETTE_NONE);
    return decide(why, "colour terminal", PALETTE_16);
}

static int terminfo_read(const char *term, struct termcaps_terminfo *ti_out)
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

struct terminfo_job {
    const char *term;
    struct termcaps_terminfo *ti;
    int rc;
};

static void terminfo_job(void *p)
{
    struct terminfo_job *j = p;
    j->rc = terminfo_read(j->term, j->ti);
}

int termcaps_terminfo(const char *term, struct termcaps_terminfo *ti_out)
{
    /* libtinfo reads the entry into a 32 KiB buffer on its stack: on a stack of its own */
    struct terminfo_job j = {term, ti_out, -1};
    workers_call(terminfo_job, &j);
    return j.rc;
}

enum palette_mode termcaps_detect_env(const char **why_out)
{
    struct termcaps_terminfo ti;
    termcaps_terminfo(getenv("TERM"), &ti);
    return termcaps_detect((const char *const *)environ, &ti, why_out);
}

/* Terminals whose XTVERSION name means 24-bit colour. */
static const char *const TRUECOLOR_NAMES[] = {"tmux", "kitty", "WezTerm", "foot", "contour",
                                              "iTerm2", "ghostty", "mintty", "Konsole"};

/* The body of the next DCS string (ESC P ... ESC \) in *p, NUL-terminated into out; advances
 * *p past it. 0 when there is none. */
static int next_dcs(const char **p, char *out, size_t n)
{
    const char *s = strstr(*p, "\033P");
    if (!s)
        return 0;
    s += 2;
    const char *e = strstr(s, "\033\\");
    size_t len = e ? (size_t)(e - s) : strlen(s);
    len = len < n - 1 ? len : n - 1;
    memcpy(out, s, len);
    out[len] = '\0';
    *p = e ? e + 2 : s + strlen(s);
    return 1;
}

enum palette_mode termcaps_from_reply(enum palette_mode env, const char *reply,
                                      const char **why_out)
{
    const char *why_dummy;
    const char **why = why_out ? why_out : &why_dummy;
    char d[256];
    for (const char *p = reply; next_dcs(&p, d, sizeof d);) {
        if (d[0] == '>' && d[1] == '|') { /* XTVERSION: ">|name(version)" or ">|name version" */
            for (size_t i = 0; i < sizeof TRUECOLOR_NAMES / sizeof TRUECOLOR_NAMES[0]; i++)
                if (str_starts(d + 2, TRUECOLOR_NAMES[i]))
                    return decide(why, "XTVERSION names a truecolor terminal", PALETTE_TRUECOLOR);
            if (str_starts(d + 2, "XTerm(") && atoi(d + 8) >= 331)
                return decide(why, "XTVERSION: xterm patch 331+", PALETTE_TRUECOLOR);
        } else if (str_starts(d, "1$r")) { /* DECRQSS: our colour, as the terminal keeps it */
            if (strstr(d, "48:2::1:2:3") || strstr(d, "48:2:1:2:3") || strstr(d, "48;2;1;2;3"))
                return decide(why, "DECRQSS: the terminal keeps 24-bit colour", PALETTE_TRUECOLOR);
        } else if (str_starts(d, "1+r524742")) { /* XTGETTCAP: RGB is known */
            return decide(why, "XTGETTCAP: RGB", PALETTE_TRUECOLOR);
        }
    }
    *why = "no terminal answer said truecolor";
    return env;
}

int termcaps_tmux_rgb(const char *features)
{
    if (!features || !*features)
        return -1;
    char buf[512];
    snprintf(buf, sizeof buf, ",%s,", features);
    buf[strcspn(buf, "\n")] = '\0';
    return strstr(buf, ",RGB,") != NULL;
}

int termcaps_tmux_features(char *out, size_t n)
{
    if (n)
        out[0] = '\0';
    if (!getenv("TMUX") || !*getenv("TMUX") || n < 2)
        return -1;
    int fd[2];
    if (pipe(fd))
        return -1;
    pid_t pid = fork();
    if (pid < 0) {
        close(fd[0]);
        close(fd[1]);
        return -1;
    }
    if (pid == 0) {
        int null = open("/dev/null", O_RDWR);
        dup2(fd[1], STDOUT_FILENO);
        if (null >= 0) {
            dup2(null, STDIN_FILENO);
            dup2(null, STDERR_FILENO);
        }
        execlp("tmux", "tmux", "display-message", "-p", "#{client_termfeatures}", (char *)NULL);
        _exit(127);
    }
    close(fd[1]);
    size_t len = 0;
    bool eof = false;
    double t0 = timing_now_ms();
    for (;;) {
        long left = 1000 - (long)(timing_now_ms() - t0);
        fd_set rd;
        FD_ZERO(&rd);
        FD_SET(fd[0], &rd);
        struct timeval tv = {left / 1000, (left % 1000) * 1000};
        if (left <= 0 || select(fd[0] + 1, &rd, NULL, NULL, &tv) <= 0)
            break;
        ssize_t r = read(fd[0], out + len, n - 1 - len);
        if (r < 0 && errno == EINTR)
            continue;
        if (r <= 0 || (len += (size_t)r) >= n - 1) {
            eof = r == 0;
            break;
        }
    }
    out[len] = '\0';
    close(fd[0]);
    int status;
    if (!eof) /* no answer within a second: do not wait for it */
        kill(pid, SIGKILL);
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR)
        ;
    if (!eof)
        return -1;
    out[strcspn(out, "\n")] = '\0';
    return WIFEXITED(status) && WEXITSTATUS(status) == 0 ? 0 : -1;
}

int termcaps_cell_pixels(const char *reply, int *h_out, int *w_out)
{
    for (const char *p = strstr(reply, "\033[6;"); p; p = strstr(p + 1, "\033[6;")) {
        const char *q = p + 4;
        long v[2];
        int k = 0;
        for (; k < 2; k++) {
            char *end;
            if (*q < '0' || *q > '9')
                break;
            v[k] = strtol(q, &end, 10);
            if (v[k] <= 0 || v[k] > 100000 || *end != (k == 0 ? ';' : 't'))
                break;
            q = end + 1;
        }
        if (k == 2) {
            *h_out = (int)v[0];
            *w_out = (int)v[1];
            return 0;
        }
    }
    return -1;
}
