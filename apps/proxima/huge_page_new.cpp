// The command line's global operator new: allocations of 2 MiB and more are 2 MiB-aligned
// and marked for transparent huge pages (madvise MADV_HUGEPAGE; Debian's default THP mode
// is "madvise", so nothing else gets them). proxima's frames live in a few dozen whole-image
// buffers (4–12 MB each at 1024²); on 4 KiB pages the steps that read them right after the
// G-buffer pass spend most of their time in TLB misses and page faults — temporal reuse's
// best match and warp ran 2–3× slower in `proxima reflect` than in their benchmark
// (docs/RESULTS.md, issue 8, "Huge pages"). Smaller allocations go to malloc as before.
// Not compiled under the sanitizers: they replace operator new themselves.
#include <sys/mman.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <new>

#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || __has_feature(memory_sanitizer)
#define PROXIMA_SANITIZED_NEW 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define PROXIMA_SANITIZED_NEW 1
#endif

#if !defined(PROXIMA_SANITIZED_NEW)

namespace {

constexpr std::size_t kHugePage = std::size_t(2) << 20;

std::size_t round_up(std::size_t size, std::size_t to) { return (size + to - 1) / to * to; }

// One attempt; nullptr when out of memory (or the size overflows).
void* try_allocate(std::size_t size, std::size_t align) {
  if (size == 0) size = 1;
  if (size >= kHugePage) {
    if (size > SIZE_MAX - kHugePage) return nullptr;
    const std::size_t rounded = round_up(size, kHugePage);
    void* p = std::aligned_alloc(std::max(align, kHugePage), rounded);
    if (p) madvise(p, rounded, MADV_HUGEPAGE);  // advice only: no huge pages is no error
    return p;
  }
  if (align <= alignof(std::max_align_t)) return std::malloc(size);
  return std::aligned_alloc(align, round_up(size, align));
}

// operator new's contract: call the new-handler until it succeeds or there is none.
void* allocate(std::size_t size, std::size_t align) {
  for (;;) {
    if (void* p = try_allocate(size, align)) return p;
    std::new_handler handler = std::get_new_handler();
    if (!handler) throw std::bad_alloc();
    handler();
  }
}

void* allocate_nothrow(std::size_t size, std::size_t align) noexcept {
  try {
    return allocate(size, align);
  } catch (...) {
    return nullptr;
  }
}

constexpr std::size_t kDefault = alignof(std::max_align_t);

}  // namespace

void* operator new(std::size_t n) { return allocate(n, kDefault); }
void* operator new[](std::size_t n) { return allocate(n, kDefault); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept { return allocate_nothrow(n, kDefault); }
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept { return allocate_nothrow(n, kDefault); }
void* operator new(std::size_t n, std::align_val_t a) { return allocate(n, std::size_t(a)); }
void* operator new[](std::size_t n, std::align_val_t a) { return allocate(n, std::size_t(a)); }
void* operator new(std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
  return allocate_nothrow(n, std::size_t(a));
}
void* operator new[](std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
  return allocate_nothrow(n, std::size_t(a));
}

void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept { std::free(p); }

#endif
