/* timing.h: wall-clock time and medians of repeated measurements (benchmarks, --repeat).
 * Measurements are numbers for people, never asserted by tests. */
#ifndef RASTTY_TIMING_H
#define RASTTY_TIMING_H

/* CLOCK_MONOTONIC in milliseconds */
double timing_now_ms(void);
/* The median of v[0..n-1], n >= 1 (the mean of the middle two when n is even); sorts v. */
double timing_median(double *v, int n);
/* The smallest value with at least a fraction p of v[0..n-1] at or below it, n >= 1; sorts v. */
double timing_percentile(double *v, int n, double p);

#endif
