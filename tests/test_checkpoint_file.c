// SPDX-License-Identifier: MIT
/* The checkpoint file (dist/checkpoint.c) and the render identity (scene/scene_hash.c), in
 * process, without a device: a round trip keeps every bit; every truncation and every flipped
 * bit of a checkpoint is refused with one message naming the file, leaving the film empty; each
 * difference of scene or settings is named; the scene hash is stable across loads and changes
 * with any input of the image. The end-to-end kill-and-resume tests are test_checkpoint.c. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "dist/checkpoint.h"
#include "render/film.h"
#include "scene/scene_hash.h"
#include "support.h"

/* A small grid (3 tiles x 4 blocks) and a film with some units done and arbitrary sums. */
static RenderIdentity tiny_identity(void)
{
    RenderIdentity id = {.scene = 0x0123456789abcdefull, .max_depth = 8, .seed = 7};
    Error err = {0};
    cr_assert(unit_grid_init(&id.grid, 5, 6, 4, 1, 2, &err), "%s", err.message);
    return id;
}

static void fill_film(UnitFilm *f, const RenderIdentity *id, uint64_t seed)
{
    Error err = {0};
    cr_assert(unit_film_init(f, &id->grid, &err), "%s", err.message);
    uint64_t x = seed;
    for (size_t i = 0; i < f->num_pixels * FILM_WORDS; i++) {
        x = x * 6364136223846793005ull + 1442695040888963407ull;
        f->sums[i] = x;
    }
    for (uint32_t u = 0; u < f->grid.count; u += 3) {
        unit_bitmap_set(f->done, u);
        f->units_done++;
    }
}

static const char *checkpoint_file(void)
{
    static char path[128];
    snprintf(path, sizeof path, "%s/out.exr.ptckpt", test_temp_dir());
    return path;
}

static bool film_is_empty(const UnitFilm *f)
{
    for (size_t i = 0; i < f->num_pixels * FILM_WORDS; i++)
        if (f->sums[i])
            return false;
    for (size_t i = 0; i < unit_bitmap_bytes(f->grid.count); i++)
        if (f->done[i])
            return false;
    return f->units_done == 0;
}

/* Reads path back into a fresh film; returns whether it was accepted, the message in err. */
static bool read_back(const char *path, RenderIdentity id, UnitFilm *f, Error *err)
{
    Error init = {0};
    cr_assert(unit_film_init(f, &id.grid, &init));
    memset(err, 0, sizeof *err);
    bool ok = checkpoint_read(path, id, f, err);
    if (!ok) {
        cr_expect(film_is_empty(f), "a refused checkpoint left data in the film");
        cr_expect(strstr(err->message, path), "the message names the file: %s", err->message);
        cr_expect(!strchr(err->message, '\n'), "one line: %s", err->message);
    }
    return ok;
}

static void write_tiny(const char *path, RenderIdentity id, UnitFilm *f)
{
    fill_film(f, &id, 42);
    Error err = {0};
    cr_assert(checkpoint_write(path, id, f, &err), "%s", err.message);
}

/* The tests of damaged files start from a tiny checkpoint written, and its bytes. */
typedef struct {
    RenderIdentity id;
    const char *path;
    UnitFilm film; /* what was written */
    size_t size;
} Tiny;

static uint8_t *tiny_setup(Tiny *t)
{
    t->id = tiny_identity();
    t->path = checkpoint_file();
    write_tiny(t->path, t->id, &t->film);
    uint8_t *data = (uint8_t *)test_read_file(t->path, &t->size);
    cr_assert(data, "cannot read %s back", t->path);
    return data;
}

static void write_bytes(const char *path, const uint8_t *data, size_t size)
{
    FILE *file = fopen(path, "wb");
    cr_assert(file);
    cr_assert_eq(fwrite(data, 1, size, file), size);
    fclose(file);
}

Test(checkpoint_file, round_trip_keeps_every_bit_and_leaves_no_temporary_file)
{
    RenderIdentity id = tiny_identity();
    const char *path = checkpoint_file();
    UnitFilm a, b;
    write_tiny(path, id, &a);
    Error err;
    cr_assert(read_back(path, id, &b, &err), "%s", err.message);
    cr_expect_eq(b.units_done, a.units_done);
    cr_expect_arr_eq(b.done, a.done, unit_bitmap_bytes(a.grid.count));
    cr_expect_arr_eq(b.sums, a.sums, a.num_pixels * FILM_BYTES_PER_PIXEL);
    char temp[256];
    snprintf(temp, sizeof temp, "%s.tmp-%d", path, (int)getpid());
    cr_expect_neq(access(temp, F_OK), 0, "%s left behind", temp);
    unit_film_free(&a), unit_film_free(&b);
}

/* Every bit of the file matters: flipping any one is refused (the checksum, or a header check
 * before it), never accepted as another film. */
Test(checkpoint_file, every_flipped_bit_is_refused)
{
    Tiny t;
    uint8_t *good = tiny_setup(&t);
    RenderIdentity id = t.id;
    const char *path = t.path;
    cr_assert_eq(t.size,
                 CHECKPOINT_HEADER_BYTES + 8 + t.film.num_pixels * FILM_BYTES_PER_PIXEL + 8);
    uint8_t *bad = malloc(t.size);
    for (size_t byte = 0; byte < t.size; byte++) {
        int bit = (int)(byte * 5 % 8);
        memcpy(bad, good, t.size);
        bad[byte] ^= (uint8_t)(1u << bit);
        write_bytes(path, bad, t.size);
        UnitFilm b;
        Error err;
        cr_expect_not(read_back(path, id, &b, &err), "bit %d of byte %zu flipped: accepted", bit,
                      byte);
        if (byte >= CHECKPOINT_HEADER_BYTES)
            cr_expect(strstr(err.message, "checksum mismatch"), "byte %zu: %s", byte, err.message);
        unit_film_free(&b);
    }
    free(bad), free(good), unit_film_free(&t.film);
}

Test(checkpoint_file, every_truncation_and_a_trailing_byte_are_refused)
{
    Tiny t;
    uint8_t *good = tiny_setup(&t);
    RenderIdentity id = t.id;
    const char *path = t.path;
    for (size_t length = 0; length < t.size; length++) {
        write_bytes(path, good, length);
        UnitFilm b;
        Error err;
        cr_expect_not(read_back(path, id, &b, &err), "%zu of %zu bytes: accepted", length, t.size);
        const char *why = length < 8 ? "not a pt checkpoint" : "truncated checkpoint";
        cr_expect(strstr(err.message, why), "%zu bytes: %s", length, err.message);
        unit_film_free(&b);
    }
    uint8_t *longer = calloc(t.size + 1, 1);
    memcpy(longer, good, t.size);
    write_bytes(path, longer, t.size + 1);
    UnitFilm b;
    Error err;
    cr_expect_not(read_back(path, id, &b, &err));
    cr_expect(strstr(err.message, "damaged checkpoint"), "%s", err.message);
    unit_film_free(&b), free(longer), free(good), unit_film_free(&t.film);
}

/* Another version is named as such even when its checksum is right (a future format). */
Test(checkpoint_file, another_version_is_named)
{
    Tiny t;
    uint8_t *data = tiny_setup(&t);
    RenderIdentity id = t.id;
    const char *path = t.path;
    data[8] = CHECKPOINT_VERSION + 1;
    uint64_t checksum = hash64(data, t.size - 8);
    for (int i = 0; i < 8; i++)
        data[t.size - 8 + i] = (uint8_t)(checksum >> 8 * i);
    write_bytes(path, data, t.size);
    UnitFilm b;
    Error err;
    cr_expect_not(read_back(path, id, &b, &err));
    cr_expect(strstr(err.message, "checkpoint format version 2, this pt reads version 1"), "%s",
              err.message);
    data[0] = 'X';
    write_bytes(path, data, t.size);
    unit_film_free(&b);
    cr_expect_not(read_back(path, id, &b, &err));
    cr_expect(strstr(err.message, "not a pt checkpoint (wrong magic)"), "%s", err.message);
    unit_film_free(&b), free(data), unit_film_free(&t.film);
}

Test(checkpoint_file, no_checkpoint_says_start_without_resume)
{
    RenderIdentity id = tiny_identity();
    char path[128];
    snprintf(path, sizeof path, "%s/none.ptckpt", test_temp_dir());
    UnitFilm b;
    Error err;
    cr_expect_not(read_back(path, id, &b, &err));
    cr_expect_eq(err.code, ERR_FILE_MISSING);
    cr_expect(strstr(err.message, "no checkpoint at"), "%s", err.message);
    cr_expect(strstr(err.message, "start without --resume"), "%s", err.message);
    unit_film_free(&b);
}

/* Each part of the identity is compared, and the refusal says which differs. */
Test(checkpoint_file, another_render_is_refused_saying_what_differs)
{
    RenderIdentity id = tiny_identity();
    const char *path = checkpoint_file();
    UnitFilm a;
    write_tiny(path, id, &a);
    Error e = {0};
    struct {
        RenderIdentity id;
        const char *needle;
    } other[8];
    for (int i = 0; i < 8; i++)
        other[i].id = id;
    other[0].id.scene ^= 1, other[0].needle = "made for another scene";
    other[1].id.max_depth = 4, other[1].needle = "max depth 8 in it, 4 here";
    other[2].id.seed = 8, other[2].needle = "seed 7 in it, 8 here";
    other[3].id.first_sample = 16, other[3].needle = "first sample 0 in it, 16 here";
    other[4].id.no_nee = true, other[4].needle = "--no-nee off in it, on here";
    other[5].id.clamp_indirect = 10.0f, other[5].needle = "--clamp 0 in it, 10 here";
    cr_assert(unit_grid_init(&other[6].id.grid, 5, 6, 8, 1, 2, &e));
    other[6].needle = "spp 4 in it, 8 here";
    cr_assert(unit_grid_init(&other[7].id.grid, 5, 6, 4, 2, 2, &e));
    other[7].needle =
        "unit size differs: its units are 1 spp x 2 rows, this render's 2 spp x 2 rows";
    for (int i = 0; i < 8; i++) {
        UnitFilm b;
        Error err;
        cr_expect_not(read_back(path, other[i].id, &b, &err), "%s: accepted", other[i].needle);
        cr_expect(strstr(err.message, other[i].needle), "expected '%s' in: %s", other[i].needle,
                  err.message);
        unit_film_free(&b);
    }
    unit_film_free(&a);
}

/* The streaming hash does not depend on how the bytes are split into calls. */
Test(checkpoint_file, hash64_is_independent_of_the_split)
{
    uint8_t data[100];
    for (int i = 0; i < 100; i++)
        data[i] = (uint8_t)(i * 37 + 11);
    uint64_t whole = hash64(data, sizeof data);
    for (size_t a = 0; a <= sizeof data; a += 3) {
        for (size_t b = a; b <= sizeof data; b += 7) {
            Hash64 s;
            hash64_init(&s);
            hash64_bytes(&s, data, a);
            hash64_bytes(&s, data + a, b - a);
            hash64_bytes(&s, data + b, sizeof data - b);
            cr_expect_eq(hash64_finish(&s), whole, "split at %zu, %zu", a, b);
        }
    }
    cr_expect_neq(hash64(data, 99), whole);
    uint8_t zero[8] = {0};
    cr_expect_neq(hash64(zero, 7), hash64(zero, 8), "the length is part of the hash");
}

static uint64_t hash_of(const char *scene_path, void (*change)(Scene *))
{
    Scene scene;
    Error err = {0};
    warnings_set_quiet(true); /* the MTL's unused statements */
    cr_assert(scene_load(scene_path, &scene, &err), "%s", err.message);
    if (change)
        change(&scene);
    uint64_t h = scene_hash(&scene);
    scene_free(&scene);
    return h;
}

static void move_a_vertex(Scene *s) { s->data.positions[1].x += 1e-6f; }
static void change_a_material(Scene *s) { s->data.materials[0].roughness += 0.01f; }
static void change_a_texel(Scene *s)
{
    s->data.textures.texels[s->data.textures.num_texels / 2] ^= 1u;
}
static void move_the_camera(Scene *s) { s->desc.camera.eye[2] += 1e-3f; }
static void change_the_background(Scene *s) { s->desc.background[1] += 0.5f; }
static void change_the_film(Scene *s) { s->desc.width++; }
static void change_an_instance(Scene *s) { s->data.instances[0].to_world.m[0][3] += 1.0; }

Test(checkpoint_file, scene_hash_is_stable_and_sees_every_input_of_the_image)
{
    const char *scene = "tests/scenes/textured";
    uint64_t h = hash_of(scene, NULL);
    cr_expect_eq(hash_of(scene, NULL), h, "two loads of one scene hash alike");
    void (*changes[])(Scene *) = {move_a_vertex,         change_a_material, change_a_texel,
                                  move_the_camera,       change_the_background,
                                  change_the_film,       change_an_instance};
    for (size_t i = 0; i < sizeof changes / sizeof changes[0]; i++)
        cr_expect_neq(hash_of(scene, changes[i]), h, "change %zu left the hash alike", i);
    cr_expect_neq(hash_of("scenes/cornell-box", NULL), h);
}
