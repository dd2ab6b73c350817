// Wall-clock timing for benchmarks and reports (never for pass/fail in tests).
#pragma once

#include <chrono>
#include <vector>

namespace proxima {

class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  void restart() { start_ = std::chrono::steady_clock::now(); }
  double elapsed_ms() const {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::chrono::steady_clock::time_point start_;
};

// Adds the scope's duration in milliseconds to `*out_ms`.
class ScopedTimer {
 public:
  explicit ScopedTimer(double* out_ms) : out_ms_(out_ms) {}
  ~ScopedTimer() { *out_ms_ += watch_.elapsed_ms(); }
  ScopedTimer(const ScopedTimer&) = delete;
  ScopedTimer& operator=(const ScopedTimer&) = delete;

 private:
  double* out_ms_;
  Stopwatch watch_;
};

// CPU time of the whole process (all threads) in milliseconds: under load from other
// processes a step's CPU time stays what it costs, unlike its wall-clock time.
double process_cpu_ms();

// Median of the samples (mean of the middle two for an even count); 0 for none.
double median(std::vector<double> samples);

}  // namespace proxima
