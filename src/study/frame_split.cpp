#include "proxima/study/frame_split.h"

#include <cstdint>
#include <stdexcept>
#include <string>

namespace proxima::study {

std::pair<int, int> frame_span(const FramePart& part, int n) {
  const auto at = [&](int k) { return int(int64_t(k) * int64_t(n) / int64_t(part.count)); };
  return {at(part.index), at(part.index + 1)};
}

void append_figures(FrameFigures& all, const FrameFigures& part) {
  if (all.series.empty()) all.series.resize(part.series.size());
  if (all.series.size() != part.series.size())
    throw std::runtime_error("frame parts list " + std::to_string(all.series.size()) + " and " +
                             std::to_string(part.series.size()) + " series");
  for (size_t i = 0; i < part.series.size(); ++i)
    all.series[i].insert(all.series[i].end(), part.series[i].begin(), part.series[i].end());
}

}  // namespace proxima::study
