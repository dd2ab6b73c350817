#include "proxima/sweep/frame_parts.h"

#include <stdexcept>

#include <nlohmann/json.hpp>

#include "proxima/sweep/bytes.h"

namespace proxima::sweep {

namespace {

using nlohmann::json;

// figures.bin: the number of series, then each as its values (sweep/bytes.h).
std::string pack_figures(const study::FrameFigures& f) {
  ByteWriter w;
  w.put(uint64_t(f.series.size()));
  for (const std::vector<double>& s : f.series) w.put_span(std::span<const double>(s));
  return std::move(w.out);
}

study::FrameFigures unpack_figures(std::string_view in) {
  ByteReader r{in, "figures.bin"};
  study::FrameFigures f;
  const uint64_t n = r.get<uint64_t>();
  r.need(n, sizeof(uint64_t));  // each series has at least its count
  f.series.resize(n);
  for (std::vector<double>& s : f.series) s = r.get_vector<double>();
  r.expect_end();
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
    for (const auto& [name, data] : part.files.files) write_bytes(out.dir / name, data);
  }
  Results results = study::study_part_results(study, scene, options, figures);
  if (out.writes()) results.images = images;
  return results;
}

}  // namespace proxima::sweep
