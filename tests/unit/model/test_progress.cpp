// SPDX-License-Identifier: BSD-3-Clause
// The progress lines of a long solve (model/progress.hpp): a heartbeat
// names the phase while one call runs long; quiet and held print nothing.
#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <thread>

#include "model/progress.hpp"

namespace igac {
namespace {

size_t count_of(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

std::string run(bool quiet, bool held) {
  testing::internal::CaptureStderr();
  {
    Progress p(quiet, 0.0, 0.1);
    if (held) p.hold(true);
    p.phase("factorising K");
    std::this_thread::sleep_for(std::chrono::milliseconds(450));  // one long call: no line of its own
    p.line("active set   1: 3 active, 0 changing");
  }
  return testing::internal::GetCapturedStderr();
}

TEST(Progress, HeartbeatNamesWhatRunsLong) {
  const std::string out = run(false, false);
  EXPECT_EQ(out.rfind("factorising K (0.0 s)\n", 0), 0u) << out;
  EXPECT_GE(count_of(out, "  ... still factorising K ("), 2u) << out;  // every 0.1 s without a line
  EXPECT_NE(out.find("active set   1: 3 active, 0 changing\n"), std::string::npos) << out;
}

TEST(Progress, BarShowsTheFractionDone) {
  EXPECT_EQ(progress_bar(0.0), "[--------------------] 0 %");
  EXPECT_EQ(progress_bar(0.4), "[########------------] 40 %");
  EXPECT_EQ(progress_bar(1.0), "[####################] 100 %");
  EXPECT_EQ(progress_bar(1.7), progress_bar(1.0));  // clamped
  EXPECT_EQ(progress_bar(-0.2, 4), "[----] 0 %");
}

TEST(Progress, QuietAndHeldPrintNothing) {
  EXPECT_EQ(run(true, false), "");
  EXPECT_EQ(run(false, true), "");
}

// Held until late (the PETSc path until its first solve, a large mesh's
// step 0): a short hold prints nothing, and one that lasts a period
// releases itself, calls its callback once (the run's header) and goes on
// with the heartbeat: a 3D PETSc run was silent for its first 177 s.
TEST(Progress, HoldUntilLateReleasesALongHold) {
  int released = 0;
  testing::internal::CaptureStderr();
  {
    Progress p(false, 0.0, 0.1);
    p.hold_until_late([&] {
      ++released;
      fmt::print(stderr, "HEADER\n");
    });
    p.phase("the active-set iterations with PETSc");
    std::this_thread::sleep_for(std::chrono::milliseconds(450));
  }
  const std::string out = testing::internal::GetCapturedStderr();
  EXPECT_EQ(released, 1);
  EXPECT_EQ(out.rfind("HEADER\n  ... still the active-set iterations with PETSc (", 0), 0u) << out;
  EXPECT_GE(count_of(out, "  ... still the active-set iterations with PETSc ("), 2u) << out;
  // A short one: nothing, no callback.
  testing::internal::CaptureStderr();
  {
    Progress p(false, 0.0, 30.0);
    p.hold_until_late([&] { ++released; });
    p.phase("writing step 0");
  }
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  EXPECT_EQ(released, 1);
}

// One Progress after another (step 0's, then the solve's) counts the
// silence from the last line of either: a new one does not start a fresh
// period (measured before: 8.2 s without a line between the two).
TEST(Progress, SilenceCountsFromTheLastLineOfAnyProgress) {
  testing::internal::CaptureStderr();
  {
    Progress first(false, 0.0, 1.0);
    first.line("step 0 begins");
    std::this_thread::sleep_for(std::chrono::milliseconds(800));
  }
  {
    Progress second(false, 0.0, 1.0);
    second.hold_until_late();
    second.phase("setting up");
    std::this_thread::sleep_for(std::chrono::milliseconds(800));  // its own period would end at 1.0 s
  }
  const std::string out = testing::internal::GetCapturedStderr();
  EXPECT_EQ(count_of(out, "  ... still setting up ("), 1u) << out;
}

// A quiet inner solve (the coarser meshes a PETSc run starts from) holds and
// releases its own Progress without printing: that must not restart the
// silence of the run around it (measured before: the header of a 3D PETSc
// run came at 5.2 s, after two coarse solves had each restarted the count).
TEST(Progress, AQuietInnerSolveDoesNotRestartTheSilence) {
  testing::internal::CaptureStderr();
  {
    Progress outer(false, 0.0, 1.0);
    outer.hold_until_late([] { fmt::print(stderr, "HEADER\n"); });
    outer.phase("the active-set iterations with PETSc");
    for (int k = 0; k < 3; ++k) {  // an inner solve every 0.4 s: before, each one restarted the period
      std::this_thread::sleep_for(std::chrono::milliseconds(400));
      Progress inner(true);
      inner.hold(false);
      inner.now("a coarser mesh's solve");
    }
  }  // 1.2 s in all: the outer period (1 s) ended once
  const std::string out = testing::internal::GetCapturedStderr();
  EXPECT_EQ(out.rfind("HEADER\n  ... still the active-set iterations with PETSc (", 0), 0u) << out;
}

}  // namespace
}  // namespace igac
