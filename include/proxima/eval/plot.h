// Charts as inline SVG for the HTML report: line charts (y against a numeric x) and grouped
// bar charts, with axes, ticks, labels and a legend. Plain SVG elements only — no script,
// no CSS beyond attributes, no external references — so the page stays self-contained.
#pragma once

#include <string>
#include <vector>

#include "proxima/eval/results.h"

namespace proxima {

struct ChartSeries {
  std::string name;
  std::vector<double> y;  // one per x value / category; NaN = missing (gap)
};

struct Chart {
  enum class Kind { Line, Bar };
  Kind kind = Kind::Line;
  std::string title, x_label, y_label;
  std::vector<double> x;                 // Line: ascending x values
  std::vector<std::string> categories;   // Bar: one group of bars each
  std::vector<ChartSeries> series;
  bool log_y = false;                    // logarithmic y axis (values ≤ 0 skipped)
};

// "Nice" axis ticks covering [lo, hi]: steps of 1, 2 or 5 × 10^k, about `target` of them.
std::vector<double> nice_ticks(double lo, double hi, int target = 5);

// The chart as an <svg> element (width × height px, no XML declaration).
std::string svg_chart(const Chart& chart, int width = 560, int height = 320);

// The chart `spec` asks for, from its table's columns. Throws InputError naming the
// missing column.
Chart chart_from_table(const PlotSpec& spec, const Table& table);

}  // namespace proxima
