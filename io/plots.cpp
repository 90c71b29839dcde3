#include "io/plots.hpp"

#include <cerrno>
#include <fcntl.h>
#include <filesystem>
#include <fmt/format.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

extern char** environ;

namespace igac {

int run_program(const std::vector<std::string>& argv) {
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  // The child's output would interleave with igac's: send it nowhere.
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  const int rc = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) return -1;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

bool draw_plot(const std::string& script, const std::string& csv, const std::string& png, const std::string& title,
               bool quiet) {
  const std::string path = std::string(IGAC_SOURCE_DIR) + "/scripts/" + script;
  // Debian's interpreter, where python3-matplotlib is installed.
  const std::string python = std::filesystem::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  // Drawn beside the target, renamed over it only when complete: a kill or a
  // failure never leaves a short picture in place of a good one.
  const std::string tmp = fmt::format("{}.tmp{}.png", png, getpid());
  const int rc = run_program({python, path, csv, tmp, title});
  std::error_code ec;
  const bool ok = rc == 0 && std::filesystem::file_size(tmp, ec) > 0 && !ec;
  if (ok) std::filesystem::rename(tmp, png, ec);
  std::filesystem::remove(tmp, ec);
  if (!ok && !quiet) fmt::print(stderr, "igac: warning: could not draw a plot ({} failed)\n", script);
  return ok;
}

}  // namespace igac
