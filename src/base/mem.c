/* mem.c: large arrays on huge pages (see mem.h). */
#include "mem.h"

#include <stdint.h>
#include <sys/mman.h>

#define HUGE_PAGE ((uintptr_t)2 << 20)

void *mem_big(void *p, size_t n)
{
#ifdef MADV_HUGEPAGE
    if (p && n >= MEM_BIG_MIN) {
        uintptr_t a = ((uintptr_t)p + HUGE_PAGE - 1) & ~(HUGE_PAGE - 1);
        uintptr_t b = ((uintptr_t)p + n) & ~(HUGE_PAGE - 1);
        if (b > a)
            madvise((void *)a, b - a, MADV_HUGEPAGE); /* a hint: a refusal changes nothing */
    }
#else
    (void)n;
#endif
    return p;
}
