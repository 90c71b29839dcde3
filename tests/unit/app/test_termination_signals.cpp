// SPDX-License-Identifier: BSD-3-Clause
// A SIGTERM ends igac whatever library runs when it comes
// (end_on_termination_signals, app/launcher.hpp).  A library may install a
// SIGTERM handler of its own for the time of a call (METIS does, inside a
// fill-reducing ordering, for its error returns): a SIGTERM sent then was
// swallowed and the run went on (a 2M-dof run under `timeout 60` ran 421 s
// and reported converged).
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <thread>

#include "app/launcher.hpp"

namespace {

void swallow(int) {}  // a library's handler that returns as if nothing came

TEST(TerminationSignals, SigtermEndsTheProcessThroughALibrarysOwnHandler) {
  // "fast": the child is a fork of this process, which runs only the statement
  GTEST_FLAG_SET(death_test_style, "fast");
  for (int sig : {SIGTERM, SIGINT}) {
    EXPECT_EXIT(
        {
          igac::end_on_termination_signals();
          signal(sig, swallow);  // as the library does on entry
          kill(getpid(), sig);
          std::this_thread::sleep_for(std::chrono::seconds(5));
          std::exit(0);  // the signal was swallowed
        },
        testing::ExitedWithCode(128 + sig), "stopped by");
  }
}

// A signal the parent set to be ignored stays ignored (`nohup igac run ...`
// ignores SIGHUP): blocking it would queue it, and the run would end.
TEST(TerminationSignals, SignalIgnoredByTheParentStaysIgnored) {
  // "fast": the child is a fork of this process, which runs only the statement
  GTEST_FLAG_SET(death_test_style, "fast");
  EXPECT_EXIT(
      {
        signal(SIGHUP, SIG_IGN);  // as nohup leaves it
        igac::end_on_termination_signals();
        kill(getpid(), SIGHUP);
        std::this_thread::sleep_for(std::chrono::milliseconds(300));
        std::exit(0);  // the run went on
      },
      testing::ExitedWithCode(0), "");
}

}  // namespace
