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
    int button;          /* 1 = left; 4/5 = wheel up/down; 0 = motion */
    bool pressed, released;
};

struct tty {
    int cols, rows;
    bool mouse;          /* the terminal reports mouse events */
};

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
/* Was Ctrl-Z pressed? The caller first collects the answers to its outstanding requests
 * (so that none lands at the shell's prompt), then calls tty_suspend. */
bool tty_stop_requested(void);
/* If Ctrl-Z was pressed: restore the terminal, drop unread input, stop the process, and when
 * it is continued in the foreground (fg) take the terminal back. Continued in the background
 * (bg, kill -CONT) it stops again until brought to the foreground — or, if a quit signal came
 * (kill %1 sends SIGTERM and SIGCONT), returns at once leaving the terminal to the shell;
 * tty_close then does not touch it. Returns true when it stopped: the screen is blank and
 * must be drawn again. */
bool tty_suspend(struct tty *t);
/* Send req, then a DSR, and collect the terminal's answer until the DSR's (which every
 * terminal sends, after the answers to anything before it) or timeout_ms. Returns the number
 * of bytes that came before the DSR answer, in reply (NUL-terminated, at most cap - 1), or
 * -1 on a timeout, a write error or a quit signal. Only before the first tty_next_event
 * (ncurses must not have read ahead). */
int tty_query(const char *req, char *reply, size_t cap, int timeout_ms);
/* A request whose answer (TTY_SYNC_REPLY) tells the caller the terminal has processed
 * everything written before it: append it to a frame to count frames in flight. */
#define TTY_SYNC_REQUEST "\033[5n" /* DSR; the terminal answers ESC [ 0 n */
/* Has SIGINT/SIGTERM/SIGHUP/SIGQUIT arrived? Which one (0 = none)? */
bool tty_signalled(void);
int tty_quit_signal(void);

#endif
