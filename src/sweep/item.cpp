#include "proxima/sweep/item.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <system_error>
#include <variant>

#include <nlohmann/json.hpp>

#include "proxima/core/atomic_file.h"
#include "proxima/core/error.h"
#include "proxima/core/parallel.h"
#include "proxima/core/timer.h"
#include "proxima/eval/results.h"
#include "proxima/scene/load.h"
#include "proxima/scene/visibility_models.h"
#include "proxima/sweep/bytes.h"
#include "proxima/sweep/frame_parts.h"
#include "proxima/sweep/gibr_photos.h"

namespace proxima::sweep {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// JSON of an option value; infinities as "inf" / "-inf" (JSON has none).
json value_json(const study::OptionValue& v) {
  return std::visit(
      [&](const auto& x) -> json {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<T, double>)
          if (std::isinf(x)) return study::option_text(v);
        return x;
      },
      v);
}

// What identifies an item's work: a stored item counts as finished only for the same one.
json item_identity(const SweepItem& item) {
  json options = json::object();
  for (const auto& [name, value] : study::resolved_options(item.study, item.options)) options[name] = value_json(value);
  json id = {{"id", item.id}, {"scene", item.scene}, {"study", item.study}, {"options", options}};
  if (item.photo >= 0) id["photo"] = item.photo;
  if (item.frame_part >= 0) id["frame_part"] = item.frame_part;
  if (item.frame_parts > 1) id["frame_parts"] = item.frame_parts;
  return id;
}

// A built-in scene, a scene file, or "building:floors=N" (`proxima visibility --floors N`).
Scene load_item_scene(const std::string& name) {
  const std::string floors = "building:floors=";
  if (name.rfind(floors, 0) != 0) return load_scene(name);
  const std::string n = name.substr(floors.size());
  if (n.empty() || n.size() > 4 || n.find_first_not_of("0123456789") != std::string::npos)
    fail_input("scene '" + name + "': floors must be a number");
  return make_vis_building(std::stoi(n));
}

// The item as a command-like line for its results.json: study, scene, the options given.
std::vector<std::string> item_command(const SweepItem& item) {
  std::vector<std::string> c{"study=" + item.study, "scene=" + item.scene};
  for (const auto& [name, value] : item.options) c.push_back(name + "=" + study::option_text(value));
  return c;
}

ItemFiles read_dir(const fs::path& dir) {
  ItemFiles files;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) files.files.emplace_back(fs::relative(e.path(), dir).generic_string(), read_bytes(e.path()));
  std::sort(files.files.begin(), files.files.end());
  return files;
}

// A frame part run into `dir` (then removed), packed as its part.bin.
std::string run_part(const Scene& scene, const SweepItem& item, const fs::path& dir) {
  FramePartData part;
  const Results results = study::run_study_part(item.study, scene, item.options,
                                                {item.frame_part, item.frame_parts}, {dir}, part.figures);
  part.images = results.images;
  if (fs::exists(dir)) part.files = read_dir(dir);
  fs::remove_all(dir);
  return pack_frame_part(part);
}

ItemStatus status_of(const json& record) {
  ItemStatus s;
  s.state = record.value("status", std::string()) == "ok" ? ItemState::Ok : ItemState::Failed;
  s.error = record.value("error", std::string());
  s.seconds = record.value("seconds", 0.0);
  return s;
}

}  // namespace

std::string pack_item(const ItemFiles& files) {
  ByteWriter w;
  w.put(uint64_t(files.files.size()));
  for (const auto& [name, bytes] : files.files) {
    w.put_string(name);
    w.put_string(bytes);
  }
  return std::move(w.out);
}

ItemFiles unpack_item(std::string_view packed) {
  ByteReader r{packed, "item pack"};
  ItemFiles files;
  const uint64_t n = r.get<uint64_t>();
  for (uint64_t i = 0; i < n; ++i) {
    std::string name = r.get_string();
    std::string bytes = r.get_string();
    if (name.empty() || name.front() == '/' || name.find("..") != std::string::npos) r.fail("bad file name " + name);
    files.files.emplace_back(std::move(name), std::move(bytes));
  }
  r.expect_end();
  return files;
}

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path.string() + ": cannot read");
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const fs::path& path, std::string_view bytes) {
  fs::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) throw std::runtime_error(path.string() + ": cannot write");
}

ItemFiles run_item(const SweepItem& item, const fs::path& scratch, const std::vector<std::string>& inputs) {
  const fs::path dir = scratch / item.id;
  fs::remove_all(dir);
  fs::create_directories(dir);
  json record = item_identity(item);
  Stopwatch watch;
  try {
    const Scene scene = load_item_scene(item.scene);
    if (item.photo >= 0) {
      write_bytes(dir / "photo.bin", run_gibr_photo(scene, item.options, item.photo));
    } else if (item.frame_part >= 0) {
      write_bytes(dir / "part.bin", run_part(scene, item, dir / "part"));
    } else {
      if (inputs.size() != item.inputs.size()) throw std::runtime_error("sweep: the item's inputs are missing");
      const study::StudyOutput out{dir};
      Results results = item.inputs.empty()   ? study::run_study(item.study, scene, item.options, out)
                        : item.frame_parts > 1 ? run_with_frame_parts(scene, item.study, item.options, out, inputs)
                                               : run_gibr_with_photos(scene, item.options, out, inputs);
      results.command = item_command(item);
      results.threads = active_threads();
      write_results_json(dir / "results.json", results);
    }
    record["status"] = "ok";
  } catch (const std::exception& e) {
    // Nothing half-written: a failed item is its record alone.
    fs::remove_all(dir);
    fs::create_directories(dir);
    record["status"] = "failed";
    record["error"] = e.what();
  }
  record["seconds"] = watch.elapsed_ms() / 1000.0;
  write_text_file(dir / "item.json", record.dump(2) + "\n");
  ItemFiles files = read_dir(dir);
  fs::remove_all(dir);
  return files;
}

void store_item(const fs::path& out, const SweepItem& item, const ItemFiles& files) {
  const fs::path items = out / "items";
  const fs::path final_dir = items / item.id;
  const fs::path tmp = items / ("." + item.id + ".tmp");
  fs::remove_all(tmp);
  fs::create_directories(tmp);
  for (const auto& [name, bytes] : files.files) write_bytes(tmp / name, bytes);
  fs::remove_all(final_dir);
  fs::rename(tmp, final_dir);
}

ItemStatus stored_item(const fs::path& out, const SweepItem& item) {
  std::ifstream in(out / "items" / item.id / "item.json");
  if (!in) return {};
  const json record = json::parse(in, nullptr, false);
  if (record.is_discarded() || !record.is_object()) return {};
  const json identity = item_identity(item);
  for (const auto& [key, value] : identity.items())
    if (!record.contains(key) || record[key] != value) return {};
  return status_of(record);
}

ItemFiles failed_item(const SweepItem& item, const std::string& error) {
  json record = item_identity(item);
  record["status"] = "failed";
  record["error"] = error;
  record["seconds"] = 0.0;
  return {{{"item.json", record.dump(2) + "\n"}}};
}

std::vector<std::string> item_inputs(const Manifest& manifest, const fs::path& out, const SweepItem& item) {
  std::vector<std::string> inputs;
  for (size_t i : item.inputs) {
    const SweepItem& input = manifest.items.at(i);
    inputs.push_back(read_bytes(out / "items" / input.id / (input.photo >= 0 ? "photo.bin" : "part.bin")));
  }
  return inputs;
}

ItemStatus item_status(const ItemFiles& files) {
  for (const auto& [name, bytes] : files.files)
    if (name == "item.json") {
      const json record = json::parse(bytes, nullptr, false);
      if (!record.is_discarded()) return status_of(record);
    }
  return {ItemState::Failed, "item.json missing", 0.0};
}

}  // namespace proxima::sweep
