// SPDX-License-Identifier: BSD-3-Clause
// The typed run status (engine/run_status.hpp): a run that has not said how
// it ended is no success, and the exit code follows from the outcome alone
// (it was chosen by the text: status.starts_with("stopped after step")).
#include <gtest/gtest.h>

#include "engine/run_status.hpp"

namespace igac {
namespace {

TEST(RunStatus, NothingSaidIsNoSuccess) {
  const RunStatus s;
  EXPECT_FALSE(s.is_set());
  EXPECT_FALSE(s.is_converged());
  EXPECT_EQ(s.exit_code(), 1);
  EXPECT_EQ(s, "not run");
}

TEST(RunStatus, TheExitCodeFollowsTheOutcome) {
  EXPECT_EQ(RunStatus::converged().exit_code(), 0);
  EXPECT_EQ(RunStatus::stopped_as_asked(3).exit_code(), 0);
  EXPECT_EQ(RunStatus::stopped_as_asked(3), "stopped after step 3 (as asked)");
  // A failure whose words read like a stop is still a failure.
  const RunStatus f = RunStatus::failed("stopped after step 3 (as asked), then the line search found no decrease");
  EXPECT_EQ(f.outcome(), RunStatus::Outcome::failed);
  EXPECT_EQ(f.exit_code(), 1);
  EXPECT_EQ(fmt::format("{}", f), f.text());
}

}  // namespace
}  // namespace igac
