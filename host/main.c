// SPDX-License-Identifier: MIT
/* pt: command-line entry, dispatch only: each command lives in app/ (or viewer/); bad input ends
 * with one line naming the file/line/value and exit status 1. */
#include <stdio.h>

#include "app/bench.h"
#include "app/cli.h"
#include "dist/mpi_link.h"
#include "app/render_cmd.h"
#include "app/tonemap_cmd.h"
#include "base/error.h"
#include "base/version.h"
#include "device/device.h"
#include "viewer/viewer.h"

static int run_command(const Options *o)
{
    Error err = {0};
    switch (o->command) {
    case CMD_HELP:
    case CMD_NONE:
        cli_print_help();
        return 0;
    case CMD_VERSION:
        printf("pt %s\n", PT_VERSION);
        return 0;
    case CMD_DEVICES:
        if (!device_list(stdout, &err))
            die("%s", err.message);
        return 0;
    case CMD_RENDER:
        return command_render(o);
    case CMD_VIEW: {
        ViewerDesc view = cli_viewer_desc(o);
        return command_view(&view);
    }
    case CMD_BENCH:
        return command_bench(o);
    case CMD_TONEMAP:
        return command_tonemap(o);
    }
    return 0;
}

int main(int argc, char **argv)
{
    Options o;
    Error err = {0};
    /* Under mpirun (only then) this process is one rank of a job (dist/mpi_link.h). */
    if (!mpi_link_init(&argc, &argv, &err))
        die("%s", err.message);
    if (!cli_parse(argc, argv, &o, &err))
        die("%s", err.message);
    int status = run_command(&o);
    mpi_link_finalize();
    return status;
}
