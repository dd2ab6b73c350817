#include "proxima/core/worker_threads.h"

#include <atomic>
#include <chrono>
#include <filesystem>
#include <optional>
#include <thread>

#include <gtest/gtest.h>

#include "proxima/core/parallel.h"

namespace proxima {
namespace {

// Threads of this process (Linux: one entry per thread under /proc/self/task).
size_t thread_count() {
  size_t n = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator("/proc/self/task")) ++n;
  return n;
}

TEST(WorkerThreads, AreGoneWhenTheScopeEnds) {
  if (!std::filesystem::exists("/proc/self/task")) GTEST_SKIP() << "no /proc/self/task";
  if (hardware_threads() < 2) GTEST_SKIP() << "one hardware thread: no workers to join";
  std::optional<WorkerThreadsJoinedAtExit> workers(std::in_place);
  // Chunks that take a while, so the workers start and join in.
  std::atomic<int> done{0};
  parallel_for(64, 1, [&](size_t, size_t) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
    ++done;
  });
  EXPECT_EQ(done.load(), 64);
  const size_t during = thread_count();
  ASSERT_GE(during, 2u) << "the loop ran without worker threads";
  workers.reset();
  EXPECT_LT(thread_count(), during);  // TBB alone would keep its workers asleep until exit
}

}  // namespace
}  // namespace proxima
