// The command line's operator new (apps/proxima/huge_page_new.cpp, linked into this test
// binary too): large blocks 2 MiB-aligned for huge pages, the rest as before, failures as
// the standard says. Compiled out under the sanitizers, which bring their own.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <new>

namespace {

#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || __has_feature(memory_sanitizer)
#define PROXIMA_TEST_SANITIZED 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define PROXIMA_TEST_SANITIZED 1
#endif

#if defined(PROXIMA_TEST_SANITIZED)
#define SKIP_UNDER_SANITIZERS() GTEST_SKIP() << "the sanitizers replace operator new"
#else
#define SKIP_UNDER_SANITIZERS() (void)0
#endif

constexpr std::uintptr_t kHugePage = std::uintptr_t(2) << 20;

// Through a volatile, so the compiler cannot elide the allocation.
std::uintptr_t address(const void* p) {
  volatile std::uintptr_t a = reinterpret_cast<std::uintptr_t>(p);
  return a;
}

struct alignas(256) OverAligned {
  char bytes[300];
};

TEST(HugePageNew, LargeBlocksAreHugePageAlignedAndUsable) {
  SKIP_UNDER_SANITIZERS();
  for (const size_t size : {size_t(2) << 20, (size_t(5) << 20) + 17, size_t(12) << 20}) {
    char* p = new char[size];
    EXPECT_EQ(address(p) % kHugePage, 0u) << size;
    std::memset(p, 0xab, size);  // every byte is ours
    EXPECT_EQ(static_cast<unsigned char>(p[size - 1]), 0xabu);
    delete[] p;
  }
}

TEST(HugePageNew, SmallAndOverAlignedBlocksKeepTheirAlignment) {
  SKIP_UNDER_SANITIZERS();
  int* small = new int(7);
  EXPECT_EQ(address(small) % alignof(std::max_align_t), 0u);
  EXPECT_EQ(*small, 7);
  delete small;
  OverAligned* over = new OverAligned;
  EXPECT_EQ(address(over) % 256u, 0u);
  delete over;
  OverAligned* many = new OverAligned[9000];  // 2.7 MB: huge-page path, still 256-aligned
  EXPECT_EQ(address(many) % kHugePage, 0u);
  delete[] many;
}

TEST(HugePageNew, ImpossibleSizesFailAsTheStandardSays) {
  SKIP_UNDER_SANITIZERS();
  volatile size_t huge = SIZE_MAX - 1000;  // overflows the rounding: no memory can hold it
  EXPECT_EQ(address(::operator new(huge, std::nothrow)), 0u);
  EXPECT_THROW(::operator delete(::operator new(huge)), std::bad_alloc);
  EXPECT_THROW(::operator delete(::operator new(huge, std::align_val_t(64))), std::bad_alloc);
}

}  // namespace
