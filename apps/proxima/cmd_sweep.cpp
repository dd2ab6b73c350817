// `proxima sweep MANIFEST --out DIR`: the study runs of a manifest as work items
// (sweep/sweep.h, docs/cli.md), in this process or, when an MPI launcher (mpirun, srun)
// started it, over the MPI ranks (sweep_ranks.h).
#include <cstdlib>
#include <iostream>

#include "command.h"
#include "proxima/core/error.h"
#include "proxima/core/parallel.h"
#include "proxima/sweep/sweep.h"
#include "sweep_ranks.h"

namespace proxima::cli {

namespace {

// Set by mpirun (OpenMPI), srun --mpi=pmix, and the PMI launchers of other MPIs.
bool started_by_mpi_launcher() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    if (std::getenv(v)) return true;
  return false;
}

int run(const std::string& manifest, const CommonOptions& common) {
  if (common.threads < 0) fail_input("--threads: must be ≥ 0");
  if (started_by_mpi_launcher()) return run_sweep_ranks({manifest, common.out, common.threads, command_line()});
  const sweep::Manifest m = sweep::read_manifest(manifest);
  const auto out = prepare_out_dir(common.out);
  ThreadLimit limit(common.threads);
  return report_sweep(out, sweep::run_sweep(m, out, command_line(), stderr));
}

}  // namespace

int report_sweep(const std::filesystem::path& out, const sweep::SweepSummary& summary) {
  const Results merged = read_results_json(out / "results.json");
  if (!merged.tables.empty()) std::cout << markdown_table(merged.tables.front()) << "\n";  // "sweep items"
  std::cout << "results: " << (out / "results.json").string() << ", report: " << (out / "index.html").string()
            << "\n";
  if (summary.failed)
    std::cerr << "sweep: " << summary.failed << " of " << summary.items << " items failed (see the table)\n";
  return summary.failed ? 1 : 0;
}

Command register_sweep(CLI::App& root) {
  static std::string manifest;
  static CommonOptions common;
  auto* app = root.add_subcommand(
      "sweep", "run the study runs of a manifest (JSON) as work items, in-process or over MPI ranks (mpirun/srun)");
  app->add_option("manifest", manifest, "manifest file (docs/cli.md: runs of a study on scenes, options, grids)")
      ->required();
  app->add_option("--threads", common.threads,
                  "worker threads per process (0 = all cores; under MPI: the node's cores / its ranks)")
      ->capture_default_str();
  add_out_flag(app, common);
  add_limit_flags(app);
  return {app, [] { return run(manifest, common); }};
}

}  // namespace proxima::cli
