/* pace.c: frame pacing and adaptive quality from the terminal's answers (see pace.h). */
#include "pace.h"

#include <stdio.h>

void pace_init(struct pace *p, double fps, double cap_bytes_s, bool local)
{
    *p = (struct pace){0};
    p->local = local && !(cap_bytes_s > 0);
    p->min_period = fps > 0 ? 1.0 / fps : 0;
    p->cap = cap_bytes_s > 0 ? cap_bytes_s : 0;
    p->rtt = -1;
    p->period = p->min_period;
}

/* The rate frames are sized for: measured, capped; 0 = unknown. */
static bool is_blind(const struct pace *p)
{
    return p->no_answers || (p->answers == 0 && p->lost >= PACE_LOST_LIMIT);
}

void pace_no_answers(struct pace *p)
{
    p->no_answers = true;
    p->inflight = false;
}

static double link_rate(const struct pace *p)
{
    bool blind = is_blind(p);
    double r = blind ? PACE_BLIND_RATE : p->rate;
    if (p->cap > 0 && (r == 0 || r > p->cap))
        r = p->cap;
    return r;
}

double pace_rate(const struct pace *p)
{
    return p->local ? 0 : link_rate(p);
}

bool pace_ready(const struct pace *p, double t, double *wait_out)
{
    double wait = 0;
    if (p->inflight)
        wait = p->deadline - t;
    if (p->next_at - t > wait)
        wait = p->next_at - t;
    if (wait_out)
        *wait_out = wait > 0 ? wait : 0;
    return wait <= 0;
}

size_t pace_budget(const struct pace *p)
{
    if (p->local)
        return 0; /* the terminal's own speed, not a link's: every frame whole */
    double r = link_rate(p);
    if (r == 0)
        return PACE_FIRST_BUDGET;
    double b = r * p->period - PACE_OVERHEAD;
    return b < 1024 ? 1024 : (size_t)b;
}

enum palette_mode pace_mode(const struct pace *p, enum palette_mode want)
{
    return want == PALETTE_TRUECOLOR && p->use_256 && !p->local ? PALETTE_256 : want;
}

void pace_sent(struct pace *p, double t, size_t bytes, size_t demand, int cells)
{
    p->inflight = true;
    p->sent_at = t;
    p->sent_bytes = bytes;
    double r = link_rate(p);
    double transfer = (double)bytes / (r > 0 ? r : PACE_SLOWEST_RATE);
    p->deadline = t + PACE_LOST_S + transfer;
    p->next_at = t + p->min_period;
    if (p->cap > 0 && t + (double)bytes / p->cap > p->next_at)
        p->next_at = t + (double)bytes / p->cap;
    if (is_blind(p)) { /* nobody answers: the time the bytes take is all we have */
        p->inflight = false;
        /* a local terminal's pty holds a few KB: a write it cannot take blocks, which
         * paces by itself; over a link, the time the bytes take at the assumed rate */
        if (!p->local)
            p->next_at = t + (transfer > p->period ? transfer : p->period);
    }
    /* the frame period: what the frames need, at the link's rate, within [1/fps, max] */
    p->demand = p->demand > 0 ? 0.5 * p->demand + 0.5 * (double)demand : (double)demand;
    if (r > 0) {
        double period = p->demand / r;
        p->period = period < p->min_period ? p->min_period
                    : period > PACE_MAX_PERIOD ? PACE_MAX_PERIOD : period;
        double per_cell = r * PACE_COLOUR_PERIOD / (cells > 0 ? cells : 1);
        if (per_cell < PACE_256_BELOW)
            p->use_256 = true;
        else if (per_cell > PACE_256_ABOVE)
            p->use_256 = false;
    }
}

void pace_answer(struct pace *p, double t)
{
    p->answers++;
    p->no_answers = false; /* a late answer to the first query: pace on the answers */
    if (!p->inflight) /* the answer to a frame already given up on */
        return;
    p->inflight = false;
    if (p->unsure) { /* the first answer after a loss may be the lost frame's: no sample */
        p->unsure = false;
        return;
    }
    double took = t - p->sent_at, bytes = (double)p->sent_bytes;
    /* round trip: what the answer took beyond the transfer at the known rate (a min filter,
     * slowly forgetting so that a slower route is noticed) */
    double rtt = took - (p->rate > 0 ? bytes / p->rate : 0);
    rtt = rtt > 0 ? rtt : 0;
    double forgetful = p->rtt < 0 ? rtt : p->rtt * 1.02;
    p->rtt = rtt < forgetful ? rtt : forgetful;
    /* throughput, from frames whose transfer dominates the answer's time */
    double transfer = took - p->rtt;
    if (bytes >= PACE_SAMPLE_MIN && transfer >= 0.002 && transfer >= 0.2 * took) {
        double sample = bytes / transfer;
        p->rate = p->rate > 0 ? (1 - PACE_RATE_WEIGHT) * p->rate + PACE_RATE_WEIGHT * sample
                              : sample;
    } else if (bytes >= PACE_SAMPLE_MIN && took > 0 && bytes / took > p->rate) {
        p->rate = bytes / took; /* too fast to time: at least this fast */
    }
}

void pace_tick(struct pace *p, double t)
{
    if (p->inflight && t >= p->deadline) {
        p->inflight = false;
        p->unsure = true;
        p->lost++;
    }
}

void pace_forget(struct pace *p)
{
    p->inflight = false;
    p->unsure = false;
}

void pace_describe(const struct pace *p, int max_err, char *out, size_t n)
{
    double r = link_rate(p);
    bool slow_fps = p->period > p->min_period * 1.5;
    if (r == 0 || p->local || (!slow_fps && !p->use_256 && max_err == 0)) {
        if (n)
            out[0] = '\0';
        return;
    }
    int k = snprintf(out, n, "%s %.0fKB/s:", p->cap > 0 && r >= p->cap ? "cap"
                                             : is_blind(p) ? "guess" : "link", r / 1000);
    if (slow_fps && k >= 0 && (size_t)k < n)
        k += snprintf(out + k, n - (size_t)k, " %.0ffps", 1.0 / p->period);
    if (p->use_256 && k >= 0 && (size_t)k < n)
        k += snprintf(out + k, n - (size_t)k, " 256c");
    if (max_err > 0 && k >= 0 && (size_t)k < n)
        snprintf(out + k, n - (size_t)k, " tol %d", max_err);
}
