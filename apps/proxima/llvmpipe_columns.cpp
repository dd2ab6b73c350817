#include "llvmpipe_columns.h"

#include <cmath>
#include <cstdio>
#include <filesystem>

#include <nlohmann/json.hpp>

namespace proxima::cli {

namespace {

std::filesystem::path harness_path() {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::filesystem::path() : self.parent_path() / "proxima_llvmpipe_bench";
}

// One harness run; NaN (and the reason in *why) when it is absent or fails.
double harness_ms(const std::string& command, std::string* why) {
  FILE* pipe = popen((command + " 2>/dev/null").c_str(), "r");
  if (!pipe) {
    *why = "cannot start the llvmpipe harness";
    return std::nan("");
  }
  std::string text;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, pipe)) > 0) text.append(buf, n);
  const int status = pclose(pipe);
  if (status != 0) {
    *why = "llvmpipe harness failed (exit status " + std::to_string(status) + "; EGL/llvmpipe unavailable?)";
    return std::nan("");
  }
  try {
    return nlohmann::json::parse(text).at("ms_depth_id").get<double>();
  } catch (const std::exception& e) {
    *why = std::string("llvmpipe harness printed unreadable output: ") + e.what();
    return std::nan("");
  }
}

}  // namespace

LlvmpipeTimes llvmpipe_run(const std::string& scene, const study::RasterBenchStudyOptions& o,
                           const Results& results) {
  LlvmpipeTimes t;
  const std::filesystem::path harness = harness_path();
  const bool present = !harness.empty() && std::filesystem::exists(harness);
  if (!present) t.why = "llvmpipe harness not built (needs libegl-dev libgl-dev)";
  for (const auto& row : results.tables.back().rows) {  // the timing table: threads in column 0
    if (!present) {
      t.ms_depth_id.push_back(std::nan(""));
      continue;
    }
    std::string command = harness.string() + " --scene " + scene + " --width " + std::to_string(o.width) +
                          " --height " + std::to_string(o.height) + " --threads " +
                          std::to_string(int(std::get<double>(row[0]))) + " --repetitions " + std::to_string(o.reps);
    if (!o.camera.camera.empty()) command += " --camera " + o.camera.camera;
    t.ms_depth_id.push_back(harness_ms(command, &t.why));
  }
  return t;
}

void add_llvmpipe_columns(Results& results, const LlvmpipeTimes& llvmpipe) {
  Table& speed = results.tables.back();
  speed.columns.push_back("llvmpipe_depth_id_ms");
  speed.columns.push_back("speedup_vs_llvmpipe");
  for (size_t i = 0; i < speed.rows.size(); ++i) {
    const double gl = llvmpipe.ms_depth_id[i], speedup = gl / std::get<double>(speed.rows[i][1]);
    speed.rows[i].push_back(gl);
    speed.rows[i].push_back(speedup);
    const std::string suffix = i + 1 == speed.rows.size() ? "" : "_1t";  // the last row is all threads
    results.metrics["llvmpipe_ms_depth_id" + suffix] = gl;
    results.metrics["speedup_vs_llvmpipe" + suffix] = speedup;
  }
  if (!llvmpipe.why.empty())
    std::fprintf(stderr, "proxima: bench raster: %s; llvmpipe columns left empty\n", llvmpipe.why.c_str());
}

}  // namespace proxima::cli
