// results.json as read back for the report (`proxima demo` → read_results_json →
// report_html), and the Markdown tables of every table read. Any well-typed file must
// give a page: no exception but InputError, and the page names every table it was given.
#include "fuzz_util.h"
#include "proxima/eval/html_report.h"
#include "proxima/eval/results.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace proxima;
  fuzz::init_limits();
  const auto path = fuzz::write_input(data, size, ".json");
  fuzz::expect_input_errors_only([&] {
    const Results r = read_results_json(path);
    const std::string html = report_html(r, "fuzz");
    FUZZ_CHECK(html.find("</html>") != std::string::npos);
    for (const Table& t : r.tables) {
      const std::string md = markdown_table(t);
      FUZZ_CHECK(md.find("| --- |") != std::string::npos || t.columns.empty());
    }
  });
  return 0;
}
