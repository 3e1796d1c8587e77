/* tty.c: terminal modes, input events, frame writes, restore on every exit path (tty.h). */
#include "tty.h"

#include <curses.h>
#include <term.h>
#include <errno.h>
#include <sys/ioctl.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <poll.h>
#include <sys/select.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include "timing.h"
#include "workers.h"

/* The signal handlers' state. Signal handlers can only reach globals; these are the only
 * mutable globals in rastty, written before the handlers are installed (saved termios) or
 * only as sig_atomic_t flags. */
static struct termios saved_termios;
static volatile sig_atomic_t have_saved, quit_signal, stop_requested, continued;
static SCREEN *screen_handle;
/* The signals that end a wait (quit, Ctrl-Z, resize) are blocked between tty_open and
 * tty_close except while we wait for the terminal (ppoll) or write to it: a signal can then
 * never slip in between "check the flag" and "block in read()" and be lost until the next
 * key (the race a plain blocking getch has). unblocked is the mask to wait with. */
static sigset_t wait_signals, unblocked;
/* Keys are read from a 1x1 pad, never from stdscr: wgetch refreshes a touched window before
 * it reads (after a resize, stdscr is touched: ncurses would redraw the screen from inside
 * getch, and block there on a stalled terminal with no signal able to stop it). A pad is
 * never refreshed by wgetch, so ncurses draws only where we ask it to. */
static WINDOW *keys;
static bool released; /* the terminal was given back (suspended, continued in the background) */
/* the terminal has no alternate screen (TERM=linux, dumb): the last frame would stay on the
 * screen under the shell's prompt, so leaving clears it */
static bool no_alt_screen;
#define CLEAR_BYTES "\033[0m\033[H\033[2J"

/* ... and leave keypad-transmit mode (xterm rmkx: normal cursor keys, numeric keypad), which
 * keypad(stdscr, TRUE) entered: without it a shell after SIGABRT gets ESC O A for the arrows */
static const char RESET_BYTES[] = "\033[?2026l\033[0m\033[?1000l\033[?1002l\033[?1003l"
                                  "\033[?1006l\033[?25h\033[?1l\033>\033[?1049l";

/* ncurses asks for press/release reports only (?1000); ?1002 adds motion while a button is
 * held, so a drag orbits live instead of on release. ?1006 asks for SGR reports
 * (ESC [ < b ; x ; y M/m): unlike the X10 bytes ncurses decodes, they work past column 223
 * and cannot be mistaken for UTF-8. Terminals without 1006 keep sending X10 reports, which
 * ncurses decodes as before; SGR reports are decoded in after_escape(). */
#define MOUSE_ON "\033[?1002h\033[?1006h"
#define MOUSE_OFF "\033[?1006l\033[?1002l"

static void on_quit(int sig)
{
    quit_signal = sig;
}

/* Ctrl-Z: only note it. Installed without SA_RESTART (and before newterm, so ncurses keeps
 * out), it also interrupts the blocking read; the loop then calls tty_suspend(). */
static void on_stop(int sig)
{
    (void)sig;
    stop_requested = 1;
}

/* SIGCONT after a stop we did not ask for (kill -STOP, then kill -CONT or the shell's fg):
 * only note it; tty_suspend looks at where we are now. */
static void on_cont(int sig)
{
    (void)sig;
    continued = 1;
}

static void on_crash(int sig)
{
    if (have_saved)
        tcsetattr(STDIN_FILENO, TCSANOW, &saved_termios);
    ssize_t unused = write(STDOUT_FILENO, RESET_BYTES, sizeof RESET_BYTES - 1);
    (void)unused;
    signal(sig, SIG_DFL);
    raise(sig);
}

bool tty_signalled(void)
{
    return quit_signal != 0;
}

int tty_quit_signal(void)
{
    return (int)quit_signal;
}

static void install_handlers(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sigemptyset(&sa.sa_mask);
    sa.sa_handler = on_quit; /* no SA_RESTART: a blocking read returns with EINTR */
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    sigaction(SIGHUP, &sa, NULL);
    sigaction(SIGQUIT, &sa, NULL);
    sa.sa_handler = on_stop;
    sigaction(SIGTSTP, &sa, NULL);
    sa.sa_handler = on_cont;
    sigaction(SIGCONT, &sa, NULL);
    sa.sa_handler = on_crash;
    sa.sa_flags = SA_RESETHAND;
    static const int crash[] = {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT};
    for (unsigned i = 0; i < sizeof crash / sizeof crash[0]; i++)
        sigaction(crash[i], &sa, NULL);
    signal(SIGPIPE, SIG_IGN);
    sigemptyset(&wait_signals);
    static const int waits[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGTSTP, SIGWINCH, SIGCONT};
    for (unsigned i = 0; i < sizeof waits / sizeof waits[0]; i++)
        sigaddset(&wait_signals, waits[i]);
    sigprocmask(SIG_BLOCK, &wait_signals, &unblocked);
    sigdelset(&unblocked, SIGINT); /* in case the caller had them blocked: wait with them on */
    sigdelset(&unblocked, SIGTERM);
    sigdelset(&unblocked, SIGHUP);
    sigdelset(&unblocked, SIGQUIT);
    sigdelset(&unblocked, SIGTSTP);
    sigdelset(&unblocked, SIGWINCH);
    sigdelset(&unblocked, SIGCONT);
}

/* Wait up to timeout_ms (-1 = forever) for input on fd, with the wait signals deliverable
 * (pselect swaps the mask atomically): 1 ready, 0 timeout or a signal arrived (the caller
 * checks the flags). */
static int wait_input(int fd, int timeout_ms)
{
    fd_set rd;
    FD_ZERO(&rd);
    FD_SET(fd, &rd);
    struct timespec ts = {timeout_ms / 1000, (long)(timeout_ms % 1000) * 1000000L};
    int r = pselect(fd + 1, &rd, NULL, NULL, timeout_ms < 0 ? NULL : &ts, &unblocked);
    struct pollfd pfd = {.fd = fd, .events = POLLIN};
    if (r > 0 && poll(&pfd, 1, 0) < 0)
        pfd.revents = 0;
    /* the terminal went away (its emulator or tmux server killed) without a SIGHUP reaching
     * us (we were started from a shell): every read is an end of file, forever; leave as a
     * hangup would make us */
    if (r > 0 && (pfd.revents & (POLLHUP | POLLERR | POLLNVAL)) && !quit_signal)
        quit_signal = SIGHUP;
    /* pselect that finds input ready returns without delivering a signal that is pending
     * (Linux restores the mask first): a hung-up terminal is always "ready", so its SIGHUP
     * would wait forever. Let pending signals in now. */
    sigset_t pending;
    if (sigpending(&pending) == 0) {
        for (int s = 1; s < NSIG; s++)
            if (sigismember(&wait_signals, s) && sigismember(&pending, s)) {
                sigprocmask(SIG_SETMASK, &unblocked, NULL);
                sigprocmask(SIG_BLOCK, &wait_signals, NULL);
                break;
            }
    }
    return r > 0;
}

/* Write everything, ignoring signals: the restore sequences on the way out. */
static void write_restore(const char *buf, size_t n)
{
    while (n > 0) {
        ssize_t w = write(STDOUT_FILENO, buf, n);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0)
            return;
        buf += w;
        n -= (size_t)w;
    }
}

static bool foreground(void)
{
    return tcgetpgrp(STDIN_FILENO) == getpgrp();
}

static void open_screen(void *unused)
{
    (void)unused;
    screen_handle = newterm(NULL, stdout, stdin);
}

int tty_keys_from_terminal(struct err *e)
{
    if (isatty(STDIN_FILENO))
        return 0;
    int fd = open("/dev/tty", O_RDWR | O_NOCTTY | O_CLOEXEC);
    if (fd < 0)
        return err_set(e, "rastty: the model came on standard input, and there is no terminal "
                          "for the keys (/dev/tty: %s)", strerror(errno));
    int rc = dup2(fd, STDIN_FILENO) < 0 ? -1 : 0;
    if (rc)
        err_set(e, "rastty: /dev/tty: %s", strerror(errno));
    close(fd);
    clearerr(stdin);
    return rc;
}

int tty_open(struct tty *t, struct err *e)
{
    memset(t, 0, sizeof *t);
    t->sync = TTY_SYNC_DSR;
    released = false;
    if (!isatty(STDIN_FILENO) || !isatty(STDOUT_FILENO))
        return err_set(e, "rastty: the viewer needs a terminal on stdin and stdout "
                          "(use 'rastty render' or 'rastty dump' for files and pipes)");
    if (tcgetattr(STDIN_FILENO, &saved_termios) == 0)
        have_saved = 1;
    install_handlers();
    /* newterm reads the terminfo entry into a 32 KiB buffer on its stack: on a stack of its
     * own, so that a small `ulimit -s` (64 KiB) holds */
    workers_call(open_screen, NULL);
    if (!screen_handle)
        return err_set(e, "rastty: cannot use this terminal (TERM=%s)",
                       getenv("TERM") ? "set but unknown" : "unset");
    set_term(screen_handle);
    const char *smcup = tigetstr("smcup");
    no_alt_screen = smcup == NULL || smcup == (char *)-1 || !*smcup;
    cbreak();
    noecho();
    nonl();
    keys = newpad(1, 1);
    if (!keys)
        return err_set(e, "rastty: out of memory");
    keypad(keys, TRUE);
    set_escdelay(25);
    curs_set(0);
    refresh(); /* ncurses' one and only drawing: it clears the alternate screen */
    mmask_t want = BUTTON1_PRESSED | BUTTON1_RELEASED | BUTTON2_PRESSED | BUTTON2_RELEASED |
                   REPORT_MOUSE_POSITION | BUTTON4_PRESSED | BUTTON5_PRESSED | BUTTON_SHIFT;
    t->mouse = mousemask(want, NULL) != 0;
    mouseinterval(0);
    if (t->mouse)
        tty_write(MOUSE_ON, sizeof MOUSE_ON - 1);
    tty_refresh_size(t);
    return 0;
}

void tty_close(struct tty *t)
{
    if (released) {
        /* stopped with Ctrl-Z and then ended in the background: the terminal was restored
         * at the stop and belongs to the shell; touching it now would only stop us again
         * (SIGTTOU) */
        if (screen_handle) {
            delwin(keys);
            delscreen(screen_handle);
        }
        keys = NULL;
        screen_handle = NULL;
        sigprocmask(SIG_UNBLOCK, &wait_signals, NULL);
        return;
    }
    if (quit_signal) {
        /* the terminal may have stopped reading (a stalled link, Ctrl-S): drop the frame bytes
         * still queued and restart output, so the restore below cannot block forever.
         * tcflow(TCOON) only undoes TCOOFF; output a Ctrl-S (XOFF) stopped restarts when
         * XON/XOFF is turned off (Linux n_tty), and the saved modes turn it back on below */
        tcflush(STDOUT_FILENO, TCOFLUSH);
        tcflow(STDOUT_FILENO, TCOON);
        struct termios now;
        if (tcgetattr(STDOUT_FILENO, &now) == 0 && (now.c_iflag & IXON)) {
            now.c_iflag &= ~(tcflag_t)IXON;
            tcsetattr(STDOUT_FILENO, TCSANOW, &now);
        }
    }
    if (screen_handle) {
        if (t->mouse)
            write_restore(MOUSE_OFF, sizeof MOUSE_OFF - 1);
        mousemask(0, NULL);
        write_restore("\033[?2026l\033[0m", 12);
        if (no_alt_screen)
            write_restore(CLEAR_BYTES, sizeof CLEAR_BYTES - 1);
        curs_set(1);
        endwin();
        delwin(keys);
        keys = NULL;
        delscreen(screen_handle);
        screen_handle = NULL;
    }
    if (have_saved)
        tcsetattr(STDIN_FILENO, TCSANOW, &saved_termios);
    sigprocmask(SIG_UNBLOCK, &wait_signals, NULL);
}

void tty_refresh_size(struct tty *t)
{
    int r, c;
    getmaxyx(stdscr, r, c);
    t->rows = r;
    t->cols = c;
    struct winsize ws;
    t->px_w = t->px_h = 0;
    if (ioctl(STDOUT_FILENO, TIOCGWINSZ, &ws) == 0) {
        t->px_w = ws.ws_xpixel;
        t->px_h = ws.ws_ypixel;
    }
}

int tty_write(const char *buf, size_t n)
{
    /* a quit signal interrupts a blocked write (stalled link, Ctrl-S) as EINTR or as a short
     * count; either way stop writing, or the viewer could never be stopped. The signals are
     * let in only here and in waits (see wait_signals); a signal that lands between the
     * check and write() is noticed at the next short count or EINTR. */
    if (released)
        return -1;
    sigprocmask(SIG_SETMASK, &unblocked, NULL);
    while (n > 0 && !quit_signal) {
        ssize_t w = write(STDOUT_FILENO, buf, n);
        if (w < 0) {
            if (errno == EINTR)
                continue;
            break;
        }
        buf += w;
        n -= (size_t)w;
    }
    sigprocmask(SIG_BLOCK, &wait_signals, NULL);
    return n ? -1 : 0;
}

enum tty_sync tty_sync_kind(const char *csi)
{
    if (strcmp(csi, "0n") == 0)
        return TTY_SYNC_DSR;
    const char *p = csi;
    if (*p == '?') { /* DA1: ?digits;digits...c */
        for (p++; (*p >= '0' && *p <= '9') || *p == ';'; p++)
            ;
        return p > csi + 1 && p[0] == 'c' && p[1] == '\0' ? TTY_SYNC_DA1 : TTY_SYNC_NONE;
    }
    int fields = 0; /* CPR: digits;digitsR */
    while (*p >= '0' && *p <= '9') {
        const char *d = p;
        while (*p >= '0' && *p <= '9')
            p++;
        fields += p > d;
        if (*p != ';')
            break;
        p++;
    }
    return fields == 2 && p[0] == 'R' && p[1] == '\0' ? TTY_SYNC_CPR : TTY_SYNC_NONE;
}

/* Which of our answers a[0..n) holds (seen[kind]), and the offset of the first of them. */
static size_t scan_answers(const char *a, size_t n, bool seen[4])
{
    size_t first = n;
    for (size_t i = 0; i + 2 < n; i++) {
        if (a[i] != '\033' || a[i + 1] != '[')
            continue;
        char csi[32];
        size_t k = 0;
        for (size_t j = i + 2; j < n && k + 1 < sizeof csi; j++) {
            csi[k++] = a[j];
            if ((unsigned char)a[j] >= 0x40 && (unsigned char)a[j] <= 0x7e)
                break;
        }
        csi[k] = '\0';
        enum tty_sync kind = tty_sync_kind(csi);
        if (kind != TTY_SYNC_NONE) {
            seen[kind] = true;
            first = i < first ? i : first;
        }
    }
    return first;
}

enum tty_sync tty_sync_from_answers(const char *a, size_t n, size_t *first_out)
{
    bool seen[4] = {false};
    size_t first = scan_answers(a, n, seen);
    if (first_out)
        *first_out = first;
    return seen[TTY_SYNC_DSR] ? TTY_SYNC_DSR : seen[TTY_SYNC_CPR] ? TTY_SYNC_CPR
         : seen[TTY_SYNC_DA1] ? TTY_SYNC_DA1 : TTY_SYNC_NONE;
}

size_t tty_sync_request(const struct tty *t, char *buf, size_t cap)
{
    int k = 0;
    switch (t->sync) {
    case TTY_SYNC_DSR: k = snprintf(buf, cap, "\033[5n"); break;
    case TTY_SYNC_CPR:
        k = snprintf(buf, cap, "\033[%d;1H\033[6n", t->rows > 1 ? t->rows : 1);
        break;
    case TTY_SYNC_DA1: k = snprintf(buf, cap, "\033[c"); break;
    case TTY_SYNC_NONE: k = snprintf(buf, cap, "%s", ""); break;
    }
    return k > 0 && (size_t)k < cap ? (size_t)k : 0;
}

#define TTY_AFTER_DSR_MS 100 /* with DSR answered, the DA1 answer is awaited this long */

int tty_query(struct tty *t, const char *req, char *reply, size_t cap, int timeout_ms)
{
    size_t len = 0;
    reply[0] = '\0';
    t->sync = TTY_SYNC_NONE;
    if (tty_write(req, strlen(req)) || tty_write(TTY_PROBE, sizeof TTY_PROBE - 1))
        return -1;
    double t0 = timing_now_ms(), end = t0 + timeout_ms;
    for (;;) {
        int left = (int)(end - timing_now_ms());
        if (left <= 0 || quit_signal || !wait_input(STDIN_FILENO, left))
            break; /* what came in time is in reply */
        char buf[256];
        ssize_t n = read(STDIN_FILENO, buf, sizeof buf);
        if (n <= 0)
            continue;
        for (ssize_t i = 0; i < n; i++)
            if (len + 1 < cap)
                reply[len++] = buf[i];
        reply[len] = '\0';
        bool seen[4] = {false};
        scan_answers(reply, len, seen);
        if (seen[TTY_SYNC_DA1])
            break; /* the DA1 answer, the last: everything has come */
        if (seen[TTY_SYNC_DSR] && end > timing_now_ms() + TTY_AFTER_DSR_MS)
            end = timing_now_ms() + TTY_AFTER_DSR_MS; /* DSR is enough; DA1 may be missing */
    }
    size_t first;
    t->sync = tty_sync_from_answers(reply, len, &first);
    if (t->sync == TTY_SYNC_NONE)
        return -1;
    reply[first] = '\0';
    return (int)first;
}

bool tty_stop_requested(void)
{
    return stop_requested != 0 || continued != 0;
}

bool tty_suspend(struct tty *t)
{
    if (!stop_requested && !continued)
        return false;
    bool asked = stop_requested != 0;
    stop_requested = 0;
    continued = 0;
    /* leaving anyway (a hangup sends SIGHUP and SIGCONT together), or continued with no
     * terminal to go back to: never stop for a shell that is not there */
    if (quit_signal || (!asked && tcgetpgrp(STDIN_FILENO) < 0))
        return false;
    if (!asked && foreground()) {
        /* stopped from outside and continued in the foreground (the shell's fg, which may
         * have put its own modes on the terminal): our modes and screen again, repainted */
        endwin();
        goto back;
    }
    /* give the shell a normal terminal, drop input nobody read (typeahead: it would land at
     * the prompt), stop, and take the terminal back when continued in the foreground. Stopped
     * from outside and continued in the background (kill -STOP, kill -CONT): the shell has
     * its prompt on our screen; give the terminal back the same way, with SIGTTOU held off
     * (a background process may then still set the modes) */
    sigset_t ttou, before;
    sigemptyset(&ttou);
    sigaddset(&ttou, SIGTTOU);
    sigprocmask(SIG_BLOCK, &ttou, &before);
    if (t->mouse)
        write_restore(MOUSE_OFF, sizeof MOUSE_OFF - 1);
    write_restore("\033[0m", 4);
    if (no_alt_screen)
        write_restore(CLEAR_BYTES, sizeof CLEAR_BYTES - 1);
    endwin();
    if (asked)
        tcflush(STDIN_FILENO, TCIFLUSH);
    sigprocmask(SIG_SETMASK, &before, NULL);
    do {
        kill(getpid(), SIGSTOP);
        /* continued: in the background (bg, kill -CONT) the terminal is the shell's, and
         * using it would stop us again with SIGTTOU; wait to be brought to the foreground,
         * or leave at once on a quit signal without touching it */
        sigset_t pending;
        sigpending(&pending);
        if (sigismember(&pending, SIGINT) || sigismember(&pending, SIGTERM) ||
            sigismember(&pending, SIGHUP) || sigismember(&pending, SIGQUIT)) {
            sigprocmask(SIG_SETMASK, &unblocked, NULL); /* run the handler now */
            sigprocmask(SIG_BLOCK, &wait_signals, NULL);
        }
        if (quit_signal && !foreground()) {
            released = true;
            return true;
        }
    } while (!foreground());
back:;
    /* the SIGCONT of this fg is this very return: not another one to act on */
    sigset_t pending;
    if (sigpending(&pending) == 0 && sigismember(&pending, SIGCONT)) {
        sigprocmask(SIG_SETMASK, &unblocked, NULL);
        sigprocmask(SIG_BLOCK, &wait_signals, NULL);
    }
    continued = 0;
    /* continued (fg): ncurses re-enters its modes and the alternate screen, cleared */
    refresh();
    curs_set(0);
    if (t->mouse)
        tty_write(MOUSE_ON, sizeof MOUSE_ON - 1);
    tty_refresh_size(t);
    return true;
}

/* An SGR mouse report "<b;x;y" + M (press, motion) or m (release), coordinates from 1:
 * the same event ncurses would make of the X10 report. Other buttons: TTY_NONE. */
static enum tty_event_kind sgr_mouse(const char *seq, struct tty_event *ev)
{
    long v[3];
    const char *p = seq + 1;
    for (int i = 0; i < 3; i++) { /* strtol, not sscanf: out-of-range digits stay defined */
        char *end;
        if (*p < '0' || *p > '9')
            return TTY_NONE;
        v[i] = strtol(p, &end, 10);
        if (v[i] > 100000 || (i < 2 && *end != ';'))
            return TTY_NONE;
        p = i < 2 ? end + 1 : end;
    }
    char final = *p;
    int b = (int)v[0];
    if (v[1] < 1 || v[2] < 1 || (final != 'M' && final != 'm') || p[1] != '\0')
        return TTY_NONE;
    ev->mx = (int)v[1] - 1;
    ev->my = (int)v[2] - 1;
    /* +4 shift (+8 meta, +16 control: ignored); a middle-button drag pans as a shift-drag */
    ev->pan = (b & 4) != 0 || (!(b & 64) && (b & 3) == 1);
    if (b & 64) { /* wheel: 64 up, 65 down; no release */
        if ((b & 3) > 1 || final == 'm')
            return TTY_NONE;
        ev->button = (b & 1) ? 5 : 4;
        ev->pressed = true;
        ev->pan = false;
    } else if ((b & 3) > 1) { /* right; 3: a release without its button (X10 style) */
        return TTY_NONE;
    } else if (b & 32) { /* motion with the left or middle button held */
        ev->button = 0;
    } else {
        ev->button = 1;
        ev->pressed = final == 'M';
        ev->released = final == 'm';
    }
    ev->kind = TTY_MOUSE;
    return ev->kind;
}

/* After an ESC ncurses did not turn into a key: a lone ESC is the Esc key; ESC ESC is the
 * Esc key followed by another sequence; ESC [ ... is a CSI sequence (our DSR answer "0n", an
 * SGR mouse report, or a key this terminfo does not know: ignored); ESC O x an unknown SS3
 * key (ignored); ESC x is Alt+x (ignored, so Alt never quits). */
static enum tty_event_kind after_escape(struct tty *t, struct tty_event *ev)
{
    wtimeout(keys, 0);
    int c = wgetch(keys);
    if (c == ERR || c == 27) {
        /* ESC ESC: the Esc key, then another sequence that arrived within the escape delay
         * (typically the answer to our per-frame DSR); keep the second ESC for the next call */
        if (c == 27)
            ungetch(27);
        ev->kind = TTY_KEY;
        ev->key = 27;
        return ev->kind;
    }
    if (c == 'O') {
        wgetch(keys);
        return TTY_NONE;
    }
    if (c != '[')
        return TTY_NONE;
    char seq[32];
    size_t n = 0;
    for (;;) {
        c = wgetch(keys);
        if (c == ERR || n + 1 >= sizeof seq)
            break;
        seq[n++] = (char)c;
        if (c >= 0x40 && c <= 0x7e)
            break;
    }
    seq[n] = '\0';
    if (seq[0] == '<')
        return sgr_mouse(seq, ev);
    /* the answer to the frames' query; a terminal taken to answer nothing whose answer to
     * tty_query's probe comes late (a slow link) is paced on the first one that comes */
    enum tty_sync kind = tty_sync_kind(seq);
    if (kind != TTY_SYNC_NONE && t->sync == TTY_SYNC_NONE)
        t->sync = kind;
    ev->kind = kind != TTY_SYNC_NONE && kind == t->sync ? TTY_SYNC_REPLY : TTY_NONE;
    return ev->kind;
}

enum tty_event_kind tty_next_event(struct tty *t, int timeout_ms, struct tty_event *ev)
{
    memset(ev, 0, sizeof *ev);
    if (quit_signal)
        return TTY_NONE;
    /* ncurses may hold bytes it read ahead: ask it first, then wait on the descriptor with
     * the signals let in (ppoll), then read what came (ncurses still waits its escape delay
     * for the rest of a sequence) */
    wtimeout(keys, 0);
    int c = wgetch(keys);
    if (c == ERR && timeout_ms != 0) {
        wait_input(STDIN_FILENO, timeout_ms);
        if (!quit_signal) /* input, or a resize (SIGWINCH ends the wait: KEY_RESIZE) */
            c = wgetch(keys);
    }
    if (c == ERR)
        return TTY_NONE;
    if (c == KEY_RESIZE) {
        tty_refresh_size(t);
        ev->kind = TTY_RESIZE;
        return ev->kind;
    }
    if (c == 27)
        return after_escape(t, ev);
    if (c == KEY_MOUSE) {
        MEVENT m;
        if (getmouse(&m) != OK)
            return TTY_NONE;
        ev->kind = TTY_MOUSE;
        ev->mx = m.x;
        ev->my = m.y;
        mmask_t b1 = BUTTON1_PRESSED | BUTTON1_RELEASED, b2 = BUTTON2_PRESSED | BUTTON2_RELEASED;
        ev->pressed = (m.bstate & (BUTTON1_PRESSED | BUTTON2_PRESSED | BUTTON4_PRESSED |
                                   BUTTON5_PRESSED)) != 0;
        ev->released = (m.bstate & (BUTTON1_RELEASED | BUTTON2_RELEASED)) != 0;
        ev->button = (m.bstate & BUTTON4_PRESSED) ? 4 : (m.bstate & BUTTON5_PRESSED) ? 5
                     : (m.bstate & (b1 | b2)) ? 1 : 0;
        ev->pan = ev->button < 4 && (m.bstate & (BUTTON_SHIFT | b2)) != 0;
        return ev->kind;
    }
    ev->kind = TTY_KEY;
    ev->key = c;
    return ev->kind;
}
