#include "proxima/eval/results.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include <nlohmann/json.hpp>

#include "proxima/core/atomic_file.h"

#ifndef PROXIMA_COMMIT
#define PROXIMA_COMMIT "unknown"
#endif
#ifndef PROXIMA_BUILD_TYPE
#define PROXIMA_BUILD_TYPE "unknown"
#endif

namespace proxima {

const char* build_type() { return PROXIMA_BUILD_TYPE; }
const char* build_commit() { return PROXIMA_COMMIT; }

namespace {

nlohmann::json number_or_null(double v) {
  // JSON has no NaN/Inf: write null so readers see "not measured" rather than garbage.
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

std::string format_cell(const std::variant<std::string, double>& cell) {
  if (const auto* s = std::get_if<std::string>(&cell)) return *s;
  double v = std::get<double>(cell);
  if (!std::isfinite(v)) return "–";
  char buf[64];
  if (v != 0.0 && (std::fabs(v) >= 1e7 || std::fabs(v) < 1e-3)) std::snprintf(buf, sizeof buf, "%.4g", v);
  else if (std::fabs(v - std::round(v)) < 1e-9) std::snprintf(buf, sizeof buf, "%.0f", v);
  else std::snprintf(buf, sizeof buf, "%.4f", v);
  std::string s = buf;
  // Trim trailing zeros of fixed-point output ("12.5000" → "12.5").
  if (s.find('.') != std::string::npos && s.find('e') == std::string::npos) {
    while (s.back() == '0') s.pop_back();
    if (s.back() == '.') s.pop_back();
  }
  return s;
}

}  // namespace

void write_results_json(const std::filesystem::path& path, const Results& results) {
  nlohmann::json j;
  j["command"] = results.command;
  j["threads"] = results.threads;
  j["build"] = build_type();
  j["commit"] = build_commit();
  nlohmann::json metrics = nlohmann::json::object();
  for (const auto& [name, value] : results.metrics) metrics[name] = number_or_null(value);
  j["metrics"] = metrics;
  nlohmann::json tables = nlohmann::json::array();
  for (const Table& t : results.tables) {
    nlohmann::json rows = nlohmann::json::array();
    for (const auto& row : t.rows) {
      nlohmann::json r = nlohmann::json::array();
      for (const auto& cell : row) {
        if (const auto* s = std::get_if<std::string>(&cell)) r.push_back(*s);
        else r.push_back(number_or_null(std::get<double>(cell)));
      }
      rows.push_back(r);
    }
    tables.push_back({{"title", t.title}, {"columns", t.columns}, {"rows", rows}});
  }
  j["tables"] = tables;
  j["images"] = results.images;
  write_text_file(path, j.dump(2) + "\n");
}

std::string markdown_table(const Table& table) {
  std::ostringstream out;
  if (!table.title.empty()) out << "### " << table.title << "\n\n";
  out << "|";
  for (const auto& c : table.columns) out << " " << c << " |";
  out << "\n|";
  for (size_t i = 0; i < table.columns.size(); ++i) out << " --- |";
  out << "\n";
  for (const auto& row : table.rows) {
    out << "|";
    for (const auto& cell : row) out << " " << format_cell(cell) << " |";
    out << "\n";
  }
  return out.str();
}

}  // namespace proxima
