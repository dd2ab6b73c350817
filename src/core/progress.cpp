#include "proxima/core/progress.h"

#include <algorithm>
#include <cmath>
#include <unistd.h>

namespace proxima {

std::string format_duration(double seconds) {
  long s = std::lround(std::max(0.0, seconds));
  char buf[32];
  if (s >= 60) std::snprintf(buf, sizeof buf, "%ldm%02lds", s / 60, s % 60);
  else std::snprintf(buf, sizeof buf, "%lds", s);
  return buf;
}

std::string progress_line(const std::string& stage, const std::string& what, int done, int total,
                          double elapsed_s, int bar_width) {
  std::string line = stage + " ";
  if (bar_width > 0) {
    const int filled = total > 0 ? std::clamp(done * bar_width / total, 0, bar_width) : 0;
    line += '[';
    line.append(size_t(filled), '#');
    line.append(size_t(bar_width - filled), '.');
    line += "] ";
  }
  line += std::to_string(done) + "/" + std::to_string(total);
  if (!what.empty()) line += " " + what;
  line += "  " + format_duration(elapsed_s);
  if (done > 0 && done < total) line += ", ETA " + format_duration(elapsed_s / done * (total - done));
  return line;
}

Progress::Progress(std::FILE* out) : out_(out), terminal_(isatty(fileno(out)) != 0) {}

void Progress::begin(const std::string& stage, int steps) {
  end();
  stage_ = stage;
  steps_ = steps;
  done_ = 0;
  watch_.restart();
}

void Progress::step(const std::string& what) {
  if (done_ < 0) return;
  draw(what);
  ++done_;
}

void Progress::draw(const std::string& what) {
  if (listener_) {
    listener_({stage_, what, done_, steps_, watch_.elapsed_ms() / 1000.0});
    return;
  }
  // The step about to run is counted as not done yet.
  const std::string line = progress_line(stage_, what, done_, steps_, watch_.elapsed_ms() / 1000.0,
                                         terminal_ ? 24 : 0);
  if (terminal_) std::fprintf(out_, "\r\033[K%s", line.c_str());
  else std::fprintf(out_, "%s\n", line.c_str());
  std::fflush(out_);
}

void Progress::end() {
  if (done_ < 0) return;
  if (listener_) {
    done_ = -1;  // closed first: a listener that throws leaves no stage open for the destructor
    listener_({stage_, "done", steps_, steps_, watch_.elapsed_ms() / 1000.0});
    return;
  }
  const std::string line = progress_line(stage_, "done", steps_, steps_, watch_.elapsed_ms() / 1000.0,
                                         terminal_ ? 24 : 0);
  std::fprintf(out_, terminal_ ? "\r\033[K%s\n" : "%s\n", line.c_str());
  std::fflush(out_);
  done_ = -1;
}

}  // namespace proxima
