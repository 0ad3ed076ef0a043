/* SPDX-License-Identifier: MIT */
/* mpi_link.h: this process as one rank of an MPI job, or alone. pt links MPI always but starts it
 * only when a launcher started pt (mpirun, srun: its environment says so), so a pt run by hand
 * never needs an MPI daemon; `mpirun -n 1` is one process that happens to call MPI_Init.
 *
 * Thread level: MPI_THREAD_FUNNELED. Only the main thread calls MPI: it relays the device
 * threads' requests (dist/render_ranks.h) and polls with MPI_Iprobe between short sleeps, because
 * OpenMPI's blocking calls spin a core while they wait, which a 2-core machine cannot spare, and
 * a request per run of units is too rare for the relay's latency (about a millisecond) to
 * matter. */
#ifndef PT_MPI_LINK_H
#define PT_MPI_LINK_H

#include <stdbool.h>

#include "base/error.h"

/* Whether a launcher started this process: OMPI_COMM_WORLD_SIZE (OpenMPI), PMIX_RANK (PMIx:
 * prterun, srun --mpi=pmix) or PMI_SIZE (MPICH's hydra, srun --mpi=pmi2) is set. */
bool mpi_link_launched(void);

/* Starts MPI when launched (else does nothing and this process is rank 0 of 1). Once started, an
 * exit without mpi_link_finalize (an error: die) ends the whole job (MPI_Abort), so that no rank
 * waits forever for one that has given up. */
bool mpi_link_init(int *argc, char ***argv, Error *err);
/* Ends MPI (when started): every rank calls it on its way out of a successful run. */
void mpi_link_finalize(void);

int mpi_link_rank(void); /* 0 alone */
int mpi_link_size(void); /* 1 alone */
/* This rank's place among the ranks of its node (OMPI_COMM_WORLD_LOCAL_RANK, else 0), to give
 * each rank of a node its own GPU. */
int mpi_link_local_rank(void);

#endif
