// SPDX-License-Identifier: BSD-3-Clause
#include "app/launcher.hpp"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <initializer_list>
#include <stdexcept>
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
