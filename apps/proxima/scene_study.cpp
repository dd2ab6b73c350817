#include "scene_study.h"

#include <unistd.h>

#include <system_error>

namespace proxima::cli {

namespace {

namespace fs = std::filesystem;

// The outermost of `dir` and its ancestors that does not exist yet; empty if `dir` exists.
fs::path first_missing(const fs::path& dir) {
  fs::path missing;
  std::error_code ec;
  for (fs::path p = fs::absolute(dir, ec); !ec && !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
    missing = p;
    if (p == p.parent_path()) break;
  }
  return missing;
}

bool holds_no_file(const fs::path& dir) {
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec))
    if (!it->is_directory(ec)) return false;
  return !ec;
}

}  // namespace

bool progress_is_terminal() { return isatty(fileno(stderr)) != 0; }

Results run_in_out_dir(const std::string& out, const std::function<Results(const fs::path&)>& study) {
  const fs::path created = first_missing(out);
  const fs::path dir = prepare_out_dir(out);
  try {
    return study(dir);
  } catch (...) {
    std::error_code ec;
    if (!created.empty() && holds_no_file(created)) fs::remove_all(created, ec);
    throw;
  }
}

int publish_study(SceneStudyRun run) { return publish_study(run.out, std::move(run.results)); }

}  // namespace proxima::cli
