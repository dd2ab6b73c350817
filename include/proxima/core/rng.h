// Seeded random numbers. PCG32 (O'Neill 2014) for streams; a 64-bit mix hash to derive
// per-pixel / per-tile seeds so results never depend on scheduling.
#pragma once

#include <cstdint>

namespace proxima {

// SplitMix64 finalizer: a bijective 64-bit mix.
constexpr uint64_t mix64(uint64_t z) {
  z += 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

// Seed for one item (pixel, tile, frame …) of a run with seed `seed`.
constexpr uint64_t derive_seed(uint64_t seed, uint64_t a, uint64_t b = 0, uint64_t c = 0) {
  return mix64(mix64(mix64(seed ^ mix64(a)) ^ b) ^ c);
}

class Pcg32 {
 public:
  explicit Pcg32(uint64_t seed = 0x853C49E6748FEA9Bull, uint64_t stream = 0xDA3E39CB94B95BDBull) {
    state_ = 0;
    inc_ = (stream << 1u) | 1u;
    next_u32();
    state_ += seed;
    next_u32();
  }

  uint32_t next_u32() {
    uint64_t old = state_;
    state_ = old * kMultiplier + inc_;
    uint32_t xorshifted = uint32_t(((old >> 18u) ^ old) >> 27u);
    uint32_t rot = uint32_t(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((~rot + 1u) & 31));
  }

  // Skips `delta` outputs in O(log delta) steps (Brown 1994, LCG jump-ahead): afterwards the
  // stream gives what it would have given after `delta` calls of next_u32 (or next_float).
  void advance(uint64_t delta) {
    uint64_t mul = kMultiplier, add = inc_, acc_mul = 1, acc_add = 0;
    for (; delta > 0; delta >>= 1) {
      if (delta & 1u) acc_mul *= mul, acc_add = acc_add * mul + add;
      add *= mul + 1;
      mul *= mul;
    }
    state_ = acc_mul * state_ + acc_add;
  }

  // Uniform in [0, 1).
  float next_float() { return float(next_u32() >> 8) * 0x1p-24f; }

  // Uniform integer in [0, bound).
  uint32_t next_below(uint32_t bound) { return uint32_t((uint64_t(next_u32()) * bound) >> 32); }

 private:
  static constexpr uint64_t kMultiplier = 6364136223846793005ull;
  uint64_t state_;
  uint64_t inc_;
};

}  // namespace proxima
