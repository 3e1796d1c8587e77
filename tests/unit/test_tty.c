/* test_tty.c: which query a terminal answers (tty_query's decision, pure parts): DSR, CPR or
 * DA1, in that order of preference, from the answers to TTY_PROBE; and the frames' request. */
#include <string.h>

#include "test.h"
#include "tty.h"

TEST(the_probe_paces_on_the_first_query_the_terminal_answers)
{
    size_t first;
    /* xterm, tmux: all three answered */
    const char *all = "\033[0n\033[24;80R\033[?64;1;2;6;22c";
    CHECK_EQ_INT(tty_sync_from_answers(all, strlen(all), &first), TTY_SYNC_DSR);
    CHECK_EQ_INT((int)first, 0);
    /* st: no DSR; an XTVERSION-like answer to the colour queries before */
    const char *st = "\033P>|st\033\\\033[1;1R\033[?6c";
    CHECK_EQ_INT(tty_sync_from_answers(st, strlen(st), &first), TTY_SYNC_CPR);
    CHECK_EQ_INT((int)first, 8);
    /* DA1 alone */
    const char *da = "\033[?1;2c";
    CHECK_EQ_INT(tty_sync_from_answers(da, strlen(da), &first), TTY_SYNC_DA1);
    /* nothing, or something that is none of them (a key, a mouse report) */
    CHECK_EQ_INT(tty_sync_from_answers("", 0, &first), TTY_SYNC_NONE);
    CHECK_EQ_INT((int)first, 0);
    const char *keys = "q\033[A\033[<0;3;4M\033[1;5A";
    CHECK_EQ_INT(tty_sync_from_answers(keys, strlen(keys), &first), TTY_SYNC_NONE);
    CHECK_EQ_INT((int)first, (int)strlen(keys));
    /* a cut-off answer is none */
    CHECK_EQ_INT(tty_sync_from_answers("\033[24;8", 6, NULL), TTY_SYNC_NONE);
}

TEST(answers_are_told_from_keys)
{
    CHECK_EQ_INT(tty_sync_kind("0n"), TTY_SYNC_DSR);
    CHECK_EQ_INT(tty_sync_kind("24;1R"), TTY_SYNC_CPR);
    CHECK_EQ_INT(tty_sync_kind("?62;22c"), TTY_SYNC_DA1);
    CHECK_EQ_INT(tty_sync_kind("?6c"), TTY_SYNC_DA1);
    CHECK_EQ_INT(tty_sync_kind("3n"), TTY_SYNC_NONE);
    CHECK_EQ_INT(tty_sync_kind("R"), TTY_SYNC_NONE);
    CHECK_EQ_INT(tty_sync_kind("5R"), TTY_SYNC_NONE);
    CHECK_EQ_INT(tty_sync_kind("A"), TTY_SYNC_NONE);
    CHECK_EQ_INT(tty_sync_kind("2~"), TTY_SYNC_NONE);
    CHECK_EQ_INT(tty_sync_kind("<0;1;1M"), TTY_SYNC_NONE);
    CHECK_EQ_INT(tty_sync_kind("?c"), TTY_SYNC_NONE);
    CHECK_EQ_INT(tty_sync_kind("c"), TTY_SYNC_NONE); /* a DA1 request, not an answer */
}

TEST(the_frames_request_is_the_answered_query)
{
    struct tty tt = {.cols = 80, .rows = 24};
    char buf[TTY_SYNC_REQUEST_MAX];
    tt.sync = TTY_SYNC_DSR;
    tty_sync_request(&tt, buf, sizeof buf);
    CHECK(strcmp(buf, "\033[5n") == 0);
    tt.sync = TTY_SYNC_CPR; /* from the last row: ESC[24;1R, never a modified F3 (ESC[1;2R) */
    CHECK_EQ_INT((int)tty_sync_request(&tt, buf, sizeof buf), 11);
    CHECK(strcmp(buf, "\033[24;1H\033[6n") == 0);
    CHECK_EQ_INT(tty_sync_kind("24;1R"), TTY_SYNC_CPR);
    tt.sync = TTY_SYNC_DA1;
    tty_sync_request(&tt, buf, sizeof buf);
    CHECK(strcmp(buf, "\033[c") == 0);
    tt.sync = TTY_SYNC_NONE; /* nothing is answered: nothing is asked */
    CHECK_EQ_INT((int)tty_sync_request(&tt, buf, sizeof buf), 0);
}
