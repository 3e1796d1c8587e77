/* main.c: rastty's entry point — parse the command line (cli/options.c), hand over to a
 * subcommand, print the one error line if it failed.
 *
 * Follow a frame from here as `rastty` draws the demo: view_run (viewer/view.c) loads the
 * scene (cli/prepare.c: prepare_scene -> scene/scene.c), then its loop draws each frame —
 * ssaa_draw -> pipeline_draw (render/pipeline.c) -> the frame's plan (render/plan_tiles.c
 * or plan_slices.c: front end in render/frontend.c, back end in render/batch.c, the
 * per-pixel kernels in render/kernel/) -> encode_fb (term/encode.c) -> tty_write
 * (term/tty.c). The README's "One frame, step by step" walks it file by file. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "bench.h"
#include "cmd.h"
#include "config.h"
#include "file.h"
#include "options.h"
#include "outputs.h"
#include "view.h"

#define RASTTY_VERSION "0.1.0"

/* --help and --version: a write error (a full disk, a closed pipe) is a failure, exit 1 */
static int flush_stdout(void)
{
    errno = 0;
    if (fflush(stdout) != 0 || ferror(stdout)) {
        fprintf(stderr, "rastty: standard output: write failed: %s\n",
                strerror(errno ? errno : EIO));
        return 1;
    }
    return 0;
}

int main(int argc, char **argv)
{
    struct options o;
    struct err e = {""};
    if (options_parse(argc, argv, &o, &e)) {
        fprintf(stderr, "%s\n", e.msg);
        return 2;
    }
    if (o.cmd == CMD_RENDER || o.cmd == CMD_DUMP || o.cmd == CMD_ANSI2PPM || o.cmd == CMD_BENCH)
        file_out_cleanup_on_signals(); /* no temporaries left behind by a signal */
    /* an output that is an input (or another output) would destroy it: refused first */
    if (o.cmd != CMD_VIEW && o.cmd != CMD_HELP && o.cmd != CMD_VERSION && outputs_check(&o, &e)) {
        fprintf(stderr, "%s\n", e.msg);
        return 2;
    }
    /* the user's defaults (config.h): the viewer's, and dump's colours on a terminal */
    static struct config cfg;
    bool dump_tty = o.cmd == CMD_DUMP && !o.out && isatty(STDOUT_FILENO);
    if (o.cmd == CMD_VIEW || dump_tty) {
        if (config_load(getenv("XDG_CONFIG_HOME"), getenv("HOME"), getenv("RASTTY_COLORS"), &cfg,
                        &e)) {
            fprintf(stderr, "%s\n", e.msg);
            return 2;
        }
        if (o.cmd == CMD_VIEW)
            config_apply(&cfg, &o);
        else if (!o.colors && cfg.colors[0])
            o.colors = cfg.colors;
    }
    int rc;
    switch (o.cmd) {
    case CMD_HELP:
        options_usage(stdout);
        return flush_stdout();
    case CMD_VERSION:
        printf("rastty %s\n", RASTTY_VERSION);
        return flush_stdout();
    case CMD_RENDER:
        rc = cmd_render(&o, &e);
        break;
    case CMD_DUMP:
        rc = cmd_dump(&o, &e);
        break;
    case CMD_ANSI2PPM:
        rc = cmd_ansi2ppm(&o, &e);
        break;
    case CMD_BENCH:
        rc = cmd_bench(&o, &e);
        break;
    case CMD_VIEW:
        rc = view_run(&o, &e);
        break;
    default:
        fprintf(stderr, "rastty: this subcommand is not built yet\n");
        return 2;
    }
    if (rc == 1 || rc == 2) /* >= 128: stopped by a signal, nothing went wrong */
        fprintf(stderr, "%s\n", e.msg[0] ? e.msg : "rastty: failed");
    return rc;
}
