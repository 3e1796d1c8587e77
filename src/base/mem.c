/* mem.c: large arrays on huge pages (see mem.h). */
#include "mem.h"

#include <stdint.h>
#include <sys/mman.h>

#define PAGE ((uintptr_t)4096)

void *mem_big(void *p, size_t n)
{
#ifdef MADV_HUGEPAGE
    /* every page the array touches, not only the whole huge pages inside it: marking part
     * of a mapping splits it in two, and realloc's mremap then cannot grow it in place
     * (it copied: 12% of the 1M sphere's load) */
    if (p && n >= MEM_BIG_MIN) {
        uintptr_t a = (uintptr_t)p & ~(PAGE - 1);
        uintptr_t b = ((uintptr_t)p + n + PAGE - 1) & ~(PAGE - 1);
        madvise((void *)a, b - a, MADV_HUGEPAGE); /* a hint: a refusal changes nothing */
    }
#else
    (void)n;
#endif
    return p;
}
