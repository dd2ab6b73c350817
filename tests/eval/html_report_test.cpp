#include "proxima/eval/html_report.h"

#include <fstream>

#include <gtest/gtest.h>

#include "proxima/core/error.h"
#include "test_util.h"

namespace proxima {
namespace {

// A small fixture results.json, written by hand as another tool would.
constexpr const char* kFixture = R"({
  "command": ["proxima", "demo"], "threads": 2, "build": "Release", "commit": "abc",
  "machine": {"cpu": "Test CPU 9000", "hardware_threads": 2},
  "metrics": {"cornell_render_ms": 12.5, "missing_ms": null},
  "tables": [
    {"title": "reference renders", "columns": ["scene", "render_ms"], "rows": [["cornell", 12.5], ["a<b", 3]]},
    {"title": "loose", "columns": ["x"], "rows": [[1.25]]}
  ],
  "images": {"cornell_reference": "cornell_reference.png"},
  "sections": [{"id": "reference", "title": "Reference renders", "text": "First paragraph.\n\nSecond.",
                "tables": ["reference renders"], "images": ["cornell_reference"],
                "commands": ["proxima render --scene cornell"],
                "plots": [{"title": "render time", "table": "reference renders", "kind": "bar", "x": "scene",
                           "y": ["render_ms"], "y_label": "ms"}]}]
})";

TEST(HtmlReport, EveryNumberComesFromResultsJson) {
  TempDir dir;
  std::ofstream(dir.path / "results.json") << kFixture;
  Results r = read_results_json(dir.path / "results.json");
  EXPECT_TRUE(std::isnan(r.metrics.at("missing_ms")));
  std::string html = report_html(r, "proxima demo");
  EXPECT_NE(html.find("<td>cornell</td><td class=\"num\">12.5</td>"), std::string::npos) << html;
  EXPECT_NE(html.find("<td>a&lt;b</td><td class=\"num\">3</td>"), std::string::npos);  // escaped
  EXPECT_NE(html.find("<img src=\"cornell_reference.png\""), std::string::npos);
  EXPECT_NE(html.find("<p>First paragraph.</p>"), std::string::npos);
  EXPECT_NE(html.find("proxima render --scene cornell"), std::string::npos);
  EXPECT_NE(html.find("Test CPU 9000"), std::string::npos);  // provenance from the file
  EXPECT_NE(html.find("<code>abc</code>"), std::string::npos);
  // The table no section names still appears, after the sections.
  EXPECT_GT(html.find("<caption>loose</caption>"), html.find("<caption>reference renders</caption>"));
  EXPECT_NE(html.find("<td class=\"num\">1.25</td>"), std::string::npos);
  // The plot is inline SVG drawn from the same table cells.
  EXPECT_NE(html.find("<svg class=\"chart\""), std::string::npos);
  EXPECT_NE(html.find("<title>render_ms, cornell: 12.5</title>"), std::string::npos) << html;
  EXPECT_NE(html.find("<title>render_ms, a&lt;b: 3</title>"), std::string::npos);
  EXPECT_EQ(r.sections[0].plots.at(0).y, std::vector<std::string>{"render_ms"});
  // Self-contained: no scripts, no remote fetches.
  EXPECT_EQ(html.find("<script"), std::string::npos);
  EXPECT_EQ(html.find("http"), std::string::npos);
}

TEST(HtmlReport, ResultsRoundTripThroughJson) {
  TempDir dir;
  Results r;
  r.command = {"proxima", "x"};
  r.threads = 3;
  r.metrics["a_ms"] = 1.5;
  r.tables.push_back({"t", {"c1", "c2"}, {{std::string("s"), 2.0}}});
  r.images["img"] = "img.png";
  r.sections.push_back({"s1", "S", "text", {"t"}, {"img"}, {"cmd"}});
  write_results_json(dir.path / "results.json", r);
  Results back = read_results_json(dir.path / "results.json");
  EXPECT_EQ(back.command, r.command);
  EXPECT_EQ(back.threads, 3);
  EXPECT_EQ(back.metrics, r.metrics);
  ASSERT_EQ(back.tables.size(), 1u);
  EXPECT_EQ(back.tables[0].rows, r.tables[0].rows);
  EXPECT_EQ(back.sections[0].commands, r.sections[0].commands);
}

TEST(HtmlReport, MalformedResultsJsonNamesTheFile) {
  TempDir dir;
  std::ofstream(dir.path / "bad.json") << "{\"command\": 3}";
  try {
    read_results_json(dir.path / "bad.json");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.json"), std::string::npos);
  }
  EXPECT_THROW(read_results_json(dir.path / "missing.json"), InputError);
  // A thread count no int holds is refused, not converted.
  for (const char* threads : {"1e300", "-1", "2.5", "\"4\""}) {
    std::ofstream(dir.path / "bad.json")
        << "{\"command\": [], \"threads\": " << threads << ", \"metrics\": {}, \"tables\": []}";
    EXPECT_THROW(read_results_json(dir.path / "bad.json"), InputError) << threads;
  }
}

}  // namespace
}  // namespace proxima
