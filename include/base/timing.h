/* timing.h: the clocks, and medians of repeated measurements (benchmarks, --repeat).
 *
 * Every clock rastty reads is read here: intervals, deadlines and pacing by the monotonic
 * clock (CLOCK_MONOTONIC: never steps when the system time is set), in milliseconds or
 * seconds as the caller counts; the wall clock only where a date is written down (a .cast
 * file's header). Measurements are numbers for people, never asserted by tests. */
#ifndef RASTTY_TIMING_H
#define RASTTY_TIMING_H

/* CLOCK_MONOTONIC in milliseconds */
double timing_now_ms(void);
/* CLOCK_MONOTONIC in seconds */
double timing_now_s(void);
/* The wall clock: seconds since the Unix epoch, time(NULL). */
long timing_wall_s(void);
/* The median of v[0..n-1], n >= 1 (the mean of the middle two when n is even); sorts v. */
double timing_median(double *v, int n);
/* The smallest value with at least a fraction p of v[0..n-1] at or below it, n >= 1; sorts v. */
double timing_percentile(double *v, int n, double p);

#endif
