/* order.c: sorting numbered records by their bytes (see order.h). */
#include "order.h"

#include <stdlib.h>
#include <string.h>

/* qsort's context, one a thread: the background builds of several scenes sort at once */
static _Thread_local const unsigned char *sort_base;
static _Thread_local size_t sort_size;

static int by_record(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    int c = memcmp(sort_base + x * sort_size, sort_base + y * sort_size, sort_size);
    return c ? c : (x > y) - (x < y);
}

void order_by_record(uint32_t *order, size_t n, const void *base, size_t size)
{
    sort_base = base, sort_size = size;
    qsort(order, n, sizeof *order, by_record);
}
