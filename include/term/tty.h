/* tty.h: the only code that touches the interactive terminal.
 *
 * Owns: terminal modes (through ncurses: cbreak, noecho, keypad, mouse), the alternate
 * screen, the hidden cursor, the signal handlers, and the file descriptor frames are written
 * to. ncurses is used for modes and input only — it never draws: frames are bytes from the
 * encoder, written here with one write() loop per frame.
 *
 * Restoring the terminal, on every exit path:
 *   normal exit, q/Esc      tty_close(): endwin() plus our own resets
 *   Ctrl-C, SIGTERM, SIGHUP tty_signalled() turns true; blocking input and blocked writes
 *                           return at once; the caller leaves its loop and calls
 *                           tty_close(), which first drops output the terminal never read
 *   Ctrl-Z, fg              the handler only sets a flag; the loop collects the answers it
 *                           waits for, then tty_suspend() restores the terminal, stops, and
 *                           takes it back on fg (in the background it stays stopped, and a
 *                           quit signal then ends it without touching the terminal)
 *   kill -STOP, kill -CONT  (SIGSTOP cannot be caught) SIGCONT sets a flag: continued in the
 *                           background, tty_suspend gives the terminal back as for Ctrl-Z
 *                           and stops until fg; continued in the foreground (fg), it takes
 *                           its modes and screen back (the shell may have set its own)
 *   crash signals           (SEGV, BUS, FPE, ILL, ABRT) an async-signal-safe handler restores
 *                           the saved termios with tcsetattr, writes fixed xterm reset bytes
 *                           (leave alternate screen, show cursor, mouse off, SGR reset), then
 *                           re-raises the signal with its default action. */
#ifndef RASTTY_TTY_H
#define RASTTY_TTY_H

#include <stdbool.h>
#include <stddef.h>

#include "err.h"

enum tty_event_kind { TTY_NONE, TTY_KEY, TTY_MOUSE, TTY_RESIZE, TTY_SYNC_REPLY };

struct tty_event {
    enum tty_event_kind kind;
    int key;             /* TTY_KEY: ncurses key code (KEY_UP, 'w', 27 = Esc, ...) */
    int mx, my;          /* TTY_MOUSE: cell position */
    int button;          /* 1 = left (or middle: pan); 4/5 = wheel up/down; 0 = motion */
    bool pressed, released;
    bool pan;            /* shift held (SGR +4, ncurses BUTTON_SHIFT) or the middle button */
};

/* The query whose answer marks a frame as arrived (see tty_query): the first of these the
 * terminal answers, or none. */
enum tty_sync {
    TTY_SYNC_NONE,       /* answers none of them: pace by time, ask nothing */
    TTY_SYNC_DSR,        /* ESC[5n -> ESC[0n          (xterm, VTE, kitty, tmux, ...) */
    TTY_SYNC_CPR,        /* ESC[6n -> ESC[row;colR    (st, and every VT100 descendant) */
    TTY_SYNC_DA1,        /* ESC[c  -> ESC[?...c       (every VT100 descendant) */
};

struct tty {
    int cols, rows;
    int px_w, px_h;      /* the window's size in pixels (TIOCGWINSZ), 0 when not told */
    bool mouse;          /* the terminal reports mouse events */
    enum tty_sync sync;  /* set by tty_query; TTY_SYNC_DSR until then */
};

/* After a model was read from standard input (`rastty -`): the keys come from the
 * controlling terminal, /dev/tty, put on descriptor 0 (as less does). 0 or -1 with a message. */
int tty_keys_from_terminal(struct err *e);
/* Fails (with a message) when stdin/stdout is not a terminal or TERM is unusable. */
int tty_open(struct tty *t, struct err *e);
void tty_close(struct tty *t);
/* Re-read the size after a resize event. */
void tty_refresh_size(struct tty *t);
/* Wait up to timeout_ms (-1 = forever) for one event; returns its kind (TTY_NONE on
 * timeout or when a quit signal arrived). */
enum tty_event_kind tty_next_event(struct tty *t, int timeout_ms, struct tty_event *ev);
/* Write all of buf to the terminal (retrying short writes); 0, or -1 on an error or when a
 * quit signal arrived meanwhile. */
int tty_write(const char *buf, size_t n);
/* Was Ctrl-Z pressed, or were we continued after a stop from outside? The caller first collects the answers to its outstanding requests
 * (so that none lands at the shell's prompt), then calls tty_suspend. */
bool tty_stop_requested(void);
/* If Ctrl-Z was pressed: restore the terminal, drop unread input, stop the process, and when
 * it is continued in the foreground (fg) take the terminal back. Continued in the background
 * (bg, kill -CONT) it stops again until brought to the foreground — or, if a quit signal came
 * (kill %1 sends SIGTERM and SIGCONT), returns at once leaving the terminal to the shell;
 * tty_close then does not touch it. Returns true when it stopped: the screen is blank and
 * must be drawn again. */
bool tty_suspend(struct tty *t);
/* Send req (may be ""), then TTY_PROBE (DSR, CPR, DA1, in that order), and collect the
 * terminal's answers until the DA1 answer (terminals answer in order, and every VT100
 * descendant answers DA1: after it nothing more will come) or timeout_ms. Sets t->sync to the
 * first of DSR, CPR, DA1 that was answered (TTY_SYNC_NONE if none was: one timeout, once).
 * Returns the number of bytes that came before the first of those answers, in reply
 * (NUL-terminated, at most cap - 1: the answers to req), or -1 when none came in time, on a
 * write error or a quit signal. Only before the first tty_next_event (ncurses must not have
 * read ahead). */
int tty_query(struct tty *t, const char *req, char *reply, size_t cap, int timeout_ms);
#define TTY_PROBE "\033[5n\033[6n\033[c"
/* What answers[0..n) says: the query to pace on (the first of DSR, CPR, DA1 answered) and in
 * *first_out the offset of the first of those answers (n if none). Pure. */
enum tty_sync tty_sync_from_answers(const char *answers, size_t n, size_t *first_out);
/* The kind of answer a CSI sequence is (the bytes after ESC [): "0n" DSR, "24;1R" CPR,
 * "?62;22c" DA1, else TTY_SYNC_NONE. Pure. */
enum tty_sync tty_sync_kind(const char *csi);
/* The request (NUL-terminated, in buf) whose answer (TTY_SYNC_REPLY) tells the caller the
 * terminal has processed everything written before it: append it to a frame to count frames
 * in flight. "" for a terminal that answers nothing. A CPR request first moves the cursor to
 * the last row (the answer ESC[rows;1R can then never read as a modified F3, ESC[1;xR). */
size_t tty_sync_request(const struct tty *t, char *buf, size_t cap);
#define TTY_SYNC_REQUEST_MAX 24
/* Has SIGINT/SIGTERM/SIGHUP/SIGQUIT arrived? Which one (0 = none)? */
bool tty_signalled(void);
int tty_quit_signal(void);

#endif
