#include "command.h"

#include <iostream>
#include <system_error>

#include "proxima/core/error.h"
#include "proxima/core/limits.h"
#include "proxima/core/parallel.h"

namespace proxima::cli {

namespace {
std::vector<std::string> g_command_line;
}

void add_limit_flags(CLI::App* app) {
  auto setter = [](uint64_t Limits::*field, const char* flag) {
    return [field, flag](uint64_t v) {
      if (v == 0) throw CLI::ValidationError(flag, "must be positive");
      try {
        Limits l = limits();  // keeps the other limit (environment or default)
        l.*field = v;
        set_limits(l);
      } catch (const InputError& e) {  // a malformed PROXIMA_MAX_* variable
        throw CLI::ValidationError(flag, e.what());
      }
    };
  };
  app->add_option_function<uint64_t>("--max-triangles", setter(&Limits::max_triangles, "--max-triangles"),
                                     "refuse scenes with more triangles (default 50000000, env PROXIMA_MAX_TRIANGLES)");
  app->add_option_function<uint64_t>("--max-memory-mb", setter(&Limits::max_memory_mb, "--max-memory-mb"),
                                     "refuse scenes/images estimated to need more MiB (default 3/4 of RAM, env "
                                     "PROXIMA_MAX_MEMORY_MB)");
}

void add_out_flag(CLI::App* app, CommonOptions& o) {
  auto* opt = app->add_option("--out", o.out, "output directory (created if missing)");
  if (o.out.empty()) opt->required();
  else opt->capture_default_str();
}

void add_common_flags(CLI::App* app, CommonOptions& o, const CommonFlagSet& flags) {
  if (flags.scene) {
    o.scene = flags.scene;
    app->add_option("--scene", o.scene, "built-in scene name (see `proxima scenes`), .json scene file, or mesh file")
        ->capture_default_str();
    add_limit_flags(app);
  }
  if (flags.camera) {
    CameraChoice& choice = *flags.camera;
    auto* cam = app->add_option("--camera", choice.camera, "scene camera, by index or name (default: the first)");
    auto* path = app->add_option("--path", choice.path, "camera path, by index or name");
    app->add_option("--frame", choice.frame, "frame on the camera path (0-based)")->needs(path);
    cam->excludes(path);
  }
  if (flags.size) {
    app->add_option("--width", o.width, "image width in pixels")->capture_default_str();
    app->add_option("--height", o.height, "image height in pixels")->capture_default_str();
  }
  app->add_option("--threads", o.threads, "worker threads (0 = all cores); results do not depend on it")
      ->capture_default_str();
  if (flags.seed)
    app->add_option("--seed", o.seed, "random seed for every sampled quantity")->capture_default_str();
  if (flags.out) add_out_flag(app, o);
}

std::filesystem::path prepare_out_dir(const std::string& out) {
  std::filesystem::path dir(out);
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir))
    fail_input("--out: cannot create directory " + out + (ec ? ": " + ec.message() : ""));
  return dir;
}

const std::vector<std::string>& command_line() { return g_command_line; }

void set_command_line(int argc, char** argv) { g_command_line.assign(argv, argv + argc); }

void publish_results(const std::filesystem::path& out_dir, const Results& results) {
  write_results_json(out_dir / "results.json", results);
  for (const Table& t : results.tables) std::cout << markdown_table(t) << "\n";
  std::cout << "results: " << (out_dir / "results.json").string() << "\n";
}

int publish_study(const std::filesystem::path& out_dir, Results results) {
  results.command = command_line();
  results.threads = active_threads();
  publish_results(out_dir, results);
  return 0;
}

}  // namespace proxima::cli
