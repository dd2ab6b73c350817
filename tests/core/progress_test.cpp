#include "proxima/core/progress.h"

#include <cstdio>
#include <stdexcept>
#include <vector>
#include <string>

#include <gtest/gtest.h>

namespace proxima {
namespace {

TEST(Progress, LineHasBarCountAndEta) {
  // 2 of 8 steps in 10 s: 5 s per step, 6 left → ETA 30 s.
  EXPECT_EQ(progress_line("sampling", "grass", 2, 8, 10.0, 8), "sampling [##......] 2/8 grass  10s, ETA 30s");
  EXPECT_EQ(progress_line("maps", "", 0, 4, 0.0, 0), "maps 0/4  0s");  // no ETA before a step is done
  EXPECT_EQ(progress_line("maps", "done", 4, 4, 125.0, 4), "maps [####] 4/4 done  2m05s");
}

TEST(Progress, PlainLinesWhenNotATerminal) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  {
    Progress p(f, false);
    p.begin("stage", 2);
    p.step("a");
    p.step("b");
  }  // the destructor ends the stage
  std::rewind(f);
  std::string text;
  char buf[256];
  while (std::fgets(buf, sizeof buf, f)) text += buf;
  std::fclose(f);
  EXPECT_EQ(text.find('\r'), std::string::npos);  // no in-place redraws in logs
  EXPECT_NE(text.find("stage 0/2 a"), std::string::npos) << text;
  EXPECT_NE(text.find("stage 1/2 b"), std::string::npos) << text;
  EXPECT_NE(text.find("stage 2/2 done"), std::string::npos) << text;
}

TEST(Progress, ListenerHearsEveryStepAndTheEnd) {
  std::vector<ProgressEvent> events;
  {
    Progress p([&](const ProgressEvent& e) { events.push_back(e); });
    p.begin("stage", 2);
    p.step("a");
    p.step("b");
  }  // the destructor ends the stage
  ASSERT_EQ(events.size(), 3u);
  EXPECT_EQ(events[0].stage, "stage");
  EXPECT_EQ(events[0].what, "a");
  EXPECT_EQ(events[0].done, 0);
  EXPECT_EQ(events[1].done, 1);
  EXPECT_EQ(events[2].what, "done");
  EXPECT_EQ(events[2].done, 2);
  EXPECT_EQ(events[2].total, 2);
}

TEST(Progress, ListenerExceptionPropagatesAndClosesTheStage) {
  int calls = 0;
  {
    Progress p([&](const ProgressEvent&) {
      ++calls;
      throw std::runtime_error("stop");
    });
    p.begin("stage", 3);
    EXPECT_THROW(p.step("a"), std::runtime_error);
    EXPECT_THROW(p.end(), std::runtime_error);
    p.end();  // closed: no further call
  }  // nor from the destructor
  EXPECT_EQ(calls, 2);
}

}  // namespace
}  // namespace proxima
