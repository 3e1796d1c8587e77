/* cmd.h: the subcommands render, dump and ansi2ppm (viewer/view.h has the viewer,
 * bench/bench.h the benchmarks), which main() hands over to. Each returns the process exit status
 * (0 ok, 1 runtime failure, 2 bad usage or bad input) and fills e when non-zero. */
#ifndef RASTTY_CMD_H
#define RASTTY_CMD_H

#include "err.h"
#include "options.h"

int cmd_render(const struct options *o, struct err *e);
int cmd_dump(const struct options *o, struct err *e);
int cmd_ansi2ppm(const struct options *o, struct err *e);

#endif
