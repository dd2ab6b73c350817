// What the study tests share: two runs of a study (e.g. at 1 and 2 threads) agree on every
// deterministic metric and write the same image bytes; a tiny cluster-study run.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>

#include "proxima/eval/results.h"
#include "proxima/study/cluster_reflect.h"

namespace proxima {

inline std::string file_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Every metric of `a` but the timings is in `b` with the same value; returns how many were
// compared.
inline size_t expect_same_metrics(const Results& a, const Results& b) {
  const std::regex timing("_ms|^ms|ms$|fps|speedup");
  size_t compared = 0;
  for (const auto& [name, value] : a.metrics) {
    if (std::regex_search(name, timing)) continue;
    auto it = b.metrics.find(name);
    EXPECT_TRUE(it != b.metrics.end()) << name;
    if (it != b.metrics.end()) {
      EXPECT_EQ(value, it->second) << name;
    }
    ++compared;
  }
  return compared;
}

// The two runs name the same images, written byte for byte alike into dir_a and dir_b.
inline void expect_same_images(const Results& a, const Results& b, const std::filesystem::path& dir_a,
                               const std::filesystem::path& dir_b) {
  ASSERT_EQ(a.images, b.images);
  for (const auto& [role, file] : a.images) EXPECT_EQ(file_bytes(dir_a / file), file_bytes(dir_b / file)) << role;
}

// Two frames of room-reflector's first path, 48×32, one sample per pixel, with --compare.
inline study::ClusterReflectOptions tiny_cluster_options() {
  study::ClusterReflectOptions o;
  o.width = 48;
  o.height = 32;
  o.camera.path = "0";
  o.frames = 2;
  o.reflection.supersample = 1;
  o.cube_size = 16;
  o.compare = true;
  return o;
}

}  // namespace proxima
