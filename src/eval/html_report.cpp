#include "proxima/eval/html_report.h"

#include <set>
#include <sstream>

#include "proxima/core/atomic_file.h"
#include "proxima/eval/html_escape.h"
#include "proxima/eval/plot.h"

namespace proxima {
namespace {

std::string escape(const std::string& text) { return html_escape(text); }

void write_table(std::ostringstream& out, const Table& t) {
  out << "<table>\n<caption>" << escape(t.title) << "</caption>\n<thead><tr>";
  for (const auto& c : t.columns) out << "<th>" << escape(c) << "</th>";
  out << "</tr></thead>\n<tbody>\n";
  for (const auto& row : t.rows) {
    out << "<tr>";
    for (const auto& cell : row) {
      bool numeric = std::holds_alternative<double>(cell);
      out << (numeric ? "<td class=\"num\">" : "<td>") << escape(format_cell(cell)) << "</td>";
    }
    out << "</tr>\n";
  }
  out << "</tbody>\n</table>\n";
}

void write_paragraphs(std::ostringstream& out, const std::string& text) {
  std::istringstream in(text);
  std::string line, para;
  auto flush = [&] {
    if (!para.empty()) out << "<p>" << escape(para) << "</p>\n";
    para.clear();
  };
  while (std::getline(in, line)) {
    if (line.find_first_not_of(" \t") == std::string::npos) flush();
    else para += (para.empty() ? "" : " ") + line;
  }
  flush();
}

constexpr const char* kStyle = R"(
body{font:15px/1.45 system-ui,sans-serif;max-width:1200px;margin:2em auto;padding:0 1em;color:#222}
h1{margin-bottom:.2em} h2{border-bottom:1px solid #ccc;padding-bottom:.2em;margin-top:2em}
dl.facts{display:grid;grid-template-columns:max-content auto;gap:.2em 1em}
dl.facts dt{font-weight:600} code,pre{background:#f4f4f4;border-radius:3px}
pre{padding:.5em;overflow-x:auto} table{border-collapse:collapse;margin:1em 0}
caption{text-align:left;font-weight:600;padding:.3em 0} th,td{border:1px solid #ccc;padding:.2em .6em}
td.num{text-align:right;font-variant-numeric:tabular-nums} th{background:#f0f0f0}
.figures{display:flex;flex-wrap:wrap;gap:1em} figure{margin:0} figure img{max-width:380px;image-rendering:pixelated}
figcaption{font-size:13px;color:#555;max-width:380px} figure.plot figcaption{max-width:560px}
)";

}  // namespace

std::string report_html(const Results& results, const std::string& title) {
  std::ostringstream out;
  out << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" << escape(title)
      << "</title>\n<style>" << kStyle << "</style>\n</head>\n<body>\n<h1>" << escape(title) << "</h1>\n";

  std::string command;
  for (const auto& a : results.command) command += (command.empty() ? "" : " ") + a;
  out << "<dl class=\"facts\">\n<dt>machine</dt><dd>" << escape(results.cpu) << "</dd>\n<dt>threads</dt><dd>"
      << results.threads << "</dd>\n<dt>build</dt><dd>" << escape(results.build) << "</dd>\n<dt>commit</dt><dd><code>"
      << escape(results.commit) << "</code></dd>\n<dt>command</dt><dd><code>" << escape(command)
      << "</code></dd>\n</dl>\n";

  if (!results.sections.empty()) {
    out << "<nav><h2>Contents</h2><ul>\n";
    for (const Section& s : results.sections)
      out << "<li><a href=\"#" << escape(s.id) << "\">" << escape(s.title) << "</a></li>\n";
    out << "</ul></nav>\n";
  }

  std::set<std::string> shown;
  for (const Section& s : results.sections) {
    out << "<section id=\"" << escape(s.id) << "\">\n<h2>" << escape(s.title) << "</h2>\n";
    write_paragraphs(out, s.text);
    if (!s.images.empty()) {
      out << "<div class=\"figures\">\n";
      for (const auto& role : s.images) {
        auto it = results.images.find(role);
        if (it == results.images.end()) continue;
        out << "<figure><img src=\"" << escape(it->second) << "\" alt=\"" << escape(role)
            << "\"><figcaption>" << escape(role) << "</figcaption></figure>\n";
      }
      out << "</div>\n";
    }
    if (!s.plots.empty()) {
      out << "<div class=\"figures\">\n";
      for (const PlotSpec& p : s.plots)
        for (const Table& t : results.tables)
          if (t.title == p.table) {
            out << "<figure class=\"plot\">" << svg_chart(chart_from_table(p, t)) << "<figcaption>from table: "
                << escape(t.title) << "</figcaption></figure>\n";
            break;
          }
      out << "</div>\n";
    }
    for (const auto& name : s.tables)
      for (const Table& t : results.tables)
        if (t.title == name) {
          write_table(out, t);
          shown.insert(name);
        }
    if (!s.commands.empty()) {
      out << "<p>Reproduce:</p>\n<pre>";
      for (const auto& c : s.commands) out << escape(c) << "\n";
      out << "</pre>\n";
    }
    out << "</section>\n";
  }

  bool header = false;
  for (const Table& t : results.tables) {
    if (shown.count(t.title)) continue;
    if (!header) out << "<section id=\"tables\">\n<h2>More tables</h2>\n";
    header = true;
    write_table(out, t);
  }
  if (header) out << "</section>\n";
  out << "</body>\n</html>\n";
  return out.str();
}

void write_report(const std::filesystem::path& out_dir, const Results& results, const std::string& title) {
  write_text_file(out_dir / "index.html", report_html(results, title));
}

}  // namespace proxima
