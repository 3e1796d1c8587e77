/* pace.h: when the viewer may send a frame, how many bytes it may take, and in which colour
 * mode — measured from the terminal's own answers, so it works at any link speed.
 *
 * Pure: the caller passes the time (seconds, monotonic) and reports what it sent and what
 * came back; tests drive it with a simulated link. Owned by the viewer loop (view.c).
 *
 * Measuring. Every frame ends with a query the terminal answers once it has processed
 * everything written before it (DSR ESC[5n, or CPR or DA1 for a terminal that does not answer
 * DSR, such as st: the one tty_query found answered at start, tty.h), so an answer marks the
 * frame as arrived. A terminal that answers none of them costs one timeout at start
 * (pace_no_answers), never one a frame. For a frame of n bytes whose write began at s and
 * that was answered at a (the time spent drawing and encoding it is not the link's):
 *   round trip  rtt  = a - s - n / rate, the least seen (slowly forgotten: +2% a sample):
 *                      the link's latency without the transfer. The viewer sends a bare DSR
 *                      (a 4-byte frame) first, which measures it before the rate is known.
 *   throughput  rate = n / (a - s - rtt) for frames of PACE_SAMPLE_MIN bytes or more whose
 *                      transfer is at least a fifth of the answer's time (and 2 ms), averaged
 *                      (EWMA, weight PACE_RATE_WEIGHT); a frame answered too fast to time
 *                      raises it to at least n / (a - s); capped by --bandwidth
 * Rules.
 *   - At most one frame in flight: the next frame goes out once the last is answered. A key
 *     press therefore waits for at most the rest of one frame, never a queue of them.
 *   - Pacing never switches itself off. An answer that does not come within PACE_LOST_S
 *     plus the frame's expected transfer time (at PACE_SLOWEST_RATE before the rate is
 *     known) counts the frame as lost and the next one goes out; the next answer, which may
 *     be the late one, ends the wait but is not taken as a sample; a terminal that has
 *     answered nothing after PACE_LOST_LIMIT frames, or that answered none of the queries
 *     at start (pace_no_answers), is taken not to answer at all: frames are then paced by
 *     time (bytes / rate, rate assumed PACE_BLIND_RATE or --bandwidth), with no queries;
 *     a local one by --fps alone (the pty's small buffer blocks a write it cannot take).
 *   - A local terminal (not over ssh, no --bandwidth): the answers time the terminal's own
 *     drawing, not a narrow link, so they only pace the frames (one in flight): no byte
 *     budget, no colour tolerance, no drop to 256 colours, nothing on the status line.
 *   - Frame period T = the frames' demand (encoder bytes without a budget, EWMA) / rate,
 *     between 1/fps and PACE_MAX_PERIOD: a picture that changes little runs at the full
 *     frame rate, a photo panning over a slow link drops to 12 fps rather than lag.
 *   - Byte budget for a frame = rate * T - PACE_OVERHEAD (status line, DSR): the encoder's
 *     rate-distortion choice spends it (encode.h, "Budget"), leaving the rest of the change
 *     for later frames, so the colour tolerance rises by itself when bytes are short.
 *     Before the first measurement: PACE_FIRST_BUDGET.
 *   - Colours: truecolor drops to 256 when the link carries fewer than PACE_256_BELOW
 *     bytes per cell in PACE_COLOUR_PERIOD (1/8 s), and comes back above PACE_256_ABOVE (hysteresis).
 *     make bench's curve: below ~0.3 byte/cell a frame, a 256-colour budgeted frame is as
 *     close to the picture as a truecolor one; above it truecolor wins.
 *   - --bandwidth RATE: rate <= RATE, and a frame of n bytes is followed by n / RATE s.
 *   - The budget is a wish, not a wall: the viewer spends more on a frame the budget would
 *     leave below its quality floor (view_frames.h), and the next frame waits for it. */
#ifndef RASTTY_PACE_H
#define RASTTY_PACE_H

#include <stdbool.h>
#include <stddef.h>

#include "palette.h"

#define PACE_MAX_PERIOD (1.0 / 12) /* s: never below 12 frames per second while changing:
                                    * a key waits for the rest of one frame at most */
#define PACE_COLOUR_PERIOD 0.125   /* s: the 256-colour rule counts bytes per cell in this */
#define PACE_FIRST_BUDGET 16000    /* bytes, before the link has been measured */
#define PACE_SLOWEST_RATE 8000.0   /* bytes/s assumed for deadlines before it has */
#define PACE_LOST_S 2.0            /* an answer later than this (+ transfer) is lost */
#define PACE_LOST_LIMIT 3          /* frames lost without any answer: no DSR support */
#define PACE_BLIND_RATE 32000.0    /* bytes/s assumed for a remote terminal that never
                                      * answers: 256 kbit/s, the slowest link make bench
                                      * tries (a faster one is only used less well) */
#define PACE_SAMPLE_MIN 512        /* frames from this size may measure the throughput */
#define PACE_RATE_WEIGHT 0.3
#define PACE_OVERHEAD 256          /* status line and DSR, outside the encoder's budget */
#define PACE_256_BELOW 0.30        /* bytes per cell per PACE_COLOUR_PERIOD */
#define PACE_256_ABOVE 0.45

struct pace {
    /* settings */
    double min_period;  /* 1 / --fps */
    double cap;         /* --bandwidth in bytes/s, 0 = none */
    bool local;         /* the terminal is on this machine (pace_init) */
    bool no_answers;    /* the terminal answered none of the start's queries */
    /* measured */
    double rate;        /* bytes/s, 0 = not measured yet */
    double rtt;         /* s, -1 = not measured yet */
    int answers;        /* answers received, ever */
    int lost;           /* frames counted lost, ever */
    /* the frame in flight */
    bool inflight;
    bool unsure;        /* a frame was given up on: its answer may still come */
    double sent_at, deadline;
    size_t sent_bytes;
    double next_at;     /* earliest time for the next frame (fps, --bandwidth, blind pacing) */
    /* decisions */
    double demand;      /* bytes a frame needs without a budget (EWMA), 0 = unknown */
    double period;      /* s */
    bool use_256;       /* truecolor dropped to 256 colours for the link */
};

/* local: the terminal is on this machine (no ssh); ignored with a cap. */
void pace_init(struct pace *p, double fps, double cap_bytes_s, bool local);
/* The terminal answers no query: pace by time from now on (until an answer comes). */
void pace_no_answers(struct pace *p);
/* The rate frames are sized for (measured, assumed or capped), bytes/s; 0 = not known yet
 * or a local terminal. */
double pace_rate(const struct pace *p);
/* May a frame go out at time t? If not, *wait_out (may be NULL) is how long until it may,
 * or until the answer in flight is given up (never negative). */
bool pace_ready(const struct pace *p, double t, double *wait_out);
/* Bytes the next frame may take (the encoder's budget); 0 = no budget (a local terminal). */
size_t pace_budget(const struct pace *p);
/* The colour mode to draw in: want, or 256 when want is truecolor and the link is slow. */
enum palette_mode pace_mode(const struct pace *p, enum palette_mode want);
/* A frame went out at t: total bytes written (DSR included) and the encoder's demand for
 * it; cells = cells on screen (for the colour rule). */
void pace_sent(struct pace *p, double t, size_t bytes, size_t demand, int cells);
/* A DSR answer arrived at t. */
void pace_answer(struct pace *p, double t);
/* Give up on an answer that is overdue at t (call once per loop turn). */
void pace_tick(struct pace *p, double t);
/* Forget the frame in flight (the terminal was reset: Ctrl-Z, resize). */
void pace_forget(struct pace *p);
/* For the status line, what the pacing does to the picture, e.g. "link 125KB/s: 8fps tol 14"
 * or "cap 50KB/s: 8fps 256c tol 30": the link's measured rate (or the cap, or "guess" for
 * PACE_BLIND_RATE when the terminal answers nothing), the frame rate if
 * lowered, 256c if the colours dropped, and max_err (the largest channel error the last frame
 * left, encode_stats) as the tolerance it came to. "" when the link keeps up. */
void pace_describe(const struct pace *p, int max_err, char *out, size_t n);

#endif
