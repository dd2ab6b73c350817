#include "proxima/core/timer.h"

#include <ctime>

#include <algorithm>

namespace proxima {

double process_cpu_ms() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) * 1e3 + double(ts.tv_nsec) * 1e-6;
}

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
