// Progress of a long run on stderr: one stage at a time, each with a number of steps. On a
// terminal a bar redrawn in place with an ETA; otherwise (CI logs, pipes) one plain line per
// step, so logs stay readable.
#pragma once

#include <cstdio>
#include <functional>
#include <string>
#include <utility>

#include "proxima/core/timer.h"

namespace proxima {

// "1m05s", "42s": a duration for people.
std::string format_duration(double seconds);

// One line: "stage [#####·····] 3/8 what  12s, ETA 20s". The ETA extrapolates the mean time
// of the done steps; none before the first step is done. `bar_width` 0 = no bar.
std::string progress_line(const std::string& stage, const std::string& what, int done, int total,
                          double elapsed_s, int bar_width);

// One report of a Progress: step `done` of `total` of `stage` is about to run (`what`), or
// the stage is over (done == total, what == "done").
struct ProgressEvent {
  std::string stage;
  std::string what;
  int done = 0;
  int total = 0;
  double elapsed_s = 0.0;
};
using ProgressListener = std::function<void(const ProgressEvent&)>;

class Progress {
 public:
  // A bar when `out` is a terminal, plain lines otherwise.
  explicit Progress(std::FILE* out = stderr);
  Progress(std::FILE* out, bool terminal) : out_(out), terminal_(terminal) {}
  // Reports every step and stage end to `listener` instead of a file (the Python module's
  // progress callbacks). An exception from the listener propagates out of step()/end().
  explicit Progress(ProgressListener listener) : out_(nullptr), terminal_(false), listener_(std::move(listener)) {}
  ~Progress() {
    try {
      end();
    } catch (...) {  // a listener's exception cannot leave a destructor
    }
  }
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void begin(const std::string& stage, int steps);
  // Step `what` starts; the previous steps of the stage are done.
  void step(const std::string& what);
  // The stage is done: its line with the total time.
  void end();

 private:
  void draw(const std::string& what);

  std::FILE* out_;
  bool terminal_;
  ProgressListener listener_;
  std::string stage_;
  int steps_ = 0, done_ = -1;  // done_ = -1: no stage open
  Stopwatch watch_;
};

}  // namespace proxima
