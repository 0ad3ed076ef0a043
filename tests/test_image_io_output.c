// SPDX-License-Identifier: MIT
/* test_image_io_output.c: output-path checks (missing folder, a directory, a read-only folder) and
 * atomic writes that leave nothing behind on failure, for EXR and PNG alike. */
#include <criterion/criterion.h>
#include <signal.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/fs.h"
#include "image_io_fixtures.h"
#include "io/image_io.h"
#include "support.h"

/* ---- output paths and atomic writes ------------------------------------------------------ */

Test(output, check_writable_accepts_a_new_file_and_creates_nothing)
{
    const char *folder = test_temp_dir();
    Error err = {0};
    cr_assert(fs_check_writable(join(folder, "new.exr"), &err), "%s", err.message);
    cr_assert_eq(folder_entry_count(folder), 0);
    /* A name without a folder part means the current folder (each test is its own process). */
    cr_assert_eq(chdir(folder), 0);
    cr_assert(fs_check_writable("relative-name.png", &err), "%s", err.message);
    cr_assert_eq(folder_entry_count("."), 0);
}

Test(output, missing_folder_is_an_output_error)
{
    const char *path = join(test_temp_dir(), "missing/out.exr");
    Error check = {0}, exr = {0}, png = {0};
    cr_assert_not(fs_check_writable(path, &check));
    cr_assert_eq(check.code, ERR_OUTPUT);
    cr_assert(strstr(check.message, path), "message does not name the path: %s", check.message);
    cr_assert(strstr(check.message, "does not exist"), "message does not say why: %s",
              check.message);

    float rgb[3] = {1, 2, 3};
    cr_assert_not(image_write_exr(path, rgb, 1, 1, &exr));
    cr_assert_eq(exr.code, ERR_OUTPUT, "%s", exr.message);
    cr_assert(strstr(exr.message, path), "%s", exr.message);
    cr_assert_not(image_write_png(path, rgb, 1, 1, clamp_at(0.0f), &png));
    cr_assert_eq(png.code, ERR_OUTPUT, "%s", png.message);
}

Test(output, path_that_is_a_directory_is_refused)
{
    const char *folder = test_temp_dir();
    const char *subfolder = join(folder, "image.exr");
    cr_assert_eq(mkdir(subfolder, 0755), 0);
    Error check = {0}, write = {0}, slash = {0};
    cr_assert_not(fs_check_writable(subfolder, &check));
    cr_assert_eq(check.code, ERR_OUTPUT);
    cr_assert(strstr(check.message, "directory"), "%s", check.message);
    float rgb[3] = {1, 2, 3};
    cr_assert_not(image_write_exr(subfolder, rgb, 1, 1, &write));
    cr_assert_eq(write.code, ERR_OUTPUT);
    struct stat info;
    cr_assert(stat(subfolder, &info) == 0 && S_ISDIR(info.st_mode), "the directory was replaced");
    cr_assert_not(fs_check_writable(join(folder, "new/"), &slash));
    cr_assert_eq(folder_entry_count(subfolder), 0);
}

/* Root ignores folder permissions, and CI runs as root: there the test drops to the unprivileged
 * 'nobody' ids first (each Criterion test is its own process, so this ends with the test). */
static void drop_root(const char *folder)
{
    if (geteuid() != 0)
        return;
    cr_assert_eq(chmod(folder, 0755), 0, "the temp folder must be reachable after dropping root");
    cr_assert_eq(setgid(65534), 0, "setgid(nobody)");
    cr_assert_eq(setuid(65534), 0, "setuid(nobody)");
    cr_assert_neq(geteuid(), 0);
}

Test(output, read_only_folder_is_refused)
{
    const char *folder = test_temp_dir();
    const char *locked = join(folder, "locked");
    cr_assert_eq(mkdir(locked, 0555), 0);
    cr_assert_eq(chmod(locked, 0555), 0);
    drop_root(folder);
    const char *path = join(locked, "out.exr");
    Error check = {0}, write = {0};
    bool checked = fs_check_writable(path, &check);
    float rgb[3] = {1, 2, 3};
    bool written = image_write_exr(path, rgb, 1, 1, &write);
    cr_assert_not(checked);
    cr_assert_eq(check.code, ERR_OUTPUT);
    cr_assert(strstr(check.message, "not writable"), "%s", check.message);
    cr_assert_not(written);
    cr_assert_eq(write.code, ERR_OUTPUT);
    cr_assert_eq(folder_entry_count(locked), 0);
}

/* A file-size limit makes the disk "fill up" part-way through the write; the failed write must
 * report ERR_OUTPUT, remove its temporary file and leave the previous image untouched. */
static void check_failed_write_leaves_previous_file(bool exr)
{
    const char *folder = test_temp_dir();
    const char *path = join(folder, exr ? "out.exr" : "out.png");
    float small[3 * 4] = {0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f, 0.7f, 0.8f, 0.9f, 1.0f, 0.0f, 0.5f};
    Error err = {0};
    bool ok = exr ? image_write_exr(path, small, 2, 2, &err)
                  : image_write_png(path, small, 2, 2, clamp_at(0.0f), &err);
    cr_assert(ok, "%s", err.message);
    size_t before_size = 0;
    char *before = test_read_file(path, &before_size);
    cr_assert_not_null(before);

    signal(SIGXFSZ, SIG_IGN);
    struct rlimit limit = {.rlim_cur = 4096, .rlim_max = RLIM_INFINITY};
    cr_assert_eq(setrlimit(RLIMIT_FSIZE, &limit), 0);
    float *noise = random_image(257, 129); /* random bits: compresses to far more than 4 KiB */
    Error failed = {0};
    ok = exr ? image_write_exr(path, noise, 257, 129, &failed)
             : image_write_png(path, noise, 257, 129, clamp_at(0.0f), &failed);
    limit.rlim_cur = RLIM_INFINITY;
    cr_assert_eq(setrlimit(RLIMIT_FSIZE, &limit), 0);

    cr_assert_not(ok, "the write should fail under a 4 KiB file-size limit");
    cr_assert_eq(failed.code, ERR_OUTPUT, "%s", failed.message);
    cr_assert(strstr(failed.message, path), "%s", failed.message);
    cr_assert_eq(folder_entry_count(folder), 1, "a temporary file was left behind");
    size_t after_size = 0;
    char *after = test_read_file(path, &after_size);
    cr_assert(after && after_size == before_size && memcmp(before, after, before_size) == 0,
              "the previous file was changed by a failed write");
    free(before);
    free(after);
    free(noise);
}

Test(output, failed_exr_write_leaves_no_temp_file_and_keeps_the_old_image)
{
    check_failed_write_leaves_previous_file(true);
}

Test(output, failed_png_write_leaves_no_temp_file_and_keeps_the_old_image)
{
    check_failed_write_leaves_previous_file(false);
}
