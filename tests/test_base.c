// SPDX-License-Identifier: MIT
/* host/base: the file-system and vector helpers every layer uses. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "base/fs.h"
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
