// results.json (DESIGN.md schema) and the Markdown tables every measuring command prints:
// {"command": [...argv], "threads": N, "build": "Release", "commit": "...",
//  "metrics": {"name_unit": number}, "tables": [{"title", "columns", "rows"}], "images": {...},
//  "machine": {"cpu", "hardware_threads"}, "sections": [{"id", "title", "text", "tables",
//  "images", "commands", "plots"}]}
// "sections" group tables (by title), images (by role) and plots of table columns for the
// HTML report; optional.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <variant>
#include <vector>

namespace proxima {

struct Table {
  std::string title;
  std::vector<std::string> columns;
  std::vector<std::vector<std::variant<std::string, double>>> rows;
};

// A chart of one table's columns (drawn by eval/plot.h, so its numbers are the table's):
// kind "line" plots each y column against the numeric x column; "bar" groups bars by the
// x column's cells.
struct PlotSpec {
  std::string title;
  std::string table;  // Table::title
  std::string kind = "line";
  std::string x;                // column name
  std::vector<std::string> y;   // column names, one series each
  std::string x_label, y_label;
  bool log_y = false;
};

// One part of a report: prose, then the tables and images it names, then the commands that
// reproduce its figures.
struct Section {
  std::string id;     // anchor, [a-z0-9-]
  std::string title;
  std::string text;   // plain text; blank lines separate paragraphs
  std::vector<std::string> tables;    // Table::title of each table shown here
  std::vector<std::string> images;    // roles (keys of Results::images) shown here
  std::vector<std::string> commands;  // shell commands reproducing the section's figures
  std::vector<PlotSpec> plots = {};
};

struct Results {
  std::vector<std::string> command;
  int threads = 0;
  std::map<std::string, double> metrics;  // snake_case names with unit suffixes
  std::vector<Table> tables;
  std::map<std::string, std::string> images;  // role → file name relative to the out dir
  std::vector<Section> sections;
  // Provenance; empty = this binary's and this machine's (filled in when written).
  std::string build;
  std::string commit;
  std::string cpu;
};

// CPU model of this machine (from /proc/cpuinfo; "unknown" elsewhere).
std::string cpu_model();

// Build type and commit this binary was built from.
const char* build_type();
const char* build_commit();

// Writes results.json atomically into `path`.
void write_results_json(const std::filesystem::path& path, const Results& results);

// Reads a results.json written by write_results_json (null numbers come back as NaN).
// Throws InputError naming the file when it is missing or malformed.
Results read_results_json(const std::filesystem::path& path);

// A table cell as text: numbers with up to 4 decimals (trailing zeros trimmed), very
// large/small ones in %.4g, non-finite as "–".
std::string format_cell(const std::variant<std::string, double>& cell);

// GitHub-flavored Markdown for one table (numbers printed with up to 4 significant decimals).
std::string markdown_table(const Table& table);

}  // namespace proxima
