// Winged-pair files: exact round trip, and malformed files rejected with InputError naming
// the file.
#include "proxima/visibility/winged_pair_io.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "proxima/core/error.h"
#include "proxima/scene/visibility_models.h"
#include "proxima/visibility/bsp_build.h"

namespace proxima::visibility {
namespace {

namespace fs = std::filesystem;

fs::path temp_file(const std::string& name) { return fs::temp_directory_path() / ("proxima_wp_" + name); }

TEST(WingedPairIo, RoundTripIsExact) {
  WingedPair wp = build_winged_pair(extract_polygons(make_vis_rooms()));
  const fs::path path = temp_file("rooms.wp");
  save_winged_pair(path, wp);
  WingedPair back = load_winged_pair(path);
  ASSERT_EQ(back.vertices.size(), wp.vertices.size());
  ASSERT_EQ(back.pairs.size(), wp.pairs.size());
  for (size_t i = 0; i < wp.vertices.size(); ++i) EXPECT_EQ(back.vertices[i].position, wp.vertices[i].position);
  for (size_t i = 0; i < wp.pairs.size(); ++i) {
    EXPECT_EQ(back.pairs[i].spin[0], wp.pairs[i].spin[0]);
    EXPECT_EQ(back.pairs[i].clock[1], wp.pairs[i].clock[1]);
  }
  EXPECT_EQ(back.loop_vertex, wp.loop_vertex);
  EXPECT_EQ(back.cell_face, wp.cell_face);
  fs::remove(path);
}

void expect_rejected(const std::string& name, const std::string& text) {
  const fs::path path = temp_file(name);
  std::ofstream(path) << text;
  try {
    load_winged_pair(path);
    ADD_FAILURE() << name << " was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
  fs::remove(path);
}

TEST(WingedPairIo, MalformedFilesThrowInputErrorNamingTheFile) {
  WingedPair wp = build_winged_pair(extract_polygons(make_vis_rooms()));
  const fs::path path = temp_file("good.wp");
  save_winged_pair(path, wp);
  std::stringstream ss;
  ss << std::ifstream(path).rdbuf();
  const std::string good = ss.str();
  fs::remove(path);
  expect_rejected("empty.wp", "");
  expect_rejected("header.wp", "not-a-winged-pair 1\n");
  expect_rejected("truncated.wp", good.substr(0, good.size() / 2));
  std::string bad_ref = good;
  bad_ref.replace(bad_ref.find("edges ") + 6, 0, "");
  size_t at = bad_ref.find('\n', bad_ref.find("edges ")) + 1;
  bad_ref.replace(at, bad_ref.find(' ', at) - at, "999999");
  expect_rejected("reference.wp", bad_ref);
  std::string nan_field = good;
  at = nan_field.find('\n', nan_field.find("vertices ")) + 1;
  nan_field.replace(at, nan_field.find(' ', at) - at, "abc");
  expect_rejected("field.wp", nan_field);
  try {
    load_winged_pair(temp_file("missing.wp"));
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("missing.wp"), std::string::npos);
  }
}

}  // namespace
}  // namespace proxima::visibility
