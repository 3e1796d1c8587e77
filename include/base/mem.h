/* mem.h: large arrays on huge pages, where the system gives them only on request.
 *
 * A model of a million triangles fills a few hundred megabytes of fresh arrays at load and
 * in its first frame (the file, the corners, the normal fans, the vertices, the vertex
 * stage's output: 64 MB alone for 500k vertices). Each 4 KiB page costs a page fault on
 * first write; in a virtual machine that was a third of `rastty render`'s load time on the
 * 1M-triangle sphere (perf: exc_page_fault under mesh_build, ply_read and vertex_run).
 * Linux's transparent huge pages fill 2 MiB at a fault, but most distributions give them
 * only to memory marked MADV_HUGEPAGE (/sys/kernel/mm/transparent_hugepage/enabled:
 * "madvise"). mem_big marks the pages of an array (the same hint glibc gives its own large
 * blocks under GLIBC_TUNABLES=glibc.malloc.hugetlb=1); the kernel maps the whole 2 MiB
 * blocks inside them as huge pages. It changes no
 * value: only how the memory is mapped. Elsewhere (another system, THP off or "always") it
 * does nothing. */
#ifndef RASTTY_MEM_H
#define RASTTY_MEM_H

#include <stddef.h>

/* Arrays smaller than this are left alone (a huge page may be mostly unused). */
#define MEM_BIG_MIN ((size_t)4 << 20)

/* Ask for huge pages under p[0..n) (when n >= MEM_BIG_MIN); p may be NULL (nothing).
 * Returns p. */
void *mem_big(void *p, size_t n);

#endif
