// All-or-nothing file output: write into a temporary file beside the target, then rename.
// A writer that throws leaves no file behind (DESIGN.md: never a partial file).
#pragma once

#include <filesystem>
#include <functional>
#include <string>

namespace proxima {

// Calls write(tmp_path); on success renames tmp_path to `path`, on any exception removes
// it and rethrows. Throws InputError naming `path` when the directory is not writable.
void write_atomically(const std::filesystem::path& path,
                      const std::function<void(const std::filesystem::path& tmp)>& write);

// Text content written atomically.
void write_text_file(const std::filesystem::path& path, const std::string& text);

}  // namespace proxima
