#include "proxima/core/parallel.h"

#include <thread>

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

namespace proxima {

void parallel_for_tiles(int width, int height, int tile_size,
                        const std::function<void(const Tile&)>& fn) {
  if (width <= 0 || height <= 0) return;
  int tiles_x = (width + tile_size - 1) / tile_size;
  int tiles_y = (height + tile_size - 1) / tile_size;
  int count = tiles_x * tiles_y;
  tbb::parallel_for(tbb::blocked_range<int>(0, count, 1), [&](const tbb::blocked_range<int>& r) {
    for (int i = r.begin(); i != r.end(); ++i) {
      int tx = i % tiles_x, ty = i / tiles_x;
      Tile t{tx * tile_size, ty * tile_size, std::min(width, (tx + 1) * tile_size),
             std::min(height, (ty + 1) * tile_size), i};
      fn(t);
    }
  });
}

void parallel_for(size_t n, size_t grain, const std::function<void(size_t, size_t)>& fn) {
  if (n == 0) return;
  if (grain == 0) grain = 1;
  // Fixed chunks [i·grain, (i+1)·grain): the split never depends on the thread count.
  size_t chunks = (n + grain - 1) / grain;
  tbb::parallel_for(size_t(0), chunks, [&](size_t i) { fn(i * grain, std::min(n, (i + 1) * grain)); });
}

struct ThreadLimit::Impl {
  tbb::global_control control;
  explicit Impl(size_t n) : control(tbb::global_control::max_allowed_parallelism, n) {}
};

ThreadLimit::ThreadLimit(int threads) {
  if (threads > 0) impl_ = std::make_unique<Impl>(size_t(threads));
}

ThreadLimit::~ThreadLimit() = default;

int active_threads() {
  return int(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
}

int hardware_threads() {
  unsigned n = std::thread::hardware_concurrency();
  return n == 0 ? 1 : int(n);
}

}  // namespace proxima
