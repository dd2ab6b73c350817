#include "proxima/sweep/manifest.h"

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <sstream>

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
    if (key != "study" && key != "scene" && key != "options" && key != "grid")
      fail_input(where + ": unknown key \"" + key + "\" (study, scene, options, grid)");
}

}  // namespace

Manifest parse_manifest(const std::string& json_text, const std::filesystem::path& base_dir,
                        const std::string& source) {
  json doc;
  try {
    doc = json::parse(json_text);
  } catch (const json::exception& e) {
    fail_input(source + ": not valid JSON: " + e.what());
  }
  if (!doc.is_object() || !doc.contains("runs") || !doc["runs"].is_array() || doc["runs"].empty())
    fail_input(source + ": expected {\"runs\": [ ... ]} with at least one run");
  struct Pending {
    std::string scene, study;
    study::OptionValues options;
  };
  std::vector<Pending> pending;
  for (size_t r = 0; r < doc["runs"].size(); ++r) {
    const json& run = doc["runs"][r];
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
    for (const std::string& scene : scenes_of(run, base_dir, where))
      for (const study::OptionValues& options : points) pending.push_back({scene, name, options});
  }
  Manifest m;
  const size_t digits = std::max<size_t>(3, std::to_string(pending.size() - 1).size());
  for (size_t i = 0; i < pending.size(); ++i) {
    std::string number = std::to_string(i);
    number.insert(0, digits - number.size(), '0');
    m.items.push_back({"i" + number + "_" + pending[i].study, pending[i].scene, pending[i].study,
                       pending[i].options});
  }
  return m;
}

Manifest read_manifest(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail_input(path.string() + ": cannot read the manifest");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_manifest(text.str(), path.parent_path(), path.string());
}

}  // namespace proxima::sweep
