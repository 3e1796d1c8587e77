/* bench.h: `rastty bench` — the viewer's frame and the encodings timed (cmd_bench.c), the
 * methods chart (--chart, chart.h) and the stress sweeps (--sweep NAME, sweep.h). Each
 * returns the process exit status (0 ok, 1 runtime failure, 2 bad usage) and fills e when
 * non-zero. */
#ifndef RASTTY_BENCH_H
#define RASTTY_BENCH_H

#include "err.h"
#include "options.h"

int cmd_bench(const struct options *o, struct err *e);
/* bench --chart (chart.h) and bench --sweep NAME (sweep.h) */
int cmd_bench_chart(const struct options *o, struct err *e);
int cmd_bench_sweep(const struct options *o, struct err *e);

#endif
