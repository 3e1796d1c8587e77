/* test_termcaps.c: colour-mode detection from environment tables and terminfo facts. */
#include <string.h>

#include <curses.h>
#include <term.h>

#include "termcaps.h"
#include "test.h"

#define MAX_ENV 6

/* One row: the environment, the terminfo facts, the expected mode. */
struct row {
    const char *env[MAX_ENV];
    struct termcaps_terminfo ti;
    enum palette_mode want;
};

static const struct termcaps_terminfo TI_NONE = {false, false, -1};
static const struct termcaps_terminfo TI_8 = {true, false, 8};
static const struct termcaps_terminfo TI_256 = {true, false, 256};
static const struct termcaps_terminfo TI_RGB = {true, true, 256};
static const struct termcaps_terminfo TI_MONO = {true, false, -1};

TEST(detect_table_of_environments)
{
    static const struct row rows[] = {
        /* NO_COLOR (non-empty) beats everything; empty NO_COLOR is ignored */
        {{"TERM=xterm-256color", "COLORTERM=truecolor", "NO_COLOR=1"}, TI_RGB, PALETTE_NONE},
        {{"TERM=xterm-256color", "NO_COLOR="}, TI_256, PALETTE_256},
        /* no TERM, or dumb: none, whatever COLORTERM says */
        {{"COLORTERM=truecolor"}, TI_NONE, PALETTE_NONE},
        {{"TERM=dumb", "COLORTERM=truecolor"}, TI_MONO, PALETTE_NONE},
        {{"TERM="}, TI_NONE, PALETTE_NONE},
        /* COLORTERM */
        {{"TERM=xterm-256color", "COLORTERM=truecolor"}, TI_256, PALETTE_TRUECOLOR},
        {{"TERM=xterm", "COLORTERM=24bit"}, TI_8, PALETTE_TRUECOLOR},
        {{"TERM=xterm-256color", "COLORTERM=yes"}, TI_256, PALETTE_256},
        /* -direct entries and terminfo RGB/Tc */
        {{"TERM=xterm-direct"}, TI_NONE, PALETTE_TRUECOLOR},
        {{"TERM=konsole-direct"}, TI_NONE, PALETTE_TRUECOLOR},
        {{"TERM=tmux-256color"}, TI_RGB, PALETTE_TRUECOLOR},
        /* inside tmux (COLORTERM gone): outer-terminal traces */
        {{"TERM=tmux-256color", "TMUX=/tmp/tmux-0/default,1,0", "TERM_PROGRAM=tmux"}, TI_256,
         PALETTE_256},
        {{"TERM=screen", "TMUX=/tmp/t,1,0", "KITTY_WINDOW_ID=1"}, TI_8, PALETTE_TRUECOLOR},
        {{"TERM=tmux-256color", "TMUX=/tmp/t,1,0", "VTE_VERSION=6800"}, TI_256,
         PALETTE_TRUECOLOR},
        {{"TERM=tmux-256color", "TMUX=/tmp/t,1,0", "VTE_VERSION=3405"}, TI_256, PALETTE_256},
        {{"TERM=screen-256color", "TMUX=/tmp/t,1,0", "LC_TERMINAL=iTerm2"}, TI_256,
         PALETTE_TRUECOLOR},
        {{"TERM=tmux-256color", "TMUX=/tmp/t,1,0", "WT_SESSION=abc"}, TI_256, PALETTE_TRUECOLOR},
        {{"TERM=screen", "TMUX=/tmp/t,1,0"}, TI_8, PALETTE_256}, /* tmux parses 38;5 itself */
        /* GNU screen: no 24-bit even if the outer terminal could */
        {{"TERM=screen-256color", "STY=123.pts-0", "KITTY_WINDOW_ID=1"}, TI_256, PALETTE_256},
        /* ssh to a box whose TERM is xterm-256color, from iTerm2 (LC_* forwarded) */
        {{"TERM=xterm-256color", "LC_TERMINAL=iTerm2"}, TI_256, PALETTE_TRUECOLOR},
        {{"TERM=xterm-256color", "TERM_PROGRAM=Apple_Terminal"}, TI_256, PALETTE_256},
        {{"TERM=xterm-256color", "TERM_PROGRAM=vscode"}, TI_256, PALETTE_TRUECOLOR},
        /* a hint on a 16-colour TERM does not upgrade it, a truecolor TERM name does */
        {{"TERM=linux", "KITTY_WINDOW_ID=1"}, TI_8, PALETTE_16},
        {{"TERM=xterm-kitty"}, TI_NONE, PALETTE_TRUECOLOR},
        /* xterm says its patch level: 24-bit since 331, 256 colours before, even with its
         * default TERM=xterm (terminfo: 8); a stale XTERM_VERSION on a console changes nothing */
        {{"TERM=xterm", "XTERM_VERSION=XTerm(379)"}, TI_8, PALETTE_TRUECOLOR},
        {{"TERM=xterm", "XTERM_VERSION=XTerm(330)"}, TI_8, PALETTE_256},
        {{"TERM=linux", "XTERM_VERSION=XTerm(379)"}, TI_8, PALETTE_16},
        /* st: 24-bit; urxvt approximates 24-bit, so 256 (or 16 for its 88-colour entry) */
        {{"TERM=st-256color"}, TI_256, PALETTE_TRUECOLOR},
        {{"TERM=st"}, TI_8, PALETTE_TRUECOLOR},
        {{"TERM=rxvt-unicode-256color", "COLORTERM=rxvt-xpm"}, TI_256, PALETTE_256},
        {{"TERM=rxvt-unicode", "COLORTERM=rxvt-xpm"}, {true, false, 88}, PALETTE_16},
        /* fallbacks */
        {{"TERM=xterm-256color"}, TI_NONE, PALETTE_256},
        {{"TERM=rxvt-unicode"}, TI_256, PALETTE_256}, /* terminfo says 256 */
        {{"TERM=linux"}, TI_8, PALETTE_16},
        {{"TERM=xterm"}, TI_NONE, PALETTE_16}, /* no terminfo: assume a colour terminal */
        {{"TERM=vt100"}, TI_MONO, PALETTE_NONE},
    };
    for (size_t i = 0; i < sizeof rows / sizeof rows[0]; i++) {
        const char *why = NULL;
        enum palette_mode got = termcaps_detect(rows[i].env, &rows[i].ti, &why);
        if (got != rows[i].want)
            test_fail(t, __FILE__, __LINE__, "row %zu (%s, %s): got %s (%s), want %s", i,
                      rows[i].env[0] ? rows[i].env[0] : "-", rows[i].env[1] ? rows[i].env[1] : "-",
                      palette_mode_name(got), why ? why : "?", palette_mode_name(rows[i].want));
        CHECK(why != NULL);
    }
    /* NULL terminfo facts and NULL env are allowed */
    static const char *const env[] = {"TERM=xterm-256color", NULL};
    CHECK_EQ_INT(termcaps_detect(env, NULL, NULL), PALETTE_256);
    CHECK_EQ_INT(termcaps_detect(NULL, NULL, NULL), PALETTE_NONE);
}

TEST(terminfo_lookup_reads_rgb_and_colors_without_keeping_state)
{
    struct termcaps_terminfo ti;
    TERMINAL *before = cur_term;
    if (termcaps_terminfo("xterm-256color", &ti) != 0) {
        test_skip(t, "no terminfo entry for xterm-256color");
        return;
    }
    CHECK(ti.found);
    CHECK_EQ_INT(ti.colors, 256);
    CHECK(!ti.rgb);
    CHECK(cur_term == before); /* ncurses' current terminal restored */
    if (termcaps_terminfo("xterm-direct", &ti) == 0) { /* from ncurses-term */
        CHECK(ti.rgb);
        CHECK(ti.colors > 256);
    }
    CHECK(termcaps_terminfo("no-such-terminal-xyz", &ti) == -1);
    CHECK(!ti.found);
    CHECK(termcaps_terminfo("", &ti) == -1);
    CHECK(termcaps_terminfo(NULL, &ti) == -1);
    if (termcaps_terminfo("vt100", &ti) == 0)
        CHECK(ti.colors < 8);
    CHECK(cur_term == before);
}

TEST(terminal_answers_decide_truecolor)
{
    /* answers recorded from the terminals (tmux 3.3a verbatim; others as their docs show) */
    static const struct {
        const char *who, *reply;
        enum palette_mode want;
    } rows[] = {
        {"tmux", "\033P>|tmux 3.3a\033\\", PALETTE_TRUECOLOR},
        {"xterm 379", "\033P>|XTerm(379)\033\\\033P1$r0;48:2::1:2:3m\033\\", PALETTE_TRUECOLOR},
        {"xterm 330", "\033P>|XTerm(330)\033\\\033P1$r0;48;5;16m\033\\", PALETTE_256},
        {"DECRQSS only", "\033P1$r0;48;2;1;2;3m\033\\", PALETTE_TRUECOLOR},
        {"kitty", "\033P>|kitty(0.26.5)\033\\\033P1+r524742=38\033\\", PALETTE_TRUECOLOR},
        {"XTGETTCAP only", "\033P1+r524742\033\\", PALETTE_TRUECOLOR},
        {"XTGETTCAP: unknown", "\033P0+r524742\033\\", PALETTE_256},
        {"DECRQSS: invalid", "\033P0$r\033\\", PALETTE_256},
        {"urxvt, screen: nothing", "", PALETTE_256},
        {"garbage", "\033P>|", PALETTE_256},
        {"a key typed meanwhile", "x\033P>|foot(1.16)\033\\", PALETTE_TRUECOLOR},
    };
    for (size_t i = 0; i < sizeof rows / sizeof rows[0]; i++) {
        const char *why = NULL;
        enum palette_mode got = termcaps_from_reply(PALETTE_256, rows[i].reply, &why);
        if (got != rows[i].want)
            test_fail(t, __FILE__, __LINE__, "%s: got %s (%s)", rows[i].who,
                      palette_mode_name(got), why ? why : "?");
        CHECK(why != NULL);
    }
    CHECK_EQ_INT(termcaps_from_reply(PALETTE_16, "", NULL), PALETTE_16);
}

TEST(tmux_client_features_say_rgb_or_not)
{
    CHECK_EQ_INT(termcaps_tmux_rgb("256,bpaste,ccolour,clipboard,RGB,title\n"), 1);
    CHECK_EQ_INT(termcaps_tmux_rgb("RGB"), 1);
    CHECK_EQ_INT(termcaps_tmux_rgb("256,title,RGBX"), 0);
    CHECK_EQ_INT(termcaps_tmux_rgb(""), -1); /* no client attached */
    CHECK_EQ_INT(termcaps_tmux_rgb(NULL), -1);
}

/* issue 25 item 8: XTWINOPS 16's answer, the cell's pixels, among the probe's other answers */
TEST(the_cell_size_answer_is_found_among_the_others)
{
    int h = 0, w = 0;
    CHECK(termcaps_cell_pixels("\033[6;22;10t", &h, &w) == 0);
    CHECK_EQ_INT(h, 22);
    CHECK_EQ_INT(w, 10);
    /* after XTVERSION's answer and before DSR's: what tty_query hands over */
    CHECK(termcaps_cell_pixels("\033P>|XTerm(379)\033\\\033[6;17;8t\033[0n", &h, &w) == 0);
    CHECK(h == 17 && w == 8);
    /* not it: another XTWINOPS answer (4: the window's pixels; 8: its cells), a zero, cut */
    CHECK(termcaps_cell_pixels("\033[4;480;640t\033[8;24;80t", &h, &w) == -1);
    CHECK(termcaps_cell_pixels("\033[6;0;10t", &h, &w) == -1);
    CHECK(termcaps_cell_pixels("\033[6;22;10", &h, &w) == -1);
    CHECK(termcaps_cell_pixels("\033[6;22t", &h, &w) == -1);
    CHECK(termcaps_cell_pixels("", &h, &w) == -1);
    /* a first bad one does not hide a good one after it */
    CHECK(termcaps_cell_pixels("\033[6;x;1t\033[6;20;9t", &h, &w) == 0);
    CHECK(h == 20 && w == 9);
}
