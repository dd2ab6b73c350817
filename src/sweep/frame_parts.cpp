#include "proxima/sweep/frame_parts.h"

#include <cstring>
#include <fstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

namespace proxima::sweep {

namespace {

using nlohmann::json;

// figures.bin: the number of series, then each as its length and its doubles (host order:
// the same binary reads them back, on the same cluster).
std::string pack_figures(const study::FrameFigures& f) {
  std::string out;
  const auto put = [&](uint64_t v) { out.append(reinterpret_cast<const char*>(&v), sizeof v); };
  put(f.series.size());
  for (const std::vector<double>& s : f.series) {
    put(s.size());
    out.append(reinterpret_cast<const char*>(s.data()), s.size() * sizeof(double));
  }
  return out;
}

study::FrameFigures unpack_figures(std::string_view in) {
  size_t at = 0;
  const auto get = [&]() {
    uint64_t v;
    if (in.size() - at < sizeof v) throw std::runtime_error("sweep: truncated figures.bin");
    std::memcpy(&v, in.data() + at, sizeof v);
    at += sizeof v;
    return v;
  };
  study::FrameFigures f;
  const uint64_t n = get();
  if (n > in.size() / sizeof(uint64_t)) throw std::runtime_error("sweep: figures.bin: too many series");
  f.series.resize(n);
  for (std::vector<double>& s : f.series) {
    const uint64_t k = get();
    if (k > (in.size() - at) / sizeof(double)) throw std::runtime_error("sweep: truncated figures.bin");
    s.resize(k);
    if (k) std::memcpy(s.data(), in.data() + at, k * sizeof(double));
    at += k * sizeof(double);
  }
  if (at != in.size()) throw std::runtime_error("sweep: figures.bin: trailing bytes");
  return f;
}

}  // namespace

std::string pack_frame_part(const FramePartData& part) {
  ItemFiles files = part.files;
  files.files.emplace_back("figures.bin", pack_figures(part.figures));
  files.files.emplace_back("images.json", json(part.images).dump());
  return pack_item(files);
}

FramePartData unpack_frame_part(std::string_view bytes) {
  FramePartData part;
  bool figures = false, images = false;
  for (auto& [name, data] : unpack_item(bytes).files) {
    if (name == "figures.bin") {
      part.figures = unpack_figures(data);
      figures = true;
    } else if (name == "images.json") {
      const json j = json::parse(data, nullptr, false);
      if (!j.is_object()) throw std::runtime_error("sweep: part.bin: bad images.json");
      for (const auto& [role, file] : j.items())
        if (file.is_string()) part.images[role] = file.get<std::string>();
      images = true;
    } else {
      part.files.files.emplace_back(std::move(name), std::move(data));
    }
  }
  if (!figures || !images) throw std::runtime_error("sweep: part.bin without its figures");
  return part;
}

Results run_with_frame_parts(const Scene& scene, const std::string& study, const study::OptionValues& options,
                             const study::StudyOutput& out, const std::vector<std::string>& parts) {
  study::FrameFigures figures;
  std::map<std::string, std::string> images;
  for (const std::string& bytes : parts) {
    const FramePartData part = unpack_frame_part(bytes);
    study::append_figures(figures, part.figures);
    images.insert(part.images.begin(), part.images.end());
    if (!out.writes()) continue;
    for (const auto& [name, data] : part.files.files) {
      const std::filesystem::path path = out.dir / name;
      std::filesystem::create_directories(path.parent_path());
      std::ofstream file(path, std::ios::binary);
      file.write(data.data(), std::streamsize(data.size()));
      if (!file) throw std::runtime_error(path.string() + ": cannot write");
    }
  }
  Results results = study::study_part_results(study, scene, options, figures);
  if (out.writes()) results.images = images;
  return results;
}

}  // namespace proxima::sweep
