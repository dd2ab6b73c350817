#include "proxima/sweep/gibr_photos.h"

#include <cstring>
#include <stdexcept>
#include <type_traits>

#include "proxima/study/gibr.h"
#include "proxima/sweep/bytes.h"

namespace proxima::sweep {

namespace {

void put_layers(ByteWriter& w, const gibr::PhotoLayers& p) {
  w.put(uint64_t(p.pixels_mapped));
  w.put(uint64_t(p.layers.size()));
  for (const auto& [polygon, L] : p.layers) {
    w.put(polygon);
    for (int v : {int(L.photo), L.x0, L.y0, L.width, L.height}) w.put(v);
    w.put(uint64_t(L.mixed));
    w.put_span(std::span<const uint32_t>(L.rgba));
    w.put_span(std::span<const uint8_t>(L.reach));
    w.put_span(std::span<const uint8_t>(L.reach_mixed));
  }
}

gibr::PhotoLayers get_layers(ByteReader& r) {
  gibr::PhotoLayers p;
  p.pixels_mapped = r.get<uint64_t>();
  const uint64_t n = r.get<uint64_t>();
  for (uint64_t i = 0; i < n; ++i) {
    const uint32_t polygon = r.get<uint32_t>();
    gibr::SampleLayer L;
    L.photo = uint32_t(r.get<int>());
    L.x0 = r.get<int>();
    L.y0 = r.get<int>();
    L.width = r.get<int>();
    L.height = r.get<int>();
    L.mixed = r.get<uint64_t>();
    L.rgba = r.get_vector<uint32_t>();
    L.reach = r.get_vector<uint8_t>();
    L.reach_mixed = r.get_vector<uint8_t>();
    if (L.width < 0 || L.height < 0 || L.rgba.size() != size_t(L.width) * size_t(L.height))
      r.fail("a layer of the wrong size");
    p.layers.emplace_back(polygon, std::move(L));
  }
  return p;
}

}  // namespace

std::string pack_photo_mapping(const gibr::PhotoMapping& m) {
  ByteWriter w;
  w.put(m.photo.width());
  w.put(m.photo.height());
  w.put(m.photo.channels());
  w.put_span(m.photo.data());
  w.put(m.silhouette_edges);
  const visibility::MapCheck& c = m.check;
  w.put(c.pass);
  w.put_string(c.reason);
  w.put(c.area_ratio);
  for (size_t v : {c.samples, c.skipped_near_edge, c.uncovered, c.multiply_covered, c.mismatches,
                   c.background_on_geometry, c.coplanar_ties})
    w.put(uint64_t(v));
  w.put(c.ms);
  put_layers(w, m.layers);
  put_layers(w, m.item_layers);
  for (double t : {m.photo_ms, m.vismap_ms, m.itembuffer_ms, m.map_ms, m.item_map_ms}) w.put(t);
  return std::move(w.out);
}

gibr::PhotoMapping unpack_photo_mapping(std::string_view bytes) {
  ByteReader r{bytes, "photo.bin"};
  gibr::PhotoMapping m;
  const int width = r.get<int>(), height = r.get<int>(), channels = r.get<int>();
  if (width < 0 || height < 0 || channels < 0 || width > 65536 || height > 65536 || channels > 4 ||
      (channels == 0 && (width != 0 || height != 0)))
    r.fail("a bad image size");
  r.need(sizeof(uint64_t) + size_t(width) * size_t(height) * size_t(channels) * sizeof(float));  // before allocating
  if (channels > 0) m.photo = ImageF(width, height, channels);
  r.get_into(m.photo.data());
  m.silhouette_edges = r.get<double>();
  visibility::MapCheck& c = m.check;
  c.pass = r.get_bool();
  c.reason = r.get_string();
  c.area_ratio = r.get<double>();
  for (size_t* v : {&c.samples, &c.skipped_near_edge, &c.uncovered, &c.multiply_covered, &c.mismatches,
                    &c.background_on_geometry, &c.coplanar_ties})
    *v = r.get<uint64_t>();
  c.ms = r.get<double>();
  m.layers = get_layers(r);
  m.item_layers = get_layers(r);
  for (double* t : {&m.photo_ms, &m.vismap_ms, &m.itembuffer_ms, &m.map_ms, &m.item_map_ms}) *t = r.get<double>();
  r.expect_end();
  return m;
}

std::string run_gibr_photo(const Scene& scene, const study::OptionValues& options, int photo) {
  const study::GibrOptions o = study::gibr_options(options);
  study::validate(o);
  const gibr::GibrModelOptions mo = study::gibr_model_options(o);
  const gibr::GibrModel g = gibr::prepare_gibr_model(scene, mo);
  if (photo < 0) throw std::runtime_error("sweep: photograph " + std::to_string(photo));
  if (size_t(photo) >= g.cameras.size()) return {};  // fewer poses than asked for: nothing to map
  gibr::PhotoMapping m = gibr::map_photograph(g, size_t(photo), mo);
  if (!o.photo_images) m.photo = ImageF();
  return pack_photo_mapping(m);
}

Results run_gibr_with_photos(const Scene& scene, const study::OptionValues& options, const study::StudyOutput& out,
                             const std::vector<std::string>& photos) {
  study::GibrOptions o = study::gibr_options(options);
  o.model.photographs = [&photos](const gibr::GibrModel&) {
    std::vector<gibr::PhotoMapping> mappings;
    for (const std::string& bytes : photos)
      if (!bytes.empty()) mappings.push_back(unpack_photo_mapping(bytes));
    return mappings;
  };
  return study::run_gibr(scene, o, out);
}

}  // namespace proxima::sweep
