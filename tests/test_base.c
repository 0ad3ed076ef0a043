// SPDX-License-Identifier: MIT
/* host/base: the file-system, vector and parallel-loop helpers every layer uses. */
#include <criterion/criterion.h>
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "base/fs.h"
#include "base/parallel_for.h"
#include "base/vec3.h"
#include "support.h"

Test(base, stem_drops_folders_trailing_slashes_and_the_last_extension)
{
    static const char *cases[][2] = {
        {"scenes/cornell-box", "cornell-box"}, {"scenes/cornell-box/", "cornell-box"},
        {"a/b.json", "b"},                     {"x.tar.gz", "x.tar"},
        {".hidden", ".hidden"},
        {"plain", "plain"},                    {"dir.d/file", "file"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char out[64];
        fs_stem(cases[i][0], out, sizeof out);
        cr_expect_str_eq(out, cases[i][1], "fs_stem(\"%s\")", cases[i][0]);
    }
}

Test(base, suffix_ignores_case_and_needs_the_whole_suffix)
{
    cr_expect(fs_has_suffix("a.EXR", ".exr"));
    cr_expect(fs_has_suffix(".png", ".png"));
    cr_expect_not(fs_has_suffix("png", ".png"));
    cr_expect_not(fs_has_suffix("a.exr.tmp", ".exr"));
}

Test(base, make_dirs_creates_parents_and_refuses_a_file_in_the_way)
{
    char root[64], path[512], file[512];
    snprintf(root, sizeof root, "%s", test_temp_dir());
    snprintf(path, sizeof path, "%s/a/b/c", root);
    cr_assert(fs_make_dirs(path));
    struct stat st;
    cr_assert(stat(path, &st) == 0 && S_ISDIR(st.st_mode));
    cr_expect(fs_make_dirs(path), "an existing folder is fine");
    snprintf(file, sizeof file, "%s/a/file", root);
    FILE *f = fopen(file, "w");
    cr_assert(f);
    fclose(f);
    char below[600];
    snprintf(below, sizeof below, "%s/sub", file);
    cr_expect_not(fs_make_dirs(below), "a file where a folder should be");
    cr_expect_not(fs_make_dirs(file), "the path itself is a file");
    snprintf(below, sizeof below, "%s/x/y/out.csv", root);
    cr_expect(fs_make_parent_dirs(below));
    snprintf(below, sizeof below, "%s/x/y", root);
    cr_expect(stat(below, &st) == 0 && S_ISDIR(st.st_mode));
}

Test(base, vectors)
{
    float x[3] = {1, 0, 0}, y[3] = {0, 1, 0}, z[3];
    cross3(x, y, z);
    cr_expect(z[0] == 0 && z[1] == 0 && z[2] == 1, "x cross y = z (right-handed)");
    cross3(x, y, x); /* aliasing the output with an input */
    cr_expect(x[0] == 0 && x[1] == 0 && x[2] == 1);
    float v[3] = {3, 0, 4};
    cr_expect(normalize3(v) && fabsf(length3(v) - 1.0f) < 1e-6f);
    float zero[3] = {0, 0, 0}, nan3[3] = {NAN, 0, 0}, inf3[3] = {INFINITY, 0, 0};
    cr_expect_not(normalize3(zero));
    cr_expect_not(normalize3(nan3));
    cr_expect_not(normalize3(inf3));
}

/* ---- Atomic writes (base/fs.h) ---------------------------------------------------------------- */

static char g_hook_target[512];
static char g_hook_seen[64];

/* What the target holds at the moment the hook runs: the old content (the rename comes after). */
static void read_target_in_hook(void)
{
    FILE *f = fopen(g_hook_target, "rb");
    size_t n = f ? fread(g_hook_seen, 1, sizeof g_hook_seen - 1, f) : 0;
    g_hook_seen[n] = '\0';
    if (f)
        fclose(f);
}

static int files_in(const char *folder)
{
    DIR *d = opendir(folder);
    int n = 0;
    for (struct dirent *e; d && (e = readdir(d));)
        n += e->d_name[0] != '.';
    if (d)
        closedir(d);
    return n;
}

Test(base, atomic_write_replaces_the_file_after_the_hook_and_leaves_no_temporary)
{
    char folder[64];
    snprintf(folder, sizeof folder, "%s", test_temp_dir());
    snprintf(g_hook_target, sizeof g_hook_target, "%s/out.txt", folder);
    Error err = {0};
    cr_assert(fs_write_atomic(g_hook_target, "old", 3, &err), "%s", err.message);
    fs_set_before_rename_hook(read_target_in_hook);
    cr_assert(fs_write_atomic(g_hook_target, "new", 3, &err), "%s", err.message);
    fs_set_before_rename_hook(NULL);
    cr_expect_str_eq(g_hook_seen, "old", "the hook runs before the rename");
    size_t size = 0;
    char *text = test_read_file(g_hook_target, &size);
    cr_expect(text && size == 3 && memcmp(text, "new", 3) == 0);
    free(text);
    cr_expect_eq(files_in(folder), 1, "only out.txt: no temporary file left");
}

Test(base, atomic_write_refuses_bad_targets_with_one_line)
{
    char folder[64], path[600];
    snprintf(folder, sizeof folder, "%s", test_temp_dir());
    static const char *const bad[] = {"", "/missing/folder/x.exr", "%s/", "%s"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        snprintf(path, sizeof path, bad[i], folder);
        Error err = {0};
        cr_expect_not(fs_write_atomic(path, "x", 1, &err), "accepted '%s'", path);
        cr_expect_eq(err.code, ERR_OUTPUT, "'%s': %s", path, err.message);
        cr_expect(strchr(err.message, '\n') == NULL, "one line: %s", err.message);
    }
    cr_expect_eq(files_in(folder), 0, "nothing written");
}

/* Each call of parallel_for's body marks its range; every index must be marked exactly once, for
 * counts below, at and above what splits across threads. */
static void mark_range(void *ctx, size_t begin, size_t end)
{
    unsigned char *marks = ctx;
    for (size_t i = begin; i < end; i++)
        __atomic_fetch_add(&marks[i], 1, __ATOMIC_RELAXED);
}

Test(base, parallel_for_visits_every_index_once)
{
    static const size_t counts[] = {0, 1, 15, 16, 17, 31, 32, 33, 255, 1000, 4096, 100003};
    for (size_t c = 0; c < sizeof counts / sizeof counts[0]; c++) {
        size_t n = counts[c];
        unsigned char *marks = calloc(n + 1, 1);
        cr_assert(marks);
        parallel_for(n, 16, mark_range, marks);
        for (size_t i = 0; i < n; i++)
            cr_assert_eq(marks[i], 1, "count %zu: index %zu visited %d times", n, i, marks[i]);
        cr_assert_eq(marks[n], 0, "count %zu: ran past the end", n);
        free(marks);
    }
}
