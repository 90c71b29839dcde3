// SPDX-License-Identifier: BSD-3-Clause
#include "app/launcher.hpp"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <initializer_list>
#include <mutex>
#include <stdexcept>
#include <pthread.h>
#include <signal.h>
#include <string>
#include <thread>
#include <unistd.h>

namespace igac {
namespace {
int env_int(std::initializer_list<const char*> names, int fallback) {
  for (const char* n : names)
    if (const char* v = std::getenv(n)) return std::atoi(v);
  return fallback;
}
}  // namespace

int launcher_rank() { return env_int({"OMPI_COMM_WORLD_RANK", "PMI_RANK", "PMIX_RANK"}, 0); }
int launcher_size() { return env_int({"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"}, 1); }

namespace {
// SIGTERM, SIGINT and SIGHUP, less those the parent set to be ignored
// (nohup ignores SIGHUP, a shell's background job SIGINT): a blocked signal
// is queued even when ignored, and sigwait would then end the run.
sigset_t termination_signals() {
  sigset_t set;
  sigemptyset(&set);
  for (int sig : {SIGTERM, SIGINT, SIGHUP}) {
    struct sigaction now {};
    if (sigaction(sig, nullptr, &now) == 0 && now.sa_handler == SIG_IGN) continue;
    sigaddset(&set, sig);
  }
  return set;
}
}  // namespace

void block_termination_signals_in_every_thread(char** argv) {
  const sigset_t set = termination_signals();
  sigset_t now;
  pthread_sigmask(SIG_BLOCK, nullptr, &now);
  bool blocked = true;
  for (int sig : {SIGTERM, SIGINT, SIGHUP})
    if (sigismember(&set, sig)) blocked = blocked && sigismember(&now, sig);
  if (blocked) return;
  pthread_sigmask(SIG_BLOCK, &set, nullptr);
  execv("/proc/self/exe", argv);  // the mask survives exec; on failure go on as we are
}

namespace {
std::mutex removal_mutex;
std::string folder_to_remove;  // guarded by removal_mutex
}  // namespace

void remove_on_termination(const std::string& folder) {
  std::lock_guard<std::mutex> lock(removal_mutex);
  folder_to_remove = folder;
}

void end_on_termination_signals() {
  const sigset_t set = termination_signals();
  pthread_sigmask(SIG_BLOCK, &set, nullptr);
  std::thread([set] {
    int sig = 0;
    if (sigwait(&set, &sig) != 0) return;
    // End here, with the status a shell gives a process the signal killed:
    // re-raising it would run whatever handler a library holds at that
    // moment (METIS's longjmps into the thread it interrupted).
    {
      // Held to the end: the run cannot register or commit a folder meanwhile.
      // A file written between two sweeps keeps the folder: sweep again.
      std::lock_guard<std::mutex> lock(removal_mutex);
      std::error_code ec;
      for (int sweep = 0; sweep < 3 && !folder_to_remove.empty() && std::filesystem::exists(folder_to_remove, ec); ++sweep)
        std::filesystem::remove_all(folder_to_remove, ec);
    }
    const std::string line = fmt::format("igac: stopped by {}\n", sig == SIGTERM ? "SIGTERM" : sig == SIGINT ? "SIGINT" : "SIGHUP");
    [[maybe_unused]] const ssize_t written = write(STDERR_FILENO, line.data(), line.size());
    _exit(128 + sig);
  }).detach();
}

void hand_over_to_petsc_build(char** argv) {
  std::error_code ec;
  const auto self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) return;
  const auto petsc = self.parent_path() / "igac-petsc";
  if (!std::filesystem::exists(petsc, ec)) return;
  execv(petsc.c_str(), argv);
  throw std::runtime_error(fmt::format("cannot start {}: {}", petsc.string(), std::strerror(errno)));
}

}  // namespace igac
