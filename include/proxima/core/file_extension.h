// A path's extension in lower case (".obj" for "Model.OBJ"): file formats are chosen by
// extension case-blind everywhere in proxima.
#pragma once

#include <cctype>
#include <filesystem>
#include <string>

namespace proxima {

inline std::string lowercase_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

}  // namespace proxima
