// SPDX-License-Identifier: GPL-3.0-or-later
// MPI for the `aquatoria` binary (README "The forest engine"). aquatoria stays one binary: MPI is
// started only when it is needed — when the process was launched by mpirun (its environment names
// a world size) or when a run asks for the forest engine (quadtree.engine = "forest"; a singleton
// MPI of one rank then) — so a run of the dense engine neither pays for MPI nor changes. Started,
// it also starts libsc and p4est with their own logging silenced (only rank 0 of aquatoria logs).
//
// Errors: a stage of the forest engine that fails on one rank fails on every rank with the same
// message and exit code (forest/comm.hpp agree()); what reaches main is settled by
// finish_run(), which every rank calls at the end: the lowest failing rank's message is printed
// once (by rank 0) and every rank exits with its code. This header does not include mpi.h.
#pragma once

#include <string>

namespace aq::forest {

/// Whether this process was started by mpirun/mpiexec (OpenMPI's OMPI_COMM_WORLD_SIZE, PMI's
/// PMI_SIZE or PMIx's PMIX_RANK in the environment).
[[nodiscard]] bool launched_by_mpirun();

/// Starts MPI (thread level FUNNELED: OpenMP threads never call MPI), libsc and p4est once;
/// later calls do nothing. argc/argv may be null (a singleton start inside a run).
void start_mpi(int* argc = nullptr, char*** argv = nullptr);
/// Whether start_mpi has run (and finish_run has not).
[[nodiscard]] bool mpi_running();
/// Rank and size of MPI_COMM_WORLD (0 and 1 when MPI is not running).
[[nodiscard]] int world_rank();
[[nodiscard]] int world_size();

/// The end of the process on every rank: `code` and `message` are this rank's outcome (0 and ""
/// when it succeeded). All ranks agree on the outcome of the lowest failing rank; rank 0 prints
/// its "error: ..." line (when `print` is true; the message of an error that passed through
/// agree() is the same on every rank), libsc and MPI are finalised, and the agreed code is
/// returned. Without MPI running it returns `code` and prints the message itself.
int finish_run(int code, const std::string& message, bool print = true);

/// Ends every rank now with `code` (MPI_Abort), after printing `message` with this rank's number:
/// the last resort for an error that could not be agreed on.
[[noreturn]] void abort_all(int code, const std::string& message);

}  // namespace aq::forest
