#include "proxima/core/timer.h"

#include <algorithm>

namespace proxima {

double median(std::vector<double> samples) {
  if (samples.empty()) return 0.0;
  size_t mid = samples.size() / 2;
  std::nth_element(samples.begin(), samples.begin() + std::ptrdiff_t(mid), samples.end());
  double upper = samples[mid];
  if (samples.size() % 2 == 1) return upper;
  double lower = *std::max_element(samples.begin(), samples.begin() + std::ptrdiff_t(mid));
  return 0.5 * (lower + upper);
}

}  // namespace proxima
