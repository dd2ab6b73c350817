#include "proxima/eval/results.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "proxima/core/atomic_file.h"
#include "proxima/core/error.h"

#include "proxima_build_info.h"

namespace proxima {

const char* build_type() { return PROXIMA_BUILD_TYPE; }
const char* build_commit() { return PROXIMA_COMMIT; }

namespace {

nlohmann::json number_or_null(double v) {
  // JSON has no NaN/Inf: write null so readers see "not measured" rather than garbage.
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

}  // namespace

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

void write_results_json(const std::filesystem::path& path, const Results& results) {
  nlohmann::json j;
  j["command"] = results.command;
  j["threads"] = results.threads;
  j["build"] = results.build.empty() ? std::string(build_type()) : results.build;
  j["commit"] = results.commit.empty() ? std::string(build_commit()) : results.commit;
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
  j["machine"] = {{"cpu", results.cpu.empty() ? cpu_model() : results.cpu},
                  {"hardware_threads", std::thread::hardware_concurrency()}};
  nlohmann::json sections = nlohmann::json::array();
  for (const Section& s : results.sections) {
    nlohmann::json plots = nlohmann::json::array();
    for (const PlotSpec& p : s.plots)
      plots.push_back({{"title", p.title}, {"table", p.table}, {"kind", p.kind}, {"x", p.x}, {"y", p.y},
                       {"x_label", p.x_label}, {"y_label", p.y_label}, {"log_y", p.log_y}});
    sections.push_back({{"id", s.id}, {"title", s.title}, {"text", s.text}, {"tables", s.tables},
                        {"images", s.images}, {"commands", s.commands}, {"plots", plots}});
  }
  j["sections"] = sections;
  write_text_file(path, j.dump(2) + "\n");
}

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("model name", 0) == 0) {
      size_t colon = line.find(':');
      if (colon != std::string::npos) return line.substr(line.find_first_not_of(' ', colon + 1));
    }
  return "unknown";
}

Results read_results_json(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) fail_input(path.string() + ": cannot open");
  try {
    nlohmann::json j = nlohmann::json::parse(in);
    auto number = [](const nlohmann::json& v) { return v.is_null() ? std::nan("") : v.get<double>(); };
    Results r;
    r.command = j.at("command").get<std::vector<std::string>>();
    const nlohmann::json& threads = j.at("threads");
    if (!threads.is_number_unsigned() || threads.get<std::uint64_t>() > 1u << 20)
      fail_input(path.string() + ": \"threads\" must be an integer in 0..1048576");
    r.threads = int(threads.get<std::uint64_t>());
    r.build = j.value("build", std::string());
    r.commit = j.value("commit", std::string());
    if (j.contains("machine")) r.cpu = j["machine"].value("cpu", std::string());
    for (const auto& [name, value] : j.at("metrics").items()) r.metrics[name] = number(value);
    for (const auto& t : j.at("tables")) {
      Table table{t.at("title").get<std::string>(), t.at("columns").get<std::vector<std::string>>(), {}};
      for (const auto& row : t.at("rows")) {
        std::vector<std::variant<std::string, double>> cells;
        for (const auto& cell : row) {
          if (cell.is_string()) cells.emplace_back(cell.get<std::string>());
          else cells.emplace_back(number(cell));
        }
        table.rows.push_back(std::move(cells));
      }
      r.tables.push_back(std::move(table));
    }
    r.images = j.value("images", std::map<std::string, std::string>{});
    for (const auto& s : j.value("sections", nlohmann::json::array())) {
      Section section{s.at("id").get<std::string>(), s.at("title").get<std::string>(),
                      s.value("text", std::string()), s.value("tables", std::vector<std::string>{}),
                      s.value("images", std::vector<std::string>{}),
                      s.value("commands", std::vector<std::string>{})};
      for (const auto& p : s.value("plots", nlohmann::json::array()))
        section.plots.push_back({p.at("title").get<std::string>(), p.at("table").get<std::string>(),
                                 p.value("kind", std::string("line")), p.at("x").get<std::string>(),
                                 p.at("y").get<std::vector<std::string>>(), p.value("x_label", std::string()),
                                 p.value("y_label", std::string()), p.value("log_y", false)});
      r.sections.push_back(std::move(section));
    }
    return r;
  } catch (const nlohmann::json::exception& e) {
    fail_input(path.string() + ": malformed results.json: " + e.what());
  }
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
