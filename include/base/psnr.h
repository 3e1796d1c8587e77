/* psnr.h: peak signal-to-noise ratio of 8-bit pictures, the one formula behind every PSNR
 * rastty prints (bench's encodings, the methods chart, the sweeps' thresholds):
 * 10 log10(255^2 / MSE) dB, MSE the mean of the squared channel differences; identical
 * pictures score INFINITY. Measurements are numbers for people, never asserted by the
 * renderer. */
#ifndef RASTTY_PSNR_H
#define RASTTY_PSNR_H

#include <stddef.h>
#include <stdint.h>

/* The sum of (a[i] - b[i])^2 over n bytes: exact (integers far below 2^53). */
double psnr_sse(const uint8_t *a, const uint8_t *b, size_t n);
/* 10 log10(255^2 / mse); INFINITY when mse is 0 (or less). */
double psnr_db(double mse);
/* The mean squared error a PSNR stands for: 255^2 10^(-db / 10); 0 for INFINITY. */
double psnr_mse(double db);

#endif
