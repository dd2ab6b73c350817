// Per-frame figures of the path-walking reflect methods (cluster, temporal), reduced to
// max / min / avg for their tables.
#pragma once

#include <algorithm>
#include <vector>

namespace proxima::cli {

struct Series {
  std::vector<double> values;
  void add(double v) { values.push_back(v); }
  double avg() const {
    double s = 0.0;
    for (double v : values) s += v;
    return values.empty() ? 0.0 : s / double(values.size());
  }
  double max() const { return values.empty() ? 0.0 : *std::max_element(values.begin(), values.end()); }
  double min() const { return values.empty() ? 0.0 : *std::min_element(values.begin(), values.end()); }
};

inline double fps(double ms) { return ms > 0.0 ? 1000.0 / ms : 0.0; }

}  // namespace proxima::cli
