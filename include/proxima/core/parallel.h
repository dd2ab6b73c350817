// Deterministic parallel loops over image tiles and index ranges (TBB underneath).
// Work is split into fixed tiles, independent of the thread count, so outputs that
// depend only on the tile never change with --threads.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>

namespace proxima {

// Pixels [x0, x1) × [y0, y1).
struct Tile {
  int x0, y0, x1, y1;
  int index;  // row-major tile number, stable for a given image size and tile size
};

// Calls fn once per tile of a width × height image, in parallel.
void parallel_for_tiles(int width, int height, int tile_size, const std::function<void(const Tile&)>& fn);

// Calls fn(begin, end) over [0, n) in the fixed chunks [i·grain, (i+1)·grain), in parallel.
void parallel_for(size_t n, size_t grain, const std::function<void(size_t, size_t)>& fn);

// Limits the worker threads for its lifetime (tbb::global_control); threads ≤ 0 = all cores.
class ThreadLimit {
 public:
  explicit ThreadLimit(int threads);
  ~ThreadLimit();
  ThreadLimit(const ThreadLimit&) = delete;
  ThreadLimit& operator=(const ThreadLimit&) = delete;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Threads the parallel loops currently may use.
int active_threads();
// Hardware threads of this machine.
int hardware_threads();

}  // namespace proxima
