// core/large_buffer.h: large blocks 2 MiB-aligned for huge pages, small ones as operator new
// gives them, failures as the standard says, and the allocator usable in containers.
#include "proxima/core/large_buffer.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <memory>
#include <new>

#include "proxima/core/image.h"

namespace proxima {
namespace {

#if defined(__SANITIZE_ADDRESS__)
#define PROXIMA_TEST_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define PROXIMA_TEST_SANITIZED 1
#endif
#endif

std::uintptr_t address(const void* p) { return reinterpret_cast<std::uintptr_t>(p); }

struct alignas(256) OverAligned {
  char bytes[300];
};

TEST(LargeBuffer, LargeBlocksAreHugePageAlignedAndUsable) {
  for (const size_t size : {kHugePageBytes, (size_t(5) << 20) + 17, size_t(12) << 20}) {
    void* p = allocate_large_buffer(size, 1);
    ASSERT_NE(p, nullptr);
    EXPECT_EQ(address(p) % kHugePageBytes, 0u) << size;
    std::memset(p, 0xab, size);  // every byte is ours
    EXPECT_EQ(static_cast<unsigned char*>(p)[size - 1], 0xabu);
    free_large_buffer(p, size, 1);
  }
}

TEST(LargeBuffer, SmallAndOverAlignedBlocksKeepTheirAlignment) {
  void* small = allocate_large_buffer(24, alignof(double));
  EXPECT_EQ(address(small) % alignof(std::max_align_t), 0u);
  std::memset(small, 1, 24);
  free_large_buffer(small, 24, alignof(double));
  void* zero = allocate_large_buffer(0, 1);
  EXPECT_NE(zero, nullptr);
  free_large_buffer(zero, 0, 1);
  free_large_buffer(nullptr, 100, 1);  // ignored

  LargeBufferAllocator<OverAligned> a;
  OverAligned* one = a.allocate(1);
  EXPECT_EQ(address(one) % 256u, 0u);
  a.deallocate(one, 1);
  OverAligned* many = a.allocate(9000);  // 2.7 MB: huge-page path, still 256-aligned
  EXPECT_EQ(address(many) % kHugePageBytes, 0u);
  std::memset(static_cast<void*>(many), 2, 9000 * sizeof(OverAligned));
  a.deallocate(many, 9000);
}

TEST(LargeBuffer, ImpossibleSizesThrowBadAlloc) {
  // Sizes whose rounding to whole huge pages overflows size_t: refused before any allocation.
  EXPECT_THROW(allocate_large_buffer(SIZE_MAX - 1000, 1), std::bad_alloc);
  EXPECT_THROW(allocate_large_buffer(SIZE_MAX - kHugePageBytes + 1, 64), std::bad_alloc);
  LargeBufferAllocator<double> a;
  EXPECT_THROW(a.allocate(SIZE_MAX / sizeof(double) + 1), std::bad_array_new_length);
  LargeBuffer<float> v;
  EXPECT_THROW(v.reserve(v.max_size() + 1), std::length_error);
#if defined(PROXIMA_TEST_SANITIZED)
  GTEST_SKIP() << "AddressSanitizer aborts on allocations larger than it supports";
#else
  // Fits in size_t, but no machine has 2^62 bytes.
  EXPECT_THROW(allocate_large_buffer(size_t(1) << 62, 1), std::bad_alloc);
  EXPECT_THROW(a.allocate(size_t(1) << 59), std::bad_alloc);
#endif
}

TEST(LargeBuffer, VectorsUseItAndCompareSwapAndGrow) {
  LargeBuffer<float> v(size_t(1) << 20, 1.5f);  // 4 MiB
  EXPECT_EQ(address(v.data()) % kHugePageBytes, 0u);
  EXPECT_EQ(v.back(), 1.5f);
  LargeBuffer<float> w(16, 2.0f);
  const float* big = v.data();
  v.swap(w);  // equal allocators: the memory moves, no copy
  EXPECT_EQ(w.data(), big);
  EXPECT_EQ(v.size(), 16u);
  for (int i = 0; i < 600000; ++i) v.push_back(float(i));  // grows across the 2 MiB threshold
  EXPECT_EQ(v[16 + 599999], 599999.0f);
  EXPECT_EQ(address(v.data()) % kHugePageBytes, 0u);
  LargeBuffer<float> copy = v;
  EXPECT_EQ(copy, v);
  copy[3] = -1.0f;
  EXPECT_NE(copy, v);
  EXPECT_TRUE(LargeBufferAllocator<float>() == LargeBufferAllocator<double>());
}

TEST(LargeBuffer, WholeImagesSitOnHugePages) {
  ImageF image(1024, 1024, 3, 0.25f);  // 12 MiB
  EXPECT_EQ(address(image.data().data()) % kHugePageBytes, 0u);
  EXPECT_EQ(image.at(1023, 1023, 2), 0.25f);
  ImageU8 small(8, 8, 1, 7);
  EXPECT_EQ(small.at(7, 7), 7);
  ImageF copy = image;
  EXPECT_EQ(copy, image);
}

}  // namespace
}  // namespace proxima
