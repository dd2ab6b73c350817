// Per-frame figures of an experiment over a camera path, reduced to max / min / avg for its
// tables; and frames per second from milliseconds.
#pragma once

#include <algorithm>
#include <vector>

namespace proxima {

// The values in the order added; every reduction of an empty series is 0.
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

// 1000 / ms; 0 for ms ≤ 0.
inline double fps(double ms) { return ms > 0.0 ? 1000.0 / ms : 0.0; }

}  // namespace proxima
