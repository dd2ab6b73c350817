// The MPI transport of `proxima sweep` (apps/proxima/mpi/): one of two implementations is
// linked, by whether the build found MPI (CMake option PROXIMA_MPI), so the library itself
// never depends on MPI.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "proxima/sweep/sweep.h"

namespace proxima::cli {

struct SweepRun {
  std::string manifest;  // the manifest file (read by rank 0, sent to the others)
  std::string out;       // DIR, written by rank 0 only
  int threads = 0;       // per rank; 0 = the node's cores / the ranks on the node
  std::vector<std::string> command;
};

// Runs the sweep over the ranks of MPI_COMM_WORLD: rank 0 hands out items one at a time to
// whichever rank asks (itself included, on a second thread), stores each finished item and
// merges; returns the exit code (0 all items ok, 1 some failed). Built without MPI: throws
// InputError saying so.
int run_sweep_ranks(const SweepRun& run);

// Prints the merged "sweep items" table and where the results are; the exit code of a
// sweep (cmd_sweep.cpp).
int report_sweep(const std::filesystem::path& out, const sweep::SweepSummary& summary);

}  // namespace proxima::cli
