// The lifetime of the parallel loops' worker threads (TBB underneath).
#pragma once

#include <memory>

namespace proxima {

// Held by main() for the whole run: its destructor waits until the worker threads have
// ended, so none is still running, or exiting, when the process exits. LeakSanitizer's
// exit check stops every thread and intermittently crashes on one that is exiting
// ("Tracer caught signal 11", seen in CI on `proxima view` under ASan).
class WorkerThreadsJoinedAtExit {
 public:
  WorkerThreadsJoinedAtExit();
  ~WorkerThreadsJoinedAtExit();
  WorkerThreadsJoinedAtExit(const WorkerThreadsJoinedAtExit&) = delete;
  WorkerThreadsJoinedAtExit& operator=(const WorkerThreadsJoinedAtExit&) = delete;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace proxima
