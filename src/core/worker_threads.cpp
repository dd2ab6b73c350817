#include "proxima/core/worker_threads.h"

#include <new>

#include <tbb/global_control.h>

namespace proxima {

struct WorkerThreadsJoinedAtExit::Impl {
  tbb::task_scheduler_handle handle{tbb::attach{}};
};

WorkerThreadsJoinedAtExit::WorkerThreadsJoinedAtExit() : impl_(std::make_unique<Impl>()) {}

// finalize returns false, and leaves the threads be, where waiting is unsafe (a ThreadLimit
// still alive, say): the exit is then as before.
WorkerThreadsJoinedAtExit::~WorkerThreadsJoinedAtExit() { tbb::finalize(impl_->handle, std::nothrow); }

}  // namespace proxima
