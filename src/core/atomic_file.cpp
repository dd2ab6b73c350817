#include "proxima/core/atomic_file.h"

#include <atomic>
#include <fstream>
#include <system_error>
#include <unistd.h>

#include "proxima/core/error.h"

namespace proxima {

namespace fs = std::filesystem;

void write_atomically(const fs::path& path, const std::function<void(const fs::path& tmp)>& write) {
  static std::atomic<unsigned> counter{0};
  fs::path dir = path.parent_path();
  std::error_code ec;
  if (!dir.empty() && !fs::is_directory(dir, ec))
    fail_input(path.string() + ": directory " + dir.string() + " does not exist");
  // The temporary keeps the target's extension: some writers choose the format by it.
  std::string name = ".";
  name += path.stem().string();
  name += ".tmp" + std::to_string(::getpid()) + "_" + std::to_string(counter++);
  name += path.extension().string();
  fs::path tmp = path;
  tmp.replace_filename(name);
  try {
    write(tmp);
    fs::rename(tmp, path, ec);
    if (ec) fail_input(path.string() + ": cannot write: " + ec.message());
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
}

void write_text_file(const fs::path& path, const std::string& text) {
  write_atomically(path, [&](const fs::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out << text;
    out.close();
    if (!out) fail_input(path.string() + ": cannot write");
  });
}

}  // namespace proxima
