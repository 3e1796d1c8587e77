/* outputs.h: no output may be an input or another output (issue 25: `dump m.obj --out m.obj`
 * replaced the model with the dump and exited 0; `--out x --depth-out x` lost the colour
 * image). Files are compared by device and inode (a symlink or a hard link to an input is
 * that input), a file not written yet by its folder's device and inode and its name. */
#ifndef RASTTY_OUTPUTS_H
#define RASTTY_OUTPUTS_H

#include "err.h"
#include "options.h"

/* 0, or -1 with "rastty: --out X is the same file as the model Y (...)" in e. */
int outputs_check(const struct options *o, struct err *e);

#endif
