/* kernel_avx2.c: the kernels for AVX2, eight lanes (kernel.h). Compiled with -mavx2 -mno-fma
 * (Makefile): the same IEEE operations in the same order as every other kernel, so the same
 * bytes, in VEX encoding with blends, gathers, rounding and 32-bit multiplies. */
#define SIMD_LANES 8
#define KERNEL_TABLE kernel_avx2
#define KERNEL_NAME "avx2"
#include "kernel_table.h"
