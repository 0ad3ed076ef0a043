// SPDX-License-Identifier: MIT
#include "cli_run.h"

#include <criterion/criterion.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "support.h"

Run run_pt_env(const char *dir, const char *env, const char *args)
{
    Run r;
    memset(&r, 0, sizeof r);
    char out_path[256], err_path[256];
    snprintf(out_path, sizeof out_path, "/tmp/pt-cli-out-%d", (int)getpid());
    snprintf(err_path, sizeof err_path, "/tmp/pt-cli-err-%d", (int)getpid());
    size_t size = strlen(args) + (dir ? strlen(dir) : 0) + (env ? strlen(env) : 0) + PATH_MAX + 1100;
    char *cmd = malloc(size);
    cr_assert(cmd);
    snprintf(cmd, size, "%s%s%s env %s '%s' %s >%s 2>%s", dir ? "cd '" : "", dir ? dir : "",
             dir ? "' && " : "", env ? env : "", test_pt_bin(), args, out_path, err_path);
    int status = system(cmd);
    free(cmd);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    char *text = test_read_file(out_path, NULL);
    snprintf(r.out, sizeof r.out, "%s", text ? text : "");
    free(text);
    text = test_read_file(err_path, NULL);
    snprintf(r.err, sizeof r.err, "%s", text ? text : "");
    free(text);
    unlink(out_path), unlink(err_path);
    return r;
}

Run run_pt(const char *dir, const char *args) { return run_pt_env(dir, NULL, args); }

void expect_clean_error(Run r, const char *what, const char *needle1, const char *needle2)
{
    cr_expect_eq(r.exit_code, 1, "%s: exit %d (stderr: %s)", what, r.exit_code, r.err);
    cr_expect(strncmp(r.err, "pt: ", 4) == 0, "%s: stderr starts with 'pt: ': %s", what, r.err);
    const char *newline = strchr(r.err, '\n');
    cr_expect(newline && newline[1] == '\0', "%s: exactly one line: %s", what, r.err);
    if (needle1)
        cr_expect(strstr(r.err, needle1), "%s: '%s' not in: %s", what, needle1, r.err);
    if (needle2)
        cr_expect(strstr(r.err, needle2), "%s: '%s' not in: %s", what, needle2, r.err);
}
