// SPDX-License-Identifier: MIT
/* Bad input found by the malformed-input corpus (tests/fuzz/): each test is one finding that used
 * to crash, hang or allocate without bound, and now is a one-line Error (or a warning and a
 * rebuild, for the kernel cache). Timeouts turn a hang back into a failure. */
#include <criterion/criterion.h>

#include <glob.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "device/kernel_cache.h"
#include "io/obj_lines.h"
#include "io/obj_loader.h"
#include "scene/scene.h"
#include "scene/texture.h"
#include "support.h"

static const char *write_bytes(const char *dir, const char *name, const void *bytes, size_t size)
{
    static char paths[8][512];
    static int next;
    char *path = paths[next++ % 8];
    snprintf(path, sizeof paths[0], "%s/%s", dir, name);
    FILE *f = fopen(path, "wb");
    cr_assert(f, "cannot write %s", path);
    cr_assert_eq(fwrite(bytes, 1, size, f), size);
    fclose(f);
    return path;
}

static const char *write_text(const char *dir, const char *name, const char *text)
{
    return write_bytes(dir, name, text, strlen(text));
}

static const char triangle_obj[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

/* ---- Kernel cache ----------------------------------------------------------------------------- */

/* The only entry in $XDG_CACHE_HOME/pt. */
static void only_cache_entry(const char *cache_home, char *out, size_t size)
{
    char pattern[600];
    snprintf(pattern, sizeof pattern, "%s/pt/kernels-*.bin", cache_home);
    glob_t found;
    cr_assert_eq(glob(pattern, 0, NULL, &found), 0, "no cache entry in %s", cache_home);
    cr_assert_eq(found.gl_pathc, 1);
    snprintf(out, size, "%s", found.gl_pathv[0]);
    globfree(&found);
}

/* A truncated entry once reached PoCL, which read past its end (ASan: heap-buffer-overflow). */
Test(bad_input, truncated_kernel_cache_entry_is_not_loaded)
{
    char home[64];
    snprintf(home, sizeof home, "%s", test_temp_dir());
    setenv("XDG_CACHE_HOME", home, 1);
    unsigned char binary[4000];
    for (size_t i = 0; i < sizeof binary; i++)
        binary[i] = (unsigned char)(i * 7 + 3);
    kernel_cache_store(42, binary, sizeof binary);
    unsigned char *data = NULL;
    size_t size = 0;
    cr_assert(kernel_cache_load(42, &data, &size), "an intact entry loads");
    cr_expect_eq(size, sizeof binary);
    cr_expect_eq(memcmp(data, binary, sizeof binary), 0);
    free(data);

    char entry[700];
    only_cache_entry(home, entry, sizeof entry);
    int warnings = warning_count();
    static const off_t cuts[] = {4000 + 32 - 1, 3000, 100, 31, 0}; /* the header is 32 bytes */
    for (size_t i = 0; i < sizeof cuts / sizeof cuts[0]; i++) {
        off_t cut = cuts[i];
        cr_assert_eq(truncate(entry, cut), 0);
        data = NULL;
        cr_expect_not(kernel_cache_load(42, &data, &size), "entry cut to %lld bytes was loaded",
                      (long long)cut);
        cr_expect_null(data);
    }
    cr_expect_gt(warning_count(), warnings, "an unusable entry is warned about");

    /* One flipped byte: same size, different content. */
    kernel_cache_store(42, binary, sizeof binary);
    FILE *f = fopen(entry, "r+b");
    cr_assert(f);
    fseek(f, -10, SEEK_END);
    fputc(0x5a, f);
    fclose(f);
    cr_expect_not(kernel_cache_load(42, &data, &size), "a corrupted entry was loaded");
}

/* A cache home that cannot hold the cache used to end in "unknown device 'cpu'" (PoCL, whose own
 * cache lives there too, then offers no device). Now: a warning, and the device opens. */
Test(bad_input, unwritable_kernel_cache_is_a_warning, .timeout = 120)
{
    const char *dir = test_temp_dir();
    const char *file = write_text(dir, "not-a-folder", "x");
    setenv("XDG_CACHE_HOME", file, 1);
    unsetenv("POCL_CACHE_DIR");
    unsetenv("PT_NO_CACHE");
    int warnings = warning_count();
    Device dev;
    Error err = {0};
    cr_assert(device_open(&dev, "cpu", &err), "%s", err.message);
    cr_expect_gt(warning_count(), warnings, "the unwritable cache is warned about");
    cr_assert(device_build(&dev, PROGRAM_FEATURES_ALL,
                           "kernel void probe(global int *x) { x[0] = 1; }", "probe.cl", &err),
              "%s", err.message);
    device_close(&dev);
}

/* ---- OBJ and MTL ------------------------------------------------------------------------------ */

/* An uncaught std::ios_base::failure ("basic_filebuf::underflow ... Is a directory") aborted. */
Test(bad_input, mtllib_naming_a_directory_is_an_error)
{
    const char *dir = test_temp_dir();
    char folder[600];
    snprintf(folder, sizeof folder, "%s/materials", dir);
    cr_assert_eq(mkdir(folder, 0755), 0);
    const char *obj = write_text(dir, "dir.obj", "mtllib materials\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                                 "usemtl x\nf 1 2 3\n");
    Mesh mesh;
    Error err = {0};
    cr_expect_not(obj_load(obj, &mesh, &err));
    cr_expect_eq(err.code, ERR_FILE_READ, "%s", err.message);
    cr_expect(strstr(err.message, "materials: is a directory"), "%s", err.message);
}

Test(bad_input, mtllib_dev_zero_is_an_error, .timeout = 20)
{
    const char *dir = test_temp_dir();
    const char *obj = write_text(dir, "zero.obj", "mtllib /dev/zero\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                                  "f 1 2 3\n");
    Mesh mesh;
    Error err = {0};
    cr_expect_not(obj_load(obj, &mesh, &err));
    cr_expect(strstr(err.message, "/dev/zero: is a character device"), "%s", err.message);
}

/* Reading /dev/zero as an OBJ grew a string without end (> 8 GiB); a FIFO blocked forever. */
Test(bad_input, obj_that_is_a_device_or_fifo_is_an_error, .timeout = 20)
{
    Mesh mesh;
    Error err = {0};
    cr_expect_not(obj_load("/dev/zero", &mesh, &err));
    cr_expect_eq(err.code, ERR_FILE_READ, "%s", err.message);
    cr_expect(strstr(err.message, "/dev/zero: is a character device, not an OBJ file"), "%s",
              err.message);

    const char *dir = test_temp_dir();
    char fifo[600];
    snprintf(fifo, sizeof fifo, "%s/pipe.obj", dir);
    cr_assert_eq(mkfifo(fifo, 0600), 0);
    Error err2 = {0};
    cr_expect_not(obj_load(fifo, &mesh, &err2));
    cr_expect(strstr(err2.message, "pipe.obj: is a FIFO"), "%s", err2.message);

    /* The same through a scene file naming it. */
    const char *scene = write_text(dir, "scene.json", "{\"objects\": [{\"obj\": \"/dev/zero\"}]}");
    Scene loaded;
    Error err3 = {0};
    cr_expect_not(scene_load(scene, &loaded, &err3));
    cr_expect(strstr(err3.message, "/dev/zero: is a character device"), "%s", err3.message);
}

Test(bad_input, obj_line_longer_than_the_limit_is_an_error)
{
    const char *dir = test_temp_dir();
    size_t n = OBJ_MAX_LINE_LENGTH + 100;
    char *text = malloc(n + 64);
    cr_assert(text);
    strcpy(text, triangle_obj);
    size_t at = strlen(text);
    text[at++] = '#';
    memset(text + at, 'x', n);
    text[at + n] = '\n';
    const char *obj = write_bytes(dir, "long.obj", text, at + n + 1);
    free(text);
    Mesh mesh;
    Error err = {0};
    cr_expect_not(obj_load(obj, &mesh, &err));
    cr_expect_eq(err.code, ERR_TOO_LARGE, "%s", err.message);
    cr_expect(strstr(err.message, "long.obj:5: line of"), "%s", err.message);
}

/* A PNG or an empty file named .obj was "the scene has no triangles", which says nothing about
 * the file. */
Test(bad_input, obj_that_is_binary_or_empty_says_why)
{
    const char *dir = test_temp_dir();
    static const unsigned char png[] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0, 0, 13,
                                        'I', 'H', 'D', 'R', 0, 0, 0, 1, 0, 0, 0, 1, 8, 6, 0, 0, 0};
    const char *fake = write_bytes(dir, "image.obj", png, sizeof png);
    Scene scene;
    Error err = {0};
    cr_expect_not(scene_load(fake, &scene, &err));
    cr_expect_eq(err.code, ERR_OBJ_PARSE, "%s", err.message);
    cr_expect(strstr(err.message, "image.obj:2: not an OBJ text file (binary data at line 2"), "%s",
              err.message);

    const char *empty = write_bytes(dir, "empty.obj", "", 0);
    Error err2 = {0};
    cr_expect_not(scene_load(empty, &scene, &err2));
    cr_expect_eq(err2.code, ERR_NO_TRIANGLES);
    cr_expect(strstr(err2.message, "empty.obj: no faces (the file is empty)"), "%s", err2.message);

    const char *points = write_text(dir, "points.obj", "v 0 0 0\nv 1 0 0\n");
    const char *json = write_text(dir, "points.json", "{\"objects\": [{\"obj\": \"points.obj\"}]}");
    (void)points;
    Error err3 = {0};
    cr_expect_not(scene_load(json, &scene, &err3));
    cr_expect(strstr(err3.message, "points.obj: no faces, 'v' records but no 'f' records"), "%s",
              err3.message);
}

/* ---- Textures ---------------------------------------------------------------------------------- */

/* A 16x2 RLE .hdr: both scanlines, or cut `cut` bytes short. stb_image looped forever on a cut
 * one (a zero-length dump read at the end of the file). */
static size_t rle_hdr(unsigned char *out, size_t cut)
{
    size_t n = (size_t)sprintf((char *)out, "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 16\n");
    for (int y = 0; y < 2; y++) {
        unsigned char start[4] = {2, 2, 0, 16};
        memcpy(out + n, start, 4);
        n += 4;
        for (int channel = 0; channel < 4; channel++) {
            out[n++] = 128 + 16; /* a run of 16 */
            out[n++] = channel == 3 ? 128 : 64;
        }
    }
    return n - cut;
}

Test(bad_input, truncated_rle_hdr_is_an_error, .timeout = 20)
{
    const char *dir = test_temp_dir();
    unsigned char bytes[256];
    TextureSet set = {0};
    Error err = {0};
    const char *whole = write_bytes(dir, "whole.hdr", bytes, rle_hdr(bytes, 0));
    cr_assert_neq(texture_set_add(&set, whole, &err), NO_TEXTURE, "%s", err.message);
    cr_expect_eq(set.infos[0].width, 16);
    for (size_t cut = 1; cut <= 12; cut++) {
        char name[32];
        snprintf(name, sizeof name, "cut%zu.hdr", cut);
        const char *path = write_bytes(dir, name, bytes, rle_hdr(bytes, cut));
        Error cut_err = {0};
        cr_expect_eq(texture_set_add(&set, path, &cut_err), NO_TEXTURE, "%s loaded", name);
        cr_expect_eq(cut_err.code, ERR_TEXTURE, "%s: %s", name, cut_err.message);
        cr_expect(strstr(cut_err.message, name), "%s", cut_err.message);
    }
    texture_set_free(&set);
}

/* A few bytes declaring a huge image are refused on the header, before any allocation. */
Test(bad_input, texture_declaring_a_huge_size_is_refused, .timeout = 20)
{
    const char *dir = test_temp_dir();
    const char header[] = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 16000000 +X 16000000\n";
    const char *hdr = write_text(dir, "huge.hdr", header);
    TextureSet set = {0};
    Error err = {0};
    cr_expect_eq(texture_set_add(&set, hdr, &err), NO_TEXTURE);
    cr_expect_eq(err.code, ERR_TOO_LARGE, "%s", err.message);
    cr_expect(strstr(err.message, "huge.hdr: declared size 16000000x16000000"), "%s", err.message);

    Error err2 = {0};
    cr_expect_eq(texture_set_add(&set, "/dev/zero", &err2), NO_TEXTURE);
    cr_expect_eq(err2.code, ERR_TEXTURE, "%s", err2.message);
    cr_expect(strstr(err2.message, "/dev/zero: is a character device"), "%s", err2.message);
    texture_set_free(&set);
}

/* libFuzzer (fuzz_texture) finding: a JPEG Huffman table of more than 256 codes made stb_image
 * write past its tables (UBSan: index 257 out of bounds for type 'stbi_uc[257]'). */
Test(bad_input, jpeg_huffman_table_over_256_codes_is_an_error)
{
    unsigned char jpeg[700];
    size_t n = 0;
    static const unsigned char start[] = {0xff, 0xd8, 0xff, 0xc4, 0x01, 0xa3, 0x01};
    memcpy(jpeg + n, start, sizeof start); /* DHT of 2 + 1 + 16 + 400 = 419 bytes, DC table 1 */
    n += sizeof start;
    memset(jpeg + n, 0, 14);
    n += 14;
    jpeg[n++] = 200;
    jpeg[n++] = 200;
    memset(jpeg + n, 0, 400);
    n += 400;
    jpeg[n++] = 0xff;
    jpeg[n++] = 0xd9;
    const char *dir = test_temp_dir();
    const char *path = write_bytes(dir, "codes.jpg", jpeg, n);
    TextureSet set = {0};
    Error err = {0};
    cr_expect_eq(texture_set_add(&set, path, &err), NO_TEXTURE);
    cr_expect(strstr(err.message, "codes.jpg: corrupt JPEG texture: Huffman table with more than "
                                  "256 codes"), "%s", err.message);
    texture_set_free(&set);
}

/* libFuzzer (fuzz_texture) finding: stb_image grew its buffer to a PNG chunk's declared length
 * before reading the chunk, so 130 bytes declaring a 2 GiB IDAT allocated 2 GiB. */
Test(bad_input, png_chunk_longer_than_the_file_is_an_error)
{
    static const unsigned char png[] = {
        0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0, 0, 13, 'I', 'H', 'D', 'R', 0, 0, 0, 4,
        0, 0, 0, 4, 8, 6, 0, 0, 0, 0xa9, 0xf1, 0x9e, 0x7e, 0x7f, 0xff, 0xff, 0xf0, 'I', 'D', 'A',
        'T', 0x78, 0x9c, 0x63, 0x60, 0, 0, 0, 0, 0, 0};
    const char *dir = test_temp_dir();
    const char *path = write_bytes(dir, "chunk.png", png, sizeof png);
    TextureSet set = {0};
    Error err = {0};
    cr_expect_eq(texture_set_add(&set, path, &err), NO_TEXTURE);
    cr_expect(strstr(err.message, "chunk.png: corrupt PNG texture: a chunk declares more bytes"),
              "%s", err.message);
    texture_set_free(&set);
}

/* libFuzzer (fuzz_texture) finding: the .hdr check found the resolution line where stb does not
 * (stb ends the header at the first empty line), so it passed a file on which stb looped forever
 * on a zero-length RLE run. */
Test(bad_input, hdr_header_is_read_as_stb_reads_it, .timeout = 20)
{
    unsigned char bytes[200];
    size_t n = (size_t)sprintf((char *)bytes, "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n-Y 1 +X 16\n\n"
                                              "-Y 1 +X 16\n");
    static const unsigned char zero_run[] = {2, 2, 0, 16, 0};
    memcpy(bytes + n, zero_run, sizeof zero_run);
    n += sizeof zero_run;
    memset(bytes + n, 1, 60);
    n += 60;
    const char *dir = test_temp_dir();
    const char *path = write_bytes(dir, "header.hdr", bytes, n);
    TextureSet set = {0};
    Error err = {0};
    cr_expect_eq(texture_set_add(&set, path, &err), NO_TEXTURE);
    cr_expect(strstr(err.message, "header.hdr: corrupt HDR texture: zero-length RLE run"), "%s",
              err.message);
    texture_set_free(&set);
}
