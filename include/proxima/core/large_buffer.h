// Large buffers on transparent huge pages. proxima's frames live in a few dozen whole-image
// buffers (4–12 MB each at 1024²); on 4 KiB pages the steps that read them right after they
// were written (temporal reuse's best match and warp) spend most of their time in TLB misses
// and page faults. Blocks of kHugePageBytes and more are therefore 2 MiB-aligned, rounded up
// to whole huge pages and marked madvise(MADV_HUGEPAGE) — Debian's default THP mode is
// "madvise", so nothing else gets huge pages. Smaller blocks go to operator new as usual.
// The library allocates its own large buffers this way (Image, the temporal buffers); it
// never replaces its users' global allocator.
#pragma once

#include <cstddef>
#include <limits>
#include <new>
#include <vector>

namespace proxima {

// Size and alignment of a transparent huge page on x86-64 and arm64 (4 KiB base pages).
inline constexpr std::size_t kHugePageBytes = std::size_t(2) << 20;

// `bytes` of uninitialized memory aligned to `alignment` (a power of two): blocks of
// kHugePageBytes and more are aligned to max(alignment, kHugePageBytes) and advised for huge
// pages (advice only: a kernel without THP still gives the memory). Throws std::bad_alloc
// when out of memory or when the rounded size does not fit in size_t. bytes = 0 gives a
// unique non-null pointer.
void* allocate_large_buffer(std::size_t bytes, std::size_t alignment);

// Frees a block of allocate_large_buffer; `bytes` and `alignment` must be the ones it was
// allocated with (they select the path it came from). Null is ignored.
void free_large_buffer(void* p, std::size_t bytes, std::size_t alignment) noexcept;

// A standard allocator over allocate_large_buffer: stateless, so all instances are equal and
// containers swap and move their memory freely.
template <typename T>
struct LargeBufferAllocator {
  using value_type = T;

  LargeBufferAllocator() noexcept = default;
  template <typename U>
  LargeBufferAllocator(const LargeBufferAllocator<U>&) noexcept {}

  T* allocate(std::size_t n) {
    if (n > std::numeric_limits<std::size_t>::max() / sizeof(T)) throw std::bad_array_new_length();
    return static_cast<T*>(allocate_large_buffer(n * sizeof(T), alignof(T)));
  }
  void deallocate(T* p, std::size_t n) noexcept { free_large_buffer(p, n * sizeof(T), alignof(T)); }

  template <typename U>
  bool operator==(const LargeBufferAllocator<U>&) const noexcept {
    return true;
  }
};

// A vector whose storage, once it reaches 2 MiB, sits on huge pages.
template <typename T>
using LargeBuffer = std::vector<T, LargeBufferAllocator<T>>;

}  // namespace proxima
