/* test_pace.c: pacing against a simulated link — one frame in flight, the link measured
 * from the answers, budgets and frame rate that keep a key press within about two frame
 * times, lost answers, a terminal that never answers, --bandwidth, the 256-colour rule. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "pace.h"
#include "test.h"

/* A link like ../shared/tools/slowlink.py behind an SSH hop: bytes leave at `rate` in
 * order, `latency` each way; the terminal answers a DSR when every byte before it arrived. */
struct link {
    double rate, latency;
    double free_at;              /* when the link has sent everything queued */
    double answer_at[4096];      /* per frame: when its answer is back (-1: never) */
    double first_byte_at[4096];  /* per frame: when its first byte reaches the terminal */
    int frames, max_queued;
    bool drop_answers;           /* the terminal never answers */
    int drop_one;                /* frame whose answer is lost (-1 none) */
};

static void link_send(struct link *l, double t, size_t bytes)
{
    double start = t > l->free_at ? t : l->free_at;
    /* frames still in the link when this one is written */
    int queued = 0;
    for (int k = 0; k < l->frames; k++)
        queued += l->answer_at[k] - l->latency > t;
    l->max_queued = queued > l->max_queued ? queued : l->max_queued;
    l->first_byte_at[l->frames] = start + l->latency;
    l->free_at = start + (double)bytes / l->rate;
    bool lost = l->drop_answers || l->frames == l->drop_one;
    l->answer_at[l->frames] = lost ? -1 : l->free_at + 2 * l->latency;
    l->frames++;
}

struct sim_result {
    double median_ms, worst_ms, bytes_per_s;
    int frames;
};

static int cmp_d(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Run `secs` of a viewer that always has a new picture (a spinning photo: each frame needs
 * `demand` bytes) and a key press every ~0.43 s: key -> the first byte of the next frame
 * (the status line goes first) reaching the terminal. */
static struct sim_result simulate(struct pace *p, struct link *l, double secs, size_t demand,
                                  int cells)
{
    double lat[512];
    int n_lat = 0, answered = 0;
    double next_key = 1.0, key_at = -1, bytes = 0;
    link_send(l, 0, 4); /* the viewer's first DSR, alone: the round trip */
    pace_sent(p, 0, 4, 0, cells);
    for (double t = 0; t < secs; t += 0.001) {
        while (answered < l->frames && (l->answer_at[answered] < 0 ||
                                        l->answer_at[answered] <= t)) {
            if (l->answer_at[answered] >= 0)
                pace_answer(p, l->answer_at[answered]);
            answered++;
        }
        pace_tick(p, t);
        if (key_at < 0 && t >= next_key) {
            key_at = t;
            next_key = t + 0.43;
        }
        if (pace_ready(p, t, NULL)) {
            size_t budget = pace_budget(p);
            size_t n = (budget && budget < demand ? budget : demand) + 100;
            if (key_at >= 0 && n_lat < 512 && t > 3) /* after the link is measured */
                lat[n_lat++] = (t - key_at + (l->free_at > t ? l->free_at - t : 0) + l->latency) * 1e3;
            key_at = -1;
            link_send(l, t, n);
            pace_sent(p, t, n, demand, cells);
            bytes += (double)n;
        }
        if (l->frames >= 4000)
            break;
    }
    struct sim_result r = {0, 0, bytes / secs, l->frames};
    if (n_lat) {
        qsort(lat, (size_t)n_lat, sizeof lat[0], cmp_d);
        r.median_ms = lat[n_lat / 2];
        r.worst_ms = lat[n_lat - 1];
    }
    return r;
}

TEST(one_frame_in_flight_and_keys_within_two_frames_on_slow_links)
{
    /* 1 Mbit/s (160x48 cells) and 4 Mbit/s (320x90), 20 ms each way, a photo that would
     * need 250 KB / 1 MB a frame: the targets, median <= 300 ms, worst <= 800 ms */
    static const struct { double rate; size_t demand; int cells; } links[] = {
        {128000, 250000, 160 * 48}, {512000, 1000000, 320 * 90}};
    for (int i = 0; i < 2; i++) {
        struct pace p;
        pace_init(&p, 60, 0, false);
        struct link l = {.rate = links[i].rate, .latency = 0.02, .drop_one = -1};
        struct sim_result r = simulate(&p, &l, 20, links[i].demand, links[i].cells);
        int failures = t->failures;
        CHECK(l.max_queued <= 1);
        CHECK(r.median_ms <= 300);
        CHECK(r.worst_ms <= 800);
        CHECK(fabs(p.rate - links[i].rate) < 0.25 * links[i].rate); /* rtt unknown: a bit low */
        CHECK(r.bytes_per_s > 0.6 * links[i].rate); /* and the link is used */
        CHECK_NEAR(p.period, PACE_MAX_PERIOD, 1e-9);
        CHECK(!p.use_256);
        if (t->failures > failures)
            fprintf(stderr, "    %.0f B/s: key -> screen median %.0f ms, worst %.0f ms; %.0f B/s; "
                            "rate estimate %.0f; period %.3f s\n",
                    links[i].rate, r.median_ms, r.worst_ms, r.bytes_per_s, p.rate, p.period);
    }
}

TEST(a_fast_link_runs_at_the_frame_rate_cap_with_no_budget_pressure)
{
    struct pace p;
    pace_init(&p, 60, 0, false);
    struct link l = {.rate = 50e6, .latency = 0.0005, .drop_one = -1};
    struct sim_result r = simulate(&p, &l, 5, 100000, 160 * 48);
    CHECK_NEAR(p.period, 1.0 / 60, 1e-9);
    CHECK(pace_budget(&p) > 100000); /* the whole frame fits */
    CHECK(r.frames > 5 * 55 && r.frames <= 5 * 60 + 1);
    char hud[64];
    pace_describe(&p, 0, hud, sizeof hud);
    CHECK_EQ_INT(hud[0], '\0'); /* nothing degraded: nothing to say */
}

TEST(a_lost_answer_does_not_stop_pacing)
{
    struct pace p;
    pace_init(&p, 60, 0, false);
    struct link l = {.rate = 128000, .latency = 0.02, .drop_one = 5};
    struct sim_result r = simulate(&p, &l, 10, 250000, 160 * 48);
    CHECK_EQ_INT(p.lost, 1);
    CHECK(r.frames > 50); /* ~8 fps on, not stuck after frame 5 */
    CHECK(l.max_queued <= 1);
}

TEST(a_terminal_that_never_answers_is_paced_by_time)
{
    struct pace p;
    pace_init(&p, 60, 0, false);
    struct link l = {.rate = 10e6, .latency = 0.001, .drop_answers = true, .drop_one = -1};
    struct sim_result r = simulate(&p, &l, 20, 250000, 160 * 48);
    CHECK(p.lost >= PACE_LOST_LIMIT);
    CHECK(r.frames > 80); /* 8 fps once blind, after three 2-second waits */
    CHECK(r.bytes_per_s <= PACE_BLIND_RATE * 1.05);
}

TEST(bandwidth_caps_the_bytes_per_second)
{
    struct pace p;
    pace_init(&p, 60, 50000, false);
    struct link l = {.rate = 10e6, .latency = 0.001, .drop_one = -1};
    struct sim_result r = simulate(&p, &l, 10, 250000, 160 * 48);
    CHECK(r.bytes_per_s <= 50000 * 1.1);
    CHECK(r.bytes_per_s >= 50000 * 0.7);
    char hud[64];
    pace_describe(&p, 12, hud, sizeof hud);
    CHECK_STR_CONTAINS(hud, "cap 50KB/s");
    CHECK_STR_CONTAINS(hud, "12fps");
    CHECK_STR_CONTAINS(hud, "tol 12");
}

TEST(a_very_slow_link_drops_to_256_colours_and_recovers)
{
    struct pace p;
    pace_init(&p, 60, 0, false);
    struct link l = {.rate = 16000, .latency = 0.02, .drop_one = -1};
    simulate(&p, &l, 10, 250000, 160 * 48); /* 16000 * 0.125 / 7680 = 0.26 byte/cell */
    CHECK(p.use_256);
    CHECK_EQ_INT(pace_mode(&p, PALETTE_TRUECOLOR), PALETTE_256);
    CHECK_EQ_INT(pace_mode(&p, PALETTE_16), PALETTE_16);
    char hud[64];
    pace_describe(&p, 0, hud, sizeof hud);
    CHECK_STR_CONTAINS(hud, "256c");
    /* a smaller window on the same link: 0.5 byte/cell, back to truecolor */
    pace_sent(&p, 100, 1000, 1000, 4000);
    CHECK(!p.use_256);
}

TEST(a_terminal_that_answers_no_query_at_start_costs_no_timeout)
{
    /* issue 25: a terminal that answered none of the start's queries (tty_query) is paced
     * by time from the first frame, never waiting for an answer; over a 256 kbit/s link with
     * a deep queue the guessed rate keeps a key within a few frames */
    struct pace p;
    pace_init(&p, 60, 0, false);
    pace_no_answers(&p);
    struct link l = {.rate = 32000, .latency = 0.02, .drop_answers = true, .drop_one = -1};
    struct sim_result r = simulate(&p, &l, 20, 250000, 160 * 48);
    CHECK_EQ_INT(p.lost, 0);
    CHECK(r.frames > 20 * 6); /* ~8 fps from the start: no 2-second waits */
    CHECK(r.median_ms <= 300);
    CHECK(r.worst_ms <= 800);
    char hud[64];
    pace_describe(&p, 9, hud, sizeof hud);
    CHECK_STR_CONTAINS(hud, "guess 32KB/s");
    /* an answer after all (a slow link delayed the start's): paced on answers again */
    pace_answer(&p, 30);
    CHECK(!p.no_answers);
}

TEST(a_local_terminal_is_paced_by_its_answers_but_never_budgeted)
{
    /* issue 25: a local terminal busy drawing (its answers come at 2 MB/s) is not a narrow
     * link: one frame in flight still, but every frame whole, truecolor, nothing said */
    struct pace p;
    pace_init(&p, 60, 0, true);
    struct link l = {.rate = 2e6, .latency = 0.0002, .drop_one = -1};
    simulate(&p, &l, 5, 250000, 320 * 90);
    CHECK(l.max_queued <= 1);
    CHECK_EQ_INT((int)pace_budget(&p), 0);
    CHECK_EQ_INT(pace_mode(&p, PALETTE_TRUECOLOR), PALETTE_TRUECOLOR);
    char hud[64];
    pace_describe(&p, 0, hud, sizeof hud);
    CHECK_EQ_INT(hud[0], '\0');
    /* --bandwidth is a link the user names: capped and budgeted as before */
    pace_init(&p, 60, 50000, true);
    CHECK(!p.local);
}
