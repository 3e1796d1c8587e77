/* kernel_avx2_4.c: the kernels for AVX2, four lanes (kernel.h): a triangle of up to four
 * pixels fills one group of four, with half the per-lane loads and stores of a group of
 * eight. Compiled with -mavx2 -mno-fma (Makefile), as kernel_avx2.c. */
#define SIMD_LANES 4
#define KERNEL_TABLE kernel_avx2_4
#define KERNEL_NAME "avx2-4"
#include "kernel_table.h"
