/* kernel_sse2.c: the kernels for the x86-64 baseline, SSE2, four lanes (kernel.h). On other
 * machines the same C is their baseline vector code (simd.h). */
#define SIMD_LANES 4
#define KERNEL_TABLE kernel_sse2
#define KERNEL_NAME "sse2"
#include "kernel_table.h"
