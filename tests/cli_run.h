/* SPDX-License-Identifier: MIT */
/* cli_run.h: running the pt binary from the end-to-end tests (test_cli*.c): its exit status,
 * stdout and stderr, and the check of a clean one-line error. */
#ifndef PT_TEST_CLI_RUN_H
#define PT_TEST_CLI_RUN_H

typedef struct {
    int exit_code; /* -1 when killed by a signal */
    char out[8192], err[8192];
} Run;

/* Runs pt with args (a shell fragment) in folder dir (NULL = here), with the environment
 * assignments env (a shell fragment such as "PT_LOCAL_SIZE=0"; NULL = none) added. stderr goes
 * to a file: it is not a terminal. */
Run run_pt_env(const char *dir, const char *env, const char *args);
Run run_pt(const char *dir, const char *args);

/* One clear line: exit 1, stderr is a single "pt: ..." line containing every needle (NULL: none). */
void expect_clean_error(Run r, const char *what, const char *needle1, const char *needle2);

#endif
