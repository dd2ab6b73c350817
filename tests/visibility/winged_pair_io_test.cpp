// Winged-pair files: exact round trip, and malformed files rejected with InputError naming
// the file.
#include "proxima/visibility/winged_pair_io.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "proxima/core/error.h"
#include "proxima/scene/visibility_models.h"
#include "proxima/visibility/bsp_build.h"
#include "proxima/visibility/visibility_map.h"
#include "proxima/scene/camera_path.h"

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


// The text of rooms' winged pair, as save_winged_pair writes it.
std::string rooms_text() {
  const fs::path path = temp_file("rooms_text.wp");
  save_winged_pair(path, build_winged_pair(extract_polygons(make_vis_rooms())));
  std::stringstream ss;
  ss << std::ifstream(path).rdbuf();
  fs::remove(path);
  return ss.str();
}

// The lines of section `name` (after its "name N" line), for editing.
std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}
std::string join_lines(const std::vector<std::string>& lines) {
  std::string out;
  for (const std::string& l : lines) out += l + "\n";
  return out;
}
size_t section_start(const std::vector<std::string>& lines, const std::string& name) {
  for (size_t i = 0; i < lines.size(); ++i)
    if (lines[i].rfind(name + " ", 0) == 0) return i + 1;
  ADD_FAILURE() << "no section " << name;
  return 0;
}

// A count the file cannot hold ("vertices 2000000000" in a 60-byte file) is rejected
// before the reader allocates 64 GB for it.
TEST(WingedPairIo, CountLargerThanTheFileIsRejectedBeforeAllocating) {
  expect_rejected("count.wp", "proxima-winged-pair 1\nscale 1 polygons 0\nvertices 2000000000\n0 0 0 -1\n");
  expect_rejected("pairs.wp",
                  "proxima-winged-pair 1\nscale 1 polygons 0\nvertices 0\nedges 0\nfaces 0\ncells 0\npairs 1000000\n");
}

// Links that are in range but do not close — a spin cycle that never returns to its
// edge's pair would make the silhouette test loop forever; a clock walk meeting itself
// would make finalize() quadratic — and non-finite or huge coordinates and non-unit
// normals are rejected before they reach the tracer.
TEST(WingedPairIo, LinksThatDoNotCloseAndBadNumbersAreRejected) {
  const std::vector<std::string> good = split_lines(rooms_text());
  auto edit = [&](const std::string& section, size_t row, size_t field, const std::string& value) {
    std::vector<std::string> lines = good;
    std::istringstream in(lines[section_start(lines, section) + row]);
    std::vector<std::string> fields;
    for (std::string f; in >> f;) fields.push_back(f);
    fields.at(field) = value;
    std::string line;
    for (const std::string& f : fields) line += (line.empty() ? "" : " ") + f;
    lines[section_start(lines, section) + row] = line;
    return join_lines(lines);
  };
  // pairs: face edge clock0 clock1 spin0 spin1 direction. Pair 0's spin0 pointing at itself
  // breaks the mutual spin links (its spin1 partner still points at it).
  expect_rejected("spin.wp", edit("pairs", 0, 4, "0"));
  expect_rejected("clock.wp", edit("pairs", 0, 2, "0"));
  expect_rejected("huge.wp", edit("vertices", 0, 0, "1e300"));
  expect_rejected("normal.wp", edit("faces", 0, 4, "0.5"));
  // The unedited text still loads (the edits above are what is rejected).
  const fs::path path = temp_file("good_again.wp");
  std::ofstream(path) << join_lines(good);
  EXPECT_NO_THROW(load_winged_pair(path));
  fs::remove(path);
}

// A structurally valid file whose cells overlap would make beam tracing loop forever. Here
// the faces through which a neighbor n of the camera's cell is left are glued to n on both
// sides: a beam goes n → n → n → …
TEST(WingedPairIo, OverlappingCellsFromAFileAreAnErrorNotAHang) {
  const Scene rooms = make_vis_rooms();
  const CameraPath& p = rooms.camera_paths.front();
  int stopped = 0;
  for (int frame = 0; frame < p.frames; frame += std::max(1, p.frames / 8)) {
    const Camera cam = camera_at_time(p, frame_time(p, frame), 32, 32, 1e-3f, 1e4f);
    const dvec3 eye(cam.position);
    WingedPair wp = build_winged_pair(extract_polygons(rooms));
    const uint32_t c = locate_cell(wp, eye);
    ASSERT_NE(c, kNone);
    for (uint32_t f : std::vector<uint32_t>(wp.faces_of_cell(c).begin(), wp.faces_of_cell(c).end())) {
      const uint32_t n = wp.cell_across(f, c);
      if (wp.faces[f].opaque() || n == kNone) continue;
      for (uint32_t g : std::vector<uint32_t>(wp.faces_of_cell(n).begin(), wp.faces_of_cell(n).end())) {
        Face& face = wp.faces[g];
        if (g == f || face.opaque() || wp.cell_across(g, n) == kNone) continue;
        if (face.cell[0] == n) {  // orient it so that n is in front (the tracer's test then reads cell[1])
          std::swap(face.cell[0], face.cell[1]);
          face.plane.normal = -face.plane.normal;
          face.plane.offset = -face.plane.offset;
        }
        if (face.plane.distance(eye) > 0.0) face.cell[0] = n;  // seen from n, and leads back into n
      }
    }
    const fs::path path = temp_file("overlap.wp");
    save_winged_pair(path, wp);
    const WingedPair back = load_winged_pair(path);  // consistent links: only tracing can tell
    fs::remove(path);
    try {
      trace_visibility_map(back, cam);
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("overlapping cells"), std::string::npos) << e.what();
      ++stopped;
    }
  }
  EXPECT_GT(stopped, 0) << "no frame's beams crossed a glued face";
}

}  // namespace
}  // namespace proxima::visibility
