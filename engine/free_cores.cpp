// SPDX-License-Identifier: BSD-3-Clause
#include "engine/free_cores.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <system_error>
#include <omp.h>

namespace igac {

namespace {
// /proc/stat's procs_running (the runnable threads, the caller included),
// or 0 where it cannot be read.
int runnable_threads() {
  std::FILE* f = std::fopen("/proc/stat", "r");
  if (!f) return 0;
  char line[256];
  int running = 0;
  while (std::fgets(line, sizeof line, f))
    if (std::strncmp(line, "procs_running ", 14) == 0) {
      running = std::atoi(line + 14);
      break;
    }
  std::fclose(f);
  return running;
}

// This process's runnable threads (the caller, and workers of an OpenMP or
// OpenBLAS team that still spin after their last call; see the header).
int own_runnable_threads() {
  int own = 0;
  std::error_code ec;
  for (const auto& task : std::filesystem::directory_iterator("/proc/self/task", ec)) {
    std::FILE* f = std::fopen((task.path() / "stat").c_str(), "r");
    if (!f) continue;
    char buf[512];
    const size_t n = std::fread(buf, 1, sizeof buf - 1, f);
    std::fclose(f);
    buf[n] = 0;
    // "pid (comm) S ...": the state follows the last ')'
    const char* close = std::strrchr(buf, ')');
    if (close && close[1] == ' ' && close[2] == 'R') ++own;
  }
  return own;
}
}  // namespace

int free_cores() {
  const int available = std::max(1, omp_get_max_threads());
  if (available == 1) return 1;
  const int running = runnable_threads();
  if (running <= 0) return available;
  const int others = running - std::max(1, own_runnable_threads());
  return std::clamp(available - others, 1, available);
}

}  // namespace igac
