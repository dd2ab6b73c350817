#include "proxima/sweep/gibr_photos.h"

#include <cstring>
#include <stdexcept>
#include <type_traits>

#include "proxima/core/error.h"
#include "proxima/study/gibr.h"

namespace proxima::sweep {

namespace {

// Plain little-endian-as-the-host bytes: items travel between ranks of one cluster, and a
// stored photo.bin is read back by the same binary (its identity is checked by the sweep).
struct Writer {
  std::string out;
  template <typename T>
    requires std::is_trivially_copyable_v<T>
  void put(const T& v) {
    out.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  template <typename T>
  void put_span(std::span<const T> v) {
    put(uint64_t(v.size()));
    out.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  void put_string(const std::string& s) { put_span(std::span<const char>(s.data(), s.size())); }
};

struct Reader {
  std::string_view in;
  size_t at = 0;
  [[noreturn]] static void fail(const std::string& what) { fail_input("sweep: photo.bin: " + what); }
  // `n` elements of `size` bytes are left (no overflow for any n).
  void need(uint64_t n, size_t size = 1) const {
    if (n > (in.size() - at) / size) fail("truncated");
  }
  template <typename T>
    requires std::is_trivially_copyable_v<T>
  T get() {
    need(sizeof(T));
    T v;
    std::memcpy(&v, in.data() + at, sizeof v);
    at += sizeof v;
    return v;
  }
  bool get_bool() {
    const uint8_t b = get<uint8_t>();
    if (b > 1) fail("a flag that is neither 0 nor 1");
    return b == 1;
  }
  // n elements of T into `dst` (sized n first by the caller).
  template <typename T>
  void get_into(std::span<T> dst) {
    const uint64_t n = get<uint64_t>();
    if (n != dst.size()) fail("an array of the wrong size");
    need(n, sizeof(T));
    if (n) std::memcpy(dst.data(), in.data() + at, n * sizeof(T));
    at += n * sizeof(T);
  }
  template <typename T>
  std::vector<T> get_vector() {
    const uint64_t n = get<uint64_t>();
    need(n, sizeof(T));
    std::vector<T> v(n);
    if (n) std::memcpy(v.data(), in.data() + at, n * sizeof(T));
    at += n * sizeof(T);
    return v;
  }
  std::string get_string() {
    const std::vector<char> c = get_vector<char>();
    return {c.begin(), c.end()};
  }
};

void put_layers(Writer& w, const gibr::PhotoLayers& p) {
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

gibr::PhotoLayers get_layers(Reader& r) {
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
      Reader::fail("a layer of the wrong size");
    p.layers.emplace_back(polygon, std::move(L));
  }
  return p;
}

}  // namespace

std::string pack_photo_mapping(const gibr::PhotoMapping& m) {
  Writer w;
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
  Reader r{bytes};
  gibr::PhotoMapping m;
  const int width = r.get<int>(), height = r.get<int>(), channels = r.get<int>();
  if (width < 0 || height < 0 || channels < 0 || width > 65536 || height > 65536 || channels > 4 ||
      (channels == 0 && (width != 0 || height != 0)))
    Reader::fail("a bad image size");
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
  if (r.at != bytes.size()) Reader::fail("trailing bytes");
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
