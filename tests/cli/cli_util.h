// Running the proxima binary from tests: exit code and combined output.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "test_util.h"  // write_file, TempDir

namespace proxima {

struct RunResult {
  int exit_code;       // −1 when the process did not exit normally (a crash)
  std::string output;  // stdout + stderr
};

// `proxima ARGS` (with optional environment assignments in `env`, e.g. "X=1 ").
inline RunResult run_cli(const std::string& args, const std::string& env = "") {
  std::string cmd = env + std::string(PROXIMA_CLI_PATH) + " " + args + " 2>&1 </dev/null";
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return {-1, "popen failed"};
  std::string output;
  std::array<char, 4096> buf;
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) output.append(buf.data(), n);
  int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

}  // namespace proxima
