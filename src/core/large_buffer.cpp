#include "proxima/core/large_buffer.h"

#include <sys/mman.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>

namespace proxima {

namespace {

bool is_large(std::size_t bytes) { return bytes >= kHugePageBytes; }

}  // namespace

void* allocate_large_buffer(std::size_t bytes, std::size_t alignment) {
  if (!is_large(bytes)) {
    if (alignment <= __STDCPP_DEFAULT_NEW_ALIGNMENT__) return ::operator new(bytes);
    return ::operator new(bytes, std::align_val_t(alignment));
  }
  const std::size_t align = std::max(alignment, kHugePageBytes);
  if (bytes > SIZE_MAX - align) throw std::bad_alloc();
  const std::size_t rounded = (bytes + align - 1) / align * align;
  void* p = std::aligned_alloc(align, rounded);
  if (!p) throw std::bad_alloc();
  madvise(p, rounded, MADV_HUGEPAGE);  // advice only: no huge pages is no error
  return p;
}

void free_large_buffer(void* p, std::size_t bytes, std::size_t alignment) noexcept {
  if (!p) return;
  if (is_large(bytes)) {
    std::free(p);
  } else if (alignment <= __STDCPP_DEFAULT_NEW_ALIGNMENT__) {
    ::operator delete(p);
  } else {
    ::operator delete(p, std::align_val_t(alignment));
  }
}

}  // namespace proxima
