/* view.h: the interactive viewer (`rastty`, `rastty view FILES...`).
 *
 * The loop owns the model — camera, modes, scenes — and nothing else:
 *     input (tty.c events -> input.c commands) -> update camera -> render (pipeline.c)
 *     -> encode (encode.c, diff against what the terminal shows) -> write (tty.c)
 * It renders only when something changed (camera, light, mode, size); otherwise it blocks in
 * tty_next_event and costs no CPU and no bytes. Motion uses elapsed time. Frames in flight
 * are capped with a DSR round trip per frame (tty.h), so on a slow link input never queues
 * behind stale frames. */
#ifndef RASTTY_VIEW_H
#define RASTTY_VIEW_H

#include "err.h"
#include "options.h"

/* Returns the exit status (0; 1/2 with e filled; 128 + signal when SIGINT, SIGTERM, SIGHUP
 * or SIGQUIT ended it); the terminal is restored in all cases. */
int view_run(const struct options *o, struct err *e);

#endif
