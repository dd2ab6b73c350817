// The proxima command line: one binary, one file per subcommand. Each file registers its
// subcommand on the root CLI11 app and returns the action to run when it was chosen.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "proxima/core/camera.h"
#include "proxima/eval/results.h"
#include "proxima/scene/camera_select.h"
#include "proxima/scene/scene.h"

namespace proxima::cli {

struct Command {
  CLI::App* app;
  std::function<int()> run;  // exit code; throws InputError for bad input
};

// Flags most commands share (DESIGN.md): --scene, --width, --height, --threads, --seed, --out.
struct CommonOptions {
  std::string scene;
  int width = 512;
  int height = 512;
  int threads = 0;  // 0 = all cores
  uint64_t seed = 1;
  std::string out;
};

// Which of the common flags a command takes; add_common_flags adds them in this order. Their
// defaults are the values `CommonOptions` holds when they are added.
struct CommonFlagSet {
  const char* scene = nullptr;     // --scene with this default, and the limit flags; nullptr = none
  CameraChoice* camera = nullptr;  // --camera N|NAME, or --path P --frame F, into this choice
  bool size = true;                // --width, --height
  bool seed = true;                // --seed
  bool out = true;                 // --out: required unless CommonOptions::out holds a default
};
void add_common_flags(CLI::App* app, CommonOptions& o, const CommonFlagSet& flags);

// --max-triangles, --max-memory-mb (proxima/core/limits.h), applied while parsing.
void add_limit_flags(CLI::App* app);
// --out alone (required unless `o.out` holds a default).
void add_out_flag(CLI::App* app, CommonOptions& o);

// --width, --height into a study's options, and --seed and --threads where the options have
// such a field.
template <typename Options>
void set_common_options(const CommonOptions& common, Options& o) {
  o.width = common.width;
  o.height = common.height;
  if constexpr (requires { o.seed; }) o.seed = common.seed;
  if constexpr (requires { o.threads; }) o.threads = common.threads;
}

// Creates the output directory (InputError naming --out if impossible).
std::filesystem::path prepare_out_dir(const std::string& out);

// The argv this process was started with (for results.json).
const std::vector<std::string>& command_line();
void set_command_line(int argc, char** argv);

// Writes results.json into `out_dir` and prints its tables as Markdown on stdout.
void publish_results(const std::filesystem::path& out_dir, const Results& results);
// A study's results with this process's command line and thread count, published.
int publish_study(const std::filesystem::path& out_dir, Results results);

// Registration, one per subcommand file.
Command register_scenes(CLI::App& root);
Command register_info(CLI::App& root);
Command register_render(CLI::App& root);
Command register_bench(CLI::App& root);
Command register_demo(CLI::App& root);
Command register_visibility(CLI::App& root);
Command register_sample(CLI::App& root);
Command register_reflect(CLI::App& root);
Command register_shadows(CLI::App& root);
Command register_view(CLI::App& root);
Command register_bench_view(CLI::App& bench);  // `bench view`, cmd_bench_view.cpp
Command register_gibr(CLI::App& root);
Command register_results(CLI::App& root);  // cmd_results.cpp
Command register_sweep(CLI::App& root);    // cmd_sweep.cpp

}  // namespace proxima::cli
