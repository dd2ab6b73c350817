// `proxima sweep` under mpirun in a build without MPI: refused, rather than every rank
// running the whole sweep into the same directory.
#include "../sweep_ranks.h"
#include "proxima/core/error.h"

namespace proxima::cli {

int run_sweep_ranks(const SweepRun&) {
  fail_input(
      "sweep: started by an MPI launcher, but this proxima was built without MPI (install libopenmpi-dev and "
      "configure with -DPROXIMA_MPI=ON), or run it without mpirun/srun");
}

}  // namespace proxima::cli
