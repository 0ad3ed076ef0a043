// SPDX-License-Identifier: MIT
#include "base/parallel_for.h"

#include <pthread.h>
#include <stdbool.h>
#include <unistd.h>

#define PARALLEL_FOR_MAX_THREADS 16

typedef struct {
    void (*body)(void *ctx, size_t begin, size_t end);
    void *ctx;
    size_t begin, end;
} Chunk;

static void *run_chunk(void *arg)
{
    Chunk *c = arg;
    c->body(c->ctx, c->begin, c->end);
    return NULL;
}

void parallel_for(size_t count, size_t min_per_thread, void (*body)(void *ctx, size_t begin, size_t end),
                  void *ctx)
{
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    size_t threads = cores > 1 ? (size_t)cores : 1;
    if (threads > PARALLEL_FOR_MAX_THREADS)
        threads = PARALLEL_FOR_MAX_THREADS;
    if (min_per_thread < 1)
        min_per_thread = 1;
    if (threads > count / min_per_thread)
        threads = count / min_per_thread;
    if (threads <= 1) {
        if (count > 0)
            body(ctx, 0, count);
        return;
    }
    Chunk chunks[PARALLEL_FOR_MAX_THREADS];
    pthread_t ids[PARALLEL_FOR_MAX_THREADS];
    bool started[PARALLEL_FOR_MAX_THREADS] = {false};
    for (size_t t = 0; t < threads; t++)
        chunks[t] = (Chunk){body, ctx, count * t / threads, count * (t + 1) / threads};
    for (size_t t = 1; t < threads; t++)
        started[t] = pthread_create(&ids[t], NULL, run_chunk, &chunks[t]) == 0;
    run_chunk(&chunks[0]);
    for (size_t t = 1; t < threads; t++) {
        if (started[t])
            pthread_join(ids[t], NULL);
        else
            run_chunk(&chunks[t]);
    }
}
