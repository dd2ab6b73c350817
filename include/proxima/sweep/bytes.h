// The bytes a sweep item hands on (photo.bin, part.bin, an item's packed files): plain
// values in host byte order — the same binary reads them back, on the same cluster. The
// reader checks every count against the bytes left (no overflow) and fails with an
// InputError naming what it reads.
#pragma once

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "proxima/core/error.h"

namespace proxima::sweep {

struct ByteWriter {
  std::string out;
  template <typename T>
    requires std::is_trivially_copyable_v<T>
  void put(const T& v) {
    out.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  // The element count, then the elements.
  template <typename T>
  void put_span(std::span<const T> v) {
    put(uint64_t(v.size()));
    out.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  void put_string(std::string_view s) { put_span(std::span<const char>(s.data(), s.size())); }
};

struct ByteReader {
  std::string_view in;
  std::string what;  // "photo.bin", … : named in every error
  size_t at = 0;

  [[noreturn]] void fail(const std::string& why) const { fail_input("sweep: " + what + ": " + why); }
  // `n` elements of `size` bytes are left.
  void need(uint64_t n, size_t size = 1) const {
    if (n > (in.size() - at) / size) fail("truncated");
  }
  template <typename T>
    requires std::is_trivially_copyable_v<T>
  T get() {
    need(sizeof(T));
    T v;
    std::memcpy(&v, in.data() + at, sizeof v);
    at += sizeof v;
    return v;
  }
  bool get_bool() {
    const uint8_t b = get<uint8_t>();
    if (b > 1) fail("a flag that is neither 0 nor 1");
    return b == 1;
  }
  // Exactly dst.size() elements (the count stored must match).
  template <typename T>
  void get_into(std::span<T> dst) {
    const uint64_t n = get<uint64_t>();
    if (n != dst.size()) fail("an array of the wrong size");
    need(n, sizeof(T));
    if (n) std::memcpy(dst.data(), in.data() + at, n * sizeof(T));
    at += n * sizeof(T);
  }
  template <typename T>
  std::vector<T> get_vector() {
    const uint64_t n = get<uint64_t>();
    need(n, sizeof(T));
    std::vector<T> v(n);
    if (n) std::memcpy(v.data(), in.data() + at, n * sizeof(T));
    at += n * sizeof(T);
    return v;
  }
  std::string get_string() {
    const uint64_t n = get<uint64_t>();
    need(n);
    std::string s(in.substr(at, n));
    at += n;
    return s;
  }
  void expect_end() const {
    if (at != in.size()) fail("trailing bytes");
  }
};

// A file's bytes; a file written whole (directories created). Both throw naming the path.
std::string read_bytes(const std::filesystem::path& path);
void write_bytes(const std::filesystem::path& path, std::string_view bytes);

}  // namespace proxima::sweep
