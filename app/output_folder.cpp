// SPDX-License-Identifier: BSD-3-Clause
#include "app/output_folder.hpp"

#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>

#include "io/case_file.hpp"

namespace igac {
namespace fs = std::filesystem;
namespace {

constexpr const char* kStagingTag = ".igac-tmp-";

// Staging folders of runs that are no longer alive, beside `target`.
void remove_abandoned_staging(const fs::path& parent, const std::string& name) {
  std::error_code ec;
  const std::string prefix = "." + name + kStagingTag;
  for (const auto& e : fs::directory_iterator(parent, ec)) {
    const std::string f = e.path().filename().string();
    if (f.rfind(prefix, 0) != 0) continue;
    const std::string pid_text = f.substr(prefix.size());
    char* end = nullptr;
    const long pid = std::strtol(pid_text.c_str(), &end, 10);
    if (pid_text.empty() || *end != '\0') continue;
    if (pid > 0 && kill(pid_t(pid), 0) == 0) continue;  // a run still writing
    fs::remove_all(e.path(), ec);
  }
}

}  // namespace

OutputFolder::OutputFolder(std::string target) : target_(std::move(target)) {
  auto bad = [&](const std::string& why) {
    return InputError(fmt::format("--out '{}': {}", target_, why));
  };
  if (target_.empty()) throw bad("empty folder name");
  std::error_code ec;
  const fs::path abs = fs::weakly_canonical(fs::absolute(target_, ec), ec);
  for (const char* system : {"/proc", "/sys", "/dev"}) {
    const std::string s = abs.string();
    if (s == system || s.rfind(std::string(system) + "/", 0) == 0)
      throw bad(fmt::format("lies under {}, which is not a place for results", system));
  }
  if (fs::exists(abs, ec) && !fs::is_directory(abs, ec)) throw bad("exists and is not a folder");
  // The folder is replaced as a whole when the run ends: never one that holds
  // anything but an earlier igac output, nor the folder we stand in.
  const fs::path here = fs::current_path(ec);
  for (fs::path p = here; !p.empty(); p = p.parent_path()) {
    if (p == abs) throw bad("is the current folder or one above it; results go to a folder of their own");
    if (p == p.parent_path()) break;
  }
  if (fs::is_directory(abs, ec) && !fs::is_empty(abs, ec) && !fs::exists(abs / "summary.json", ec) &&
      !fs::exists(abs / "study.json", ec))
    throw bad("exists and holds files that are not an igac output (no summary.json or study.json); it would be "
              "replaced: choose a new or empty folder");
  const fs::path parent = abs.parent_path();
  if (abs.filename().empty() || abs.filename() == "." || abs.filename() == "..") throw bad("names no folder");
  // Nothing is created yet: the nearest existing ancestor must let us create.
  fs::path existing = parent;
  while (!fs::exists(existing, ec) && existing.has_parent_path() && existing != existing.parent_path())
    existing = existing.parent_path();
  if (!fs::is_directory(existing, ec)) throw bad(fmt::format("{} is not a folder", existing.string()));
  if (access(existing.c_str(), W_OK | X_OK) != 0)
    throw bad(fmt::format("{} is not writable ({})", existing.string(), std::strerror(errno)));
  target_ = abs.string();
}

void OutputFolder::create_staging() {
  auto bad = [&](const std::string& why) {
    return InputError(fmt::format("--out '{}': {}", target_, why));
  };
  std::error_code ec;
  const fs::path abs(target_);
  const fs::path parent = abs.parent_path();
  const std::string name = abs.filename().string();
  for (fs::path p = parent; !p.empty() && !fs::exists(p, ec) && p != p.parent_path(); p = p.parent_path())
    created_parents_.push_back(p.string());
  fs::create_directories(parent, ec);
  if (ec) throw bad(fmt::format("cannot create its parent folder ({})", ec.message()));
  remove_abandoned_staging(parent, name);
  staging_ = (parent / ("." + name + kStagingTag + std::to_string(getpid()))).string();
  fs::remove_all(staging_, ec);
  if (!fs::create_directory(staging_, ec) || ec)
    throw bad(fmt::format("cannot create a folder beside it ({})", ec ? ec.message() : "already exists"));
}

void OutputFolder::commit() {
  std::error_code ec;
  if (!fs::exists(target_, ec)) {
    fs::rename(staging_, target_, ec);
    if (ec) throw std::runtime_error(fmt::format("cannot move the results into {}: {}", target_, ec.message()));
  } else {
    if (renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, target_.c_str(), RENAME_EXCHANGE) != 0)
      throw std::runtime_error(fmt::format("cannot move the results into {}: {}", target_, std::strerror(errno)));
    fs::remove_all(staging_, ec);  // now the previous run's files
  }
  committed_ = true;
}

OutputFolder::~OutputFolder() {
  if (committed_ || staging_.empty()) return;
  std::error_code ec;
  fs::remove_all(staging_, ec);
  for (const auto& p : created_parents_) fs::remove(p, ec);  // innermost first; only if still empty
}

}  // namespace igac
