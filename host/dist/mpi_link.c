// SPDX-License-Identifier: MIT
#include "dist/mpi_link.h"

#include <mpi.h>
#include <stdlib.h>

static struct {
    bool started, finalized;
    int rank, size;
} g_mpi = {.size = 1};

bool mpi_link_launched(void)
{
    return getenv("OMPI_COMM_WORLD_SIZE") || getenv("PMIX_RANK") || getenv("PMI_SIZE");
}

/* An exit that skipped mpi_link_finalize. Alone in the job, MPI is simply ended; with other
 * ranks, they are waiting for this one: MPI_Abort ends them (mpirun prints which rank). */
static void end_unfinished(void)
{
    if (!g_mpi.started || g_mpi.finalized)
        return;
    g_mpi.finalized = true;
    if (g_mpi.size > 1)
        MPI_Abort(MPI_COMM_WORLD, 1);
    else
        MPI_Finalize();
}

bool mpi_link_init(int *argc, char ***argv, Error *err)
{
    if (!mpi_link_launched() || g_mpi.started)
        return true;
    int provided = MPI_THREAD_SINGLE;
    if (MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS) {
        error_set(err, ERR_MPI, NULL, 0, "MPI_Init_thread failed (started by mpirun?)");
        return false;
    }
    g_mpi.started = true;
    atexit(end_unfinished);
    MPI_Comm_rank(MPI_COMM_WORLD, &g_mpi.rank);
    MPI_Comm_size(MPI_COMM_WORLD, &g_mpi.size);
    if (provided < MPI_THREAD_FUNNELED) {
        error_set(err, ERR_MPI, NULL, 0,
                  "the MPI library gives thread level %d; pt needs MPI_THREAD_FUNNELED (%d)",
                  provided, MPI_THREAD_FUNNELED);
        return false;
    }
    return true;
}

void mpi_link_finalize(void)
{
    if (!g_mpi.started || g_mpi.finalized)
        return;
    g_mpi.finalized = true;
    MPI_Finalize();
}

int mpi_link_rank(void) { return g_mpi.rank; }
int mpi_link_size(void) { return g_mpi.size; }

int mpi_link_local_rank(void)
{
    const char *local = getenv("OMPI_COMM_WORLD_LOCAL_RANK");
    if (!local)
        local = getenv("MPI_LOCALRANKID"); /* MPICH */
    return local && g_mpi.started ? atoi(local) : 0;
}
