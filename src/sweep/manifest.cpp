#include "proxima/sweep/manifest.h"

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <variant>

#include <nlohmann/json.hpp>

#include "proxima/core/error.h"

namespace proxima::sweep {

namespace {

using nlohmann::json;

// An option value from JSON: true/false, an integer, a number, a string.
study::OptionValue option_value(const json& j, const std::string& where) {
  if (j.is_boolean()) return j.get<bool>();
  if (j.is_number_integer()) {
    if (j.is_number_unsigned() && j.get<std::uint64_t>() > static_cast<std::uint64_t>(INT64_MAX))
      fail_input(where + ": integer out of range");
    return j.get<std::int64_t>();
  }
  if (j.is_number_float()) return j.get<double>();
  if (j.is_string()) return j.get<std::string>();
  fail_input(where + ": expected true/false, a number or a string");
}

std::vector<std::string> scenes_of(const json& run, const std::filesystem::path& base_dir, const std::string& where) {
  if (!run.contains("scene")) fail_input(where + ": \"scene\" missing");
  const json& s = run["scene"];
  std::vector<std::string> names;
  if (s.is_string()) names.push_back(s.get<std::string>());
  else if (s.is_array() && !s.empty())
    for (const json& e : s) {
      if (!e.is_string()) fail_input(where + ": \"scene\" must be a name or a list of names");
      names.push_back(e.get<std::string>());
    }
  else fail_input(where + ": \"scene\" must be a name or a non-empty list of names");
  for (std::string& n : names) {
    const bool file = n.find('/') != std::string::npos || n.find('.') != std::string::npos;
    if (file && std::filesystem::path(n).is_relative()) n = (base_dir / n).lexically_normal().string();
  }
  return names;
}

// The grid's points: every combination of its keys' values, the last key fastest.
std::vector<study::OptionValues> grid_points(const json& run, const std::string& where) {
  std::vector<study::OptionValues> points{{}};
  if (!run.contains("grid")) return points;
  if (!run["grid"].is_object()) fail_input(where + ": \"grid\" must be an object of option → list of values");
  for (const auto& [key, values] : run["grid"].items()) {
    const std::string at = where + ": grid \"" + key + "\"";
    if (!values.is_array() || values.empty()) fail_input(at + ": must be a non-empty list of values");
    std::vector<study::OptionValues> next;
    for (const study::OptionValues& p : points)
      for (const json& v : values) {
        study::OptionValues q = p;
        q[key] = option_value(v, at);
        next.push_back(std::move(q));
      }
    points = std::move(next);
  }
  return points;
}

void check_keys(const json& run, const std::string& where) {
  for (const auto& [key, value] : run.items())
    if (key != "study" && key != "scene" && key != "options" && key != "grid" && key != "frame_items")
      fail_input(where + ": unknown key \"" + key + "\" (study, scene, options, grid, frame_items)");
}

}  // namespace

namespace {

struct Pending {
  std::string scene, study;
  study::OptionValues options;
  std::string demo_dir;  // the demo run it is, if any
  int frame_items = 1;   // frame parts (study/frame_split.h); 1 = one item
};

// A run's "frame_items": 1..10000, and only for a study that splits into frame parts.
int frame_items(const json& run, const std::string& study, const std::string& where) {
  if (!run.contains("frame_items")) return 1;
  const json& k = run["frame_items"];
  if (!k.is_number_integer() || k.get<std::int64_t>() < 1 || k.get<std::int64_t>() > 10000)
    fail_input(where + ": \"frame_items\" must be an integer in 1..10000");
  const int n = static_cast<int>(k.get<std::int64_t>());
  if (n > 1 && !study::splits_by_frames(study))
    fail_input(where + ": \"frame_items\": study " + study + " does not split into frame parts (cluster_reflect, visibility)");
  return n;
}

// The demo's rule: a cluster_reflect run along a path and a visibility run become up to
// kDemoFrameItems frame parts (fewer when the options give fewer frames).
int demo_frame_items(const std::string& study, const study::OptionValues& given) {
  if (!study::splits_by_frames(study)) return 1;
  const study::OptionValues o = study::resolved_options(study, given);
  const std::int64_t frames = std::get<std::int64_t>(o.at("frames"));
  std::int64_t n = frames > 0 ? frames : kDemoFrameItems;
  if (study == "cluster_reflect") {
    if (std::get<std::string>(o.at("path")).empty() || given.contains("frame")) return 1;
    n = frames > 0 ? (frames + std::get<std::int64_t>(o.at("frame_step")) - 1) / std::get<std::int64_t>(o.at("frame_step")) : n;
  }
  return static_cast<int>(std::min<std::int64_t>(n, kDemoFrameItems));
}

json parse_json(const std::string& json_text, const std::string& source) {
  try {
    return json::parse(json_text);
  } catch (const json::exception& e) {
    fail_input(source + ": not valid JSON: " + e.what());
  }
}

// The runs of {"runs": [...]}, expanded.
std::vector<Pending> expand_runs(const json& runs, const std::filesystem::path& base_dir, const std::string& source) {
  std::vector<Pending> pending;
  for (size_t r = 0; r < runs.size(); ++r) {
    const json& run = runs[r];
    const std::string where = source + ": runs[" + std::to_string(r) + "]";
    if (!run.is_object()) fail_input(where + ": must be an object");
    check_keys(run, where);
    if (!run.contains("study") || !run["study"].is_string()) fail_input(where + ": \"study\" missing");
    const std::string name = run["study"].get<std::string>();
    study::OptionValues base;
    if (run.contains("options")) {
      if (!run["options"].is_object()) fail_input(where + ": \"options\" must be an object");
      for (const auto& [key, value] : run["options"].items())
        base[key] = option_value(value, where + ": option \"" + key + "\"");
    }
    std::vector<study::OptionValues> points = grid_points(run, where);
    for (study::OptionValues& point : points) {
      for (const auto& [key, value] : base) point.emplace(key, value);  // the grid's value wins
      try {
        study::resolved_options(name, point);  // unknown study or option, wrong type
      } catch (const InputError& e) {
        fail_input(where + ": " + e.what());
      }
    }
    const int parts = frame_items(run, name, where);
    for (const std::string& scene : scenes_of(run, base_dir, where))
      for (const study::OptionValues& options : points) pending.push_back({scene, name, options, "", parts});
  }
  return pending;
}

// The demo options of {"demo": {...}}.
study::DemoOptions demo_options(const json& d, const std::string& where) {
  if (!d.is_object()) fail_input(where + ": must be an object (full, seed, width, height, only)");
  study::DemoOptions o;
  for (const auto& [key, value] : d.items()) {
    const std::string at = where + ": \"" + key + "\"";
    if (key == "full" && value.is_boolean()) o.full = value.get<bool>();
    else if ((key == "seed" || key == "width" || key == "height") && value.is_number_integer()) {
      const std::int64_t v = value.get<std::int64_t>();
      if (key == "seed") o.seed = static_cast<uint64_t>(v);
      else if (v < 1 || v > 16384) fail_input(at + ": must be in 1..16384");
      else (key == "width" ? o.width : o.height) = static_cast<int>(v);
    } else if (key == "only" && value.is_array()) {
      for (const json& id : value) {
        if (!id.is_string()) fail_input(at + ": must be a list of section ids");
        o.only.push_back(id.get<std::string>());
      }
    } else {
      fail_input(at + ": unknown key or wrong type (full: bool, seed/width/height: integer, only: list)");
    }
  }
  try {
    study::validate(o);
  } catch (const InputError& e) {
    fail_input(where + ": " + e.what());
  }
  return o;
}

// The demo's study runs as catalog runs (each from its reproducing command).
std::vector<Pending> expand_demo(const study::DemoOptions& o, const std::string& where) {
  std::vector<Pending> pending;
  for (const study::DemoStudyRun& run : study::plan_demo(o)) {
    study::CatalogRun c;
    try {
      c = study::catalog_run_from_command(run.args);
      study::resolved_options(c.study, c.options);
    } catch (const InputError& e) {
      fail_input(where + ": demo run " + run.dir + ": " + e.what());
    }
    pending.push_back({c.scene, c.study, c.options, run.dir, demo_frame_items(c.study, c.options)});
  }
  return pending;
}

// The photographs of a gibr run with rendered photographs, 0 otherwise.
int gibr_photos(const Pending& p) {
  if (p.study != "gibr") return 0;
  const study::OptionValues o = study::resolved_options(p.study, p.options);
  if (!std::get<std::string>(o.at("camera_file")).empty()) return 0;
  return static_cast<int>(std::get<std::int64_t>(o.at("photos")));
}

std::string item_id(size_t number, size_t digits, const std::string& name) {
  std::string n = std::to_string(number);
  n.insert(0, digits > n.size() ? digits - n.size() : 0, '0');
  return "i" + n + "_" + name;
}

// The items as a manifest lists them (informative; checked against the expansion).
json items_json(const Manifest& m) {
  json items = json::array();
  for (const SweepItem& item : m.items) {
    json options = json::object();
    for (const auto& [name, value] : item.options)
      options[name] = std::visit([](const auto& v) { return json(v); }, value);
    json j = {{"id", item.id}, {"study", item.study}, {"scene", item.scene}, {"options", options}};
    if (item.photo >= 0) j["photo"] = item.photo;
    if (item.frame_part >= 0) j["frame_part"] = item.frame_part;
    if (item.frame_parts > 1) j["frame_parts"] = item.frame_parts;
    items.push_back(j);
  }
  return items;
}

}  // namespace

Manifest parse_manifest(const std::string& json_text, const std::filesystem::path& base_dir,
                        const std::string& source) {
  const json doc = parse_json(json_text, source);
  Manifest m;
  std::vector<Pending> pending;
  if (doc.is_object() && doc.contains("demo") && !doc.contains("runs")) {
    for (const auto& [key, value] : doc.items())
      if (key != "demo" && key != "items") fail_input(source + ": unknown key \"" + key + "\" (demo, items)");
    m.demo = demo_options(doc["demo"], source + ": demo");
    pending = expand_demo(*m.demo, source);
  } else if (doc.is_object() && doc.contains("runs") && doc["runs"].is_array() && !doc["runs"].empty() &&
             !doc.contains("demo")) {
    pending = expand_runs(doc["runs"], base_dir, source);
  } else {
    fail_input(source + ": expected {\"runs\": [ ... ]} with at least one run, or {\"demo\": { ... }}");
  }
  if (pending.empty()) fail_input(source + ": no study runs (the demo sections chosen run none)");
  size_t count = 0;
  for (const Pending& p : pending) count += 1 + size_t(gibr_photos(p)) + (p.frame_items > 1 ? size_t(p.frame_items) : 0);
  const size_t digits = std::max<size_t>(3, std::to_string(count - 1).size());
  for (const Pending& p : pending) {
    SweepItem item;
    item.scene = p.scene;
    item.study = p.study;
    item.options = p.options;
    for (int k = 0; p.frame_items > 1 && k < p.frame_items; ++k) {
      SweepItem part = item;
      part.id = item_id(m.items.size(), digits, p.study + "_part");
      part.frame_part = k;
      part.frame_parts = p.frame_items;
      item.inputs.push_back(m.items.size());
      m.items.push_back(std::move(part));
    }
    item.frame_parts = p.frame_items;
    for (int k = 0, n = gibr_photos(p); k < n; ++k) {
      SweepItem photo = item;
      photo.id = item_id(m.items.size(), digits, p.study + "_photo");
      photo.photo = k;
      item.inputs.push_back(m.items.size());
      m.items.push_back(std::move(photo));
    }
    item.id = item_id(m.items.size(), digits, p.study);
    if (!p.demo_dir.empty()) m.demo_items[p.demo_dir] = m.items.size();
    m.items.push_back(std::move(item));
  }
  if (doc.contains("items") && doc["items"] != items_json(m))
    fail_input(source + ": its \"items\" are not the demo's study runs of this proxima (regenerate it: proxima demo "
                        "--manifest FILE)");
  return m;
}

std::string demo_manifest_json(const study::DemoOptions& o) {
  json demo = {{"full", o.full}, {"seed", o.seed}, {"width", o.width}, {"height", o.height}};
  if (!o.only.empty()) demo["only"] = o.only;
  json doc = {{"demo", demo}};
  doc["items"] = items_json(parse_manifest(doc.dump(), ".", "demo"));
  return doc.dump(1) + "\n";
}

Manifest read_manifest(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail_input(path.string() + ": cannot read the manifest");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_manifest(text.str(), path.parent_path(), path.string());
}

}  // namespace proxima::sweep
