// study/demo.h: the demo as a library call — sections run in-process into one Results, a
// failing or unknown section is reported, the output directory holds what the page names.
#include "proxima/study/demo.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "proxima/core/error.h"
#include "test_util.h"

namespace proxima {
namespace {

study::DemoOptions tiny(std::vector<std::string> only) {
  study::DemoOptions o;
  o.only = std::move(only);
  o.width = 64;
  o.height = 48;
  o.threads = 2;
  return o;
}

TEST(DemoStudy, ReferenceSectionRunsInProcessAndNamesItsImages) {
  TempDir dir;
  Progress progress(stderr, false);
  const study::DemoRun run = study::run_demo(tiny({"reference"}), dir.path, progress);
  EXPECT_EQ(run.failed_sections, 0);
  ASSERT_EQ(run.results.sections.size(), 2u);  // "This run" + the reference section
  EXPECT_EQ(run.results.sections[0].id, "run");
  EXPECT_EQ(run.results.sections[1].id, "reference");
  ASSERT_EQ(run.results.images.size(), 2u);
  for (const auto& [role, file] : run.results.images) EXPECT_TRUE(std::filesystem::exists(dir.path / file)) << role;
  EXPECT_GT(run.results.metrics.at("cornell_render_ms"), 0.0);
  EXPECT_EQ(run.results.threads, 2);
}

TEST(DemoStudy, SectionIdsAreValidatedNamingTheFlag) {
  const std::vector<std::string> ids = study::demo_section_ids();
  EXPECT_EQ(ids.front(), "reference");
  EXPECT_NE(std::find(ids.begin(), ids.end(), "envmap"), ids.end());
  try {
    study::validate(tiny({"no-such-section"}));
    FAIL() << "unknown section accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--only"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("gibr"), std::string::npos);  // lists the valid ids
  }
  study::DemoOptions o = tiny({});
  o.threads = -1;
  EXPECT_THROW(study::validate(o), InputError);
}

}  // namespace
}  // namespace proxima
