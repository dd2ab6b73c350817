// proxima: render scenes through approximate representations and measure them against
// an exact ray-traced reference. One binary, one subcommand per file (command.h).
#include <exception>
#include <iostream>

#include "command.h"
#include "proxima/core/error.h"
#include "proxima/core/worker_threads.h"

int main(int argc, char** argv) {
  using namespace proxima;
  const WorkerThreadsJoinedAtExit workers;  // declared first: destroyed last, after every command
  cli::set_command_line(argc, argv);
  CLI::App root{"proxima — approximate representations of complex 3D scenes, measured against ray tracing"};
  root.require_subcommand(1);
  root.set_help_all_flag("--help-all", "help for every subcommand");
  std::vector<cli::Command> commands = {
      cli::register_scenes(root), cli::register_info(root), cli::register_render(root),
      cli::register_bench(root), cli::register_demo(root),
      cli::register_visibility(root),
      cli::register_sample(root),
      cli::register_reflect(root),
      cli::register_shadows(root),
      cli::register_view(root),
      cli::register_gibr(root),
      cli::register_results(root),
      cli::register_sweep(root),
  };
  try {
    root.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return root.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return root.exit(e);
  } catch (const CLI::ParseError& e) {
    // Unknown flags, bad values, missing subcommand: a one-line error and exit code 2.
    std::cerr << "proxima: " << e.what() << " (see --help)\n";
    return 2;
  }
  try {
    for (const auto& c : commands)
      if (c.app->parsed()) return c.run();
  } catch (const InputError& e) {
    std::cerr << "proxima: " << e.what() << "\n";
    return 2;
  } catch (const std::bad_alloc&) {
    std::cerr << "proxima: out of memory (try a smaller resolution or scene)\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "proxima: internal error: " << e.what() << "\n";
    return 1;
  }
  return 1;
}
