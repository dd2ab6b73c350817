// results.json (DESIGN.md schema) and the Markdown tables every measuring command prints:
// {"command": [...argv], "threads": N, "build": "Release", "commit": "...",
//  "metrics": {"name_unit": number}, "tables": [{"title", "columns", "rows"}], "images": {...}}
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

struct Results {
  std::vector<std::string> command;
  int threads = 0;
  std::map<std::string, double> metrics;  // snake_case names with unit suffixes
  std::vector<Table> tables;
  std::map<std::string, std::string> images;  // role → file name relative to the out dir
};

// Build type and commit this binary was built from.
const char* build_type();
const char* build_commit();

// Writes results.json atomically into `path`.
void write_results_json(const std::filesystem::path& path, const Results& results);

// GitHub-flavored Markdown for one table (numbers printed with up to 4 significant decimals).
std::string markdown_table(const Table& table);

}  // namespace proxima
