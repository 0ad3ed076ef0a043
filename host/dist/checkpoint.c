// SPDX-License-Identifier: MIT
#include "dist/checkpoint.h"
#include "scene/sampler.h"

#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/fs.h"
#include "io/input_file.h"
#include "render/film.h"
#include "scene/scene_hash.h"

static const uint8_t MAGIC[8] = {'P', 'T', 'C', 'K', 'P', 'T', '\r', '\n'};
/* FLAG_SOBOL: checkpoints written before the sampler existed (independent numbers) lack it. */
enum { FLAG_NO_NEE = 1u, FLAG_SOBOL = 2u };

RenderIdentity render_identity(const Scene *scene, const RenderSettings *settings,
                               const UnitGrid *grid)
{
    return (RenderIdentity){.scene = scene_hash(scene),
                            .max_depth = (uint32_t)settings->max_depth,
                            .seed = settings->seed,
                            .first_sample = settings->first_sample,
                            .no_nee = settings->no_nee,
                            .sobol = sampler_resolve(settings->sampler, scene->desc.sampler) ==
                                     SAMPLER_SOBOL,
                            .clamp_indirect = settings->clamp_indirect,
                            .grid = *grid};
}

void checkpoint_path(const char *output, char *out, size_t size)
{
    snprintf(out, size, "%s.ptckpt", output);
}

static void put32(uint8_t *p, uint32_t v)
{
    for (int i = 0; i < 4; i++)
        p[i] = (uint8_t)(v >> 8 * i);
}

static void put64(uint8_t *p, uint64_t v)
{
    put32(p, (uint32_t)v);
    put32(p + 4, (uint32_t)(v >> 32));
}

static uint32_t get32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static uint64_t get64(const uint8_t *p) { return get32(p) | (uint64_t)get32(p + 4) << 32; }

/* A float as its bits, both ways (reading a union's other member is defined in C11). */
typedef union {
    float value;
    uint32_t bits;
} FloatBits;

/* The bitmap's bytes in the file: a whole number of words, so the sums stay 8-byte aligned. */
static uint64_t bitmap_bytes64(uint32_t count) { return ((uint64_t)count + 7u) / 8u; }
static uint64_t bitmap_file_bytes(uint32_t count) { return (bitmap_bytes64(count) + 7u) / 8u * 8u; }

static void encode_header(uint8_t h[CHECKPOINT_HEADER_BYTES], const RenderIdentity *id,
                          uint32_t units_done)
{
    memset(h, 0, CHECKPOINT_HEADER_BYTES);
    memcpy(h, MAGIC, sizeof MAGIC);
    put32(h + 8, CHECKPOINT_VERSION);
    put32(h + 12, CHECKPOINT_HEADER_BYTES);
    put64(h + 16, id->scene);
    put32(h + 24, id->max_depth);
    put32(h + 28, id->seed);
    put32(h + 32, id->first_sample);
    put32(h + 36, (id->no_nee ? FLAG_NO_NEE : 0u) | (id->sobol ? FLAG_SOBOL : 0u));
    put32(h + 40, (FloatBits){.value = id->clamp_indirect}.bits);
    const UnitGrid *g = &id->grid;
    uint32_t grid[6] = {g->width, g->height, g->spp, g->unit_spp, g->unit_rows, g->count};
    for (int i = 0; i < 6; i++)
        put32(h + 44 + 4 * i, grid[i]);
    put32(h + 68, units_done);
    put32(h + 72, FILM_WORDS);
}

/* The file's fields as read (before they are trusted). */
typedef struct {
    RenderIdentity id;
    uint32_t version, header_bytes, flags, units_done, film_words, reserved;
} Header;

static void decode_header(const uint8_t h[CHECKPOINT_HEADER_BYTES], Header *out)
{
    memset(out, 0, sizeof *out);
    out->version = get32(h + 8);
    out->header_bytes = get32(h + 12);
    out->id.scene = get64(h + 16);
    out->id.max_depth = get32(h + 24);
    out->id.seed = get32(h + 28);
    out->id.first_sample = get32(h + 32);
    out->flags = get32(h + 36);
    out->id.no_nee = out->flags & FLAG_NO_NEE;
    out->id.sobol = out->flags & FLAG_SOBOL;
    out->id.clamp_indirect = (FloatBits){.bits = get32(h + 40)}.value;
    UnitGrid *g = &out->id.grid;
    g->width = get32(h + 44), g->height = get32(h + 48), g->spp = get32(h + 52);
    g->unit_spp = get32(h + 56), g->unit_rows = get32(h + 60), g->count = get32(h + 64);
    out->units_done = get32(h + 68);
    out->film_words = get32(h + 72);
    out->reserved = get32(h + 76);
}

/* Buffered output through the checksum. */
typedef struct {
    FILE *file;
    Hash64 hash;
    uint8_t buf[1 << 16];
    size_t used;
    bool ok;
} Writer;

static void writer_flush(Writer *w)
{
    hash64_bytes(&w->hash, w->buf, w->used);
    if (w->ok && fwrite(w->buf, 1, w->used, w->file) != w->used)
        w->ok = false;
    w->used = 0;
}

static void writer_put(Writer *w, const void *data, size_t size)
{
    const uint8_t *p = data;
    while (size) {
        size_t take = sizeof w->buf - w->used < size ? sizeof w->buf - w->used : size;
        memcpy(w->buf + w->used, p, take);
        w->used += take, p += take, size -= take;
        if (w->used == sizeof w->buf)
            writer_flush(w);
    }
}

static bool write_body(Writer *w, const RenderIdentity *id, UnitFilm *f)
{
    uint8_t header[CHECKPOINT_HEADER_BYTES];
    encode_header(header, id, f->units_done);
    writer_put(w, header, sizeof header);
    uint64_t bitmap = bitmap_file_bytes(f->grid.count);
    writer_put(w, f->done, unit_bitmap_bytes(f->grid.count));
    static const uint8_t zeros[8];
    writer_put(w, zeros, (size_t)(bitmap - unit_bitmap_bytes(f->grid.count)));
    size_t words = f->num_pixels * FILM_WORDS;
    for (size_t i = 0; i < words; i++) {
        uint8_t le[8];
        put64(le, f->sums[i]);
        writer_put(w, le, sizeof le);
    }
    writer_flush(w);
    uint8_t checksum[8];
    put64(checksum, hash64_finish(&w->hash));
    if (w->ok && fwrite(checksum, 1, sizeof checksum, w->file) != sizeof checksum)
        w->ok = false;
    return w->ok;
}

bool checkpoint_write(const char *path, RenderIdentity identity, UnitFilm *f, Error *err)
{
    if (!fs_check_writable(path, err))
        return false;
    char temp[PATH_MAX];
    fs_temp_path(path, temp, sizeof temp);
    Writer *w = calloc(1, sizeof *w); /* 64 KiB: off the stack */
    if (!w) {
        error_set(err, ERR_OUTPUT, path, 0, "%s: out of memory for a checkpoint's buffer", path);
        return false;
    }
    w->ok = true;
    hash64_init(&w->hash);
    w->file = fopen(temp, "wb");
    if (!w->file) {
        error_set(err, ERR_OUTPUT, path, 0, "%s: cannot create %s (%s)", path, temp,
                  strerror(errno));
        free(w);
        return false;
    }
    pthread_mutex_lock(&f->lock);
    bool written = write_body(w, &identity, f);
    pthread_mutex_unlock(&f->lock);
    int saved_errno = errno;
    if (fclose(w->file) != 0 && written)
        written = false, saved_errno = errno;
    free(w);
    if (!written)
        error_set(err, ERR_OUTPUT, path, 0, "%s: cannot write checkpoint %s (%s)", path, temp,
                  strerror(saved_errno));
    return fs_finish_atomic_write(temp, path, written, err);
}

/* Buffered input through the checksum. */
typedef struct {
    FILE *file;
    Hash64 hash;
    uint8_t buf[1 << 16];
} Reader;

static bool reader_get(Reader *r, void *data, size_t size)
{
    if (fread(data, 1, size, r->file) != size)
        return false;
    hash64_bytes(&r->hash, data, size);
    return true;
}

/* The sums: into f when the file's film is f's size, else only through the checksum. */
static bool read_sums(Reader *r, uint64_t words, uint64_t *sums)
{
    uint64_t done = 0;
    while (done < words) {
        size_t take = words - done < sizeof r->buf / 8 ? (size_t)(words - done) : sizeof r->buf / 8;
        if (!reader_get(r, r->buf, take * 8))
            return false;
        for (size_t i = 0; sums && i < take; i++)
            sums[done + i] = get64(r->buf + 8 * i);
        done += take;
    }
    return true;
}

/* The first difference between the checkpoint's render and this one, in words ("" when none). */
static void describe_difference(const RenderIdentity *a, const RenderIdentity *b, char *out,
                                size_t size)
{
    const UnitGrid *ga = &a->grid, *gb = &b->grid;
    const char *other = "made with other settings:";
    out[0] = 0;
    if (ga->width != gb->width || ga->height != gb->height)
        snprintf(out, size, "made for a %ux%u film, this render is %ux%u", ga->width, ga->height,
                 gb->width, gb->height);
    else if (ga->spp != gb->spp)
        snprintf(out, size, "%s spp %u in it, %u here", other, ga->spp, gb->spp);
    else if (a->max_depth != b->max_depth)
        snprintf(out, size, "%s max depth %u in it, %u here", other, a->max_depth, b->max_depth);
    else if (a->seed != b->seed)
        snprintf(out, size, "%s seed %u in it, %u here", other, a->seed, b->seed);
    else if (a->first_sample != b->first_sample)
        snprintf(out, size, "%s first sample %u in it, %u here", other, a->first_sample,
                 b->first_sample);
    else if (a->no_nee != b->no_nee)
        snprintf(out, size, "%s --no-nee %s in it, %s here", other, a->no_nee ? "on" : "off",
                 b->no_nee ? "on" : "off");
    else if (a->sobol != b->sobol)
        snprintf(out, size, "%s --sampler %s in it, %s here", other, a->sobol ? "sobol" : "independent",
                 b->sobol ? "sobol" : "independent");
    else if ((FloatBits){.value = a->clamp_indirect}.bits !=
             (FloatBits){.value = b->clamp_indirect}.bits)
        snprintf(out, size, "%s --clamp %g in it, %g here", other, (double)a->clamp_indirect,
                 (double)b->clamp_indirect);
    else if (ga->unit_spp != gb->unit_spp || ga->unit_rows != gb->unit_rows ||
             ga->count != gb->count)
        snprintf(out, size, "unit size differs: its units are %u spp x %u rows, this render's %u "
                 "spp x %u rows (--unit-spp, --unit-rows)", ga->unit_spp, ga->unit_rows,
                 gb->unit_spp, gb->unit_rows);
    else if (a->scene != b->scene)
        snprintf(out, size, "made for another scene (scene hash %016llx in it, %016llx here)",
                 (unsigned long long)a->scene, (unsigned long long)b->scene);
}

static int popcount8(uint8_t v)
{
    int n = 0;
    for (; v; v &= (uint8_t)(v - 1))
        n++;
    return n;
}

/* Reads and checks everything; f filled only when it returns true. */
static bool read_checkpoint(const char *path, FILE *file, RenderIdentity *want, UnitFilm *f,
                            Reader *r, uint8_t **bitmap, Error *err)
{
    struct stat info;
    if (fstat(fileno(file), &info) != 0 || !S_ISREG(info.st_mode)) {
        error_set(err, ERR_FILE_READ, path, 0, "%s: not a regular file", path);
        return false;
    }
    uint64_t size = (uint64_t)info.st_size;
    uint8_t raw[CHECKPOINT_HEADER_BYTES];
    if (size < 8 || !reader_get(r, raw, 8) || memcmp(raw, MAGIC, 8) != 0) {
        error_set(err, ERR_FILE_READ, path, 0, "%s: not a pt checkpoint (%s)", path,
                  size < 8 ? "shorter than its magic" : "wrong magic");
        return false;
    }
    if (size < CHECKPOINT_HEADER_BYTES + 8 ||
        !reader_get(r, raw + 8, CHECKPOINT_HEADER_BYTES - 8)) {
        error_set(err, ERR_FILE_READ, path, 0, "%s: truncated checkpoint (%llu bytes, shorter "
                  "than its header): remove it to start over", path, (unsigned long long)size);
        return false;
    }
    Header h;
    decode_header(raw, &h);
    if (h.version != CHECKPOINT_VERSION) {
        error_set(err, ERR_FILE_READ, path, 0, "%s: checkpoint format version %u, this pt reads "
                  "version %u: resume with the pt that wrote it, or remove it to start over", path,
                  h.version, CHECKPOINT_VERSION);
        return false;
    }
    const UnitGrid *g = &h.id.grid;
    if (h.header_bytes != CHECKPOINT_HEADER_BYTES || h.film_words != FILM_WORDS || h.reserved ||
        (h.flags & ~(uint32_t)(FLAG_NO_NEE | FLAG_SOBOL)) || g->width > FILM_SIZE_LIMIT ||
        g->height > FILM_SIZE_LIMIT) {
        error_set(err, ERR_FILE_READ, path, 0, "%s: damaged checkpoint (header fields out of "
                  "range): remove it to start over", path);
        return false;
    }
    uint64_t words = (uint64_t)g->width * g->height * FILM_WORDS;
    uint64_t bitmap_bytes = bitmap_file_bytes(g->count);
    uint64_t expected = CHECKPOINT_HEADER_BYTES + bitmap_bytes + 8 * words + 8;
    if (size != expected) {
        error_set(err, ERR_FILE_READ, path, 0, "%s: %s checkpoint (%llu bytes, its header says "
                  "%llu): remove it to start over", path, size < expected ? "truncated" : "damaged",
                  (unsigned long long)size, (unsigned long long)expected);
        return false;
    }
    bool fits = words == (uint64_t)f->num_pixels * FILM_WORDS;
    *bitmap = malloc(bitmap_bytes ? bitmap_bytes : 1);
    uint8_t stored[8];
    if (!*bitmap || !reader_get(r, *bitmap, bitmap_bytes) ||
        !read_sums(r, words, fits ? f->sums : NULL) || fread(stored, 1, 8, file) != 8) {
        error_set(err, ERR_FILE_READ, path, 0, "%s: cannot read the checkpoint (%s)", path,
                  *bitmap ? "a read error" : "out of memory");
        return false;
    }
    if (get64(stored) != hash64_finish(&r->hash)) {
        error_set(err, ERR_FILE_READ, path, 0, "%s: damaged checkpoint (checksum mismatch): remove "
                  "it to start over", path);
        return false;
    }
    char difference[256];
    describe_difference(&h.id, want, difference, sizeof difference);
    if (difference[0]) {
        error_set(err, ERR_SETTINGS, path, 0, "%s: %s: resume with the same scene and settings, or "
                  "remove it to start over", path, difference);
        return false;
    }
    /* A valid checksum with inconsistent content: a writer's bug, refused all the same. */
    uint64_t units = 0, used = bitmap_bytes64(g->count);
    for (uint64_t i = 0; i < bitmap_bytes; i++)
        units += (uint64_t)popcount8((*bitmap)[i]);
    bool stray = g->count % 8 && (*bitmap)[used - 1] >> (g->count % 8);
    for (uint64_t i = used; i < bitmap_bytes; i++)
        stray = stray || (*bitmap)[i];
    if (stray || units != h.units_done) {
        error_set(err, ERR_FILE_READ, path, 0, "%s: damaged checkpoint (%llu finished units in its "
                  "bitmap, %u in its header): remove it to start over", path,
                  (unsigned long long)units, h.units_done);
        return false;
    }
    memcpy(f->done, *bitmap, used);
    f->units_done = h.units_done;
    return true;
}

bool checkpoint_read(const char *path, RenderIdentity identity, UnitFilm *f, Error *err)
{
    /* A FIFO, folder or device in its place is refused by name before any read (input_file.h:
     * fopen would wait for a FIFO's writer forever). */
    long long size;
    int fd = input_file_open(path, "a pt checkpoint", &size, err);
    if (fd < 0 && err->code == ERR_FILE_MISSING) {
        *err = (Error){0}; /* say what to do instead */
        error_set(err, ERR_FILE_MISSING, path, 0, "no checkpoint at %s: start without --resume",
                  path);
    }
    FILE *file = fd >= 0 ? fdopen(fd, "rb") : NULL;
    if (fd >= 0 && !file) {
        error_set(err, ERR_FILE_READ, path, 0, "%s: cannot read the checkpoint (%s)", path,
                  strerror(errno));
        close(fd);
    }
    if (!file)
        return false;
    Reader *r = calloc(1, sizeof *r);
    uint8_t *bitmap = NULL;
    bool ok = r != NULL;
    if (!ok)
        error_set(err, ERR_FILE_READ, path, 0, "%s: out of memory for reading the checkpoint",
                  path);
    if (ok) {
        r->file = file;
        hash64_init(&r->hash);
        ok = read_checkpoint(path, file, &identity, f, r, &bitmap, err);
    }
    if (!ok) { /* nothing of a refused file stays */
        memset(f->sums, 0, f->num_pixels * FILM_BYTES_PER_PIXEL);
        memset(f->done, 0, unit_bitmap_bytes(f->grid.count));
        f->units_done = 0;
    }
    free(bitmap);
    free(r);
    fclose(file);
    return ok;
}
