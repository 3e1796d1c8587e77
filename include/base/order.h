/* order.h: sorting numbered records by their bytes. */
#ifndef RASTTY_ORDER_H
#define RASTTY_ORDER_H

#include <stddef.h>
#include <stdint.h>

/* Sort order[0 .. n) — numbers of records of `size` bytes each at base — by their records'
 * bytes (memcmp), then by number: equal records come together, the lowest number first.
 * The records must have no padding. Threads may sort at once (the context is per thread). */
void order_by_record(uint32_t *order, size_t n, const void *base, size_t size);

#endif
