// SPDX-License-Identifier: BSD-3-Clause
#include "app/output_folder.hpp"

#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <algorithm>
#include <filesystem>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <fstream>
#include <set>
#include <sstream>
#include <vector>

#include "app/launcher.hpp"
#include "io/case_file.hpp"
#include "io/input_file.hpp"
#include "io/json_out.hpp"

namespace igac {
namespace fs = std::filesystem;
namespace {

constexpr const char* kStagingTag = ".igac-tmp-";
// The list of what igac wrote into an output folder, one name a line: the
// only files a later run may replace.
constexpr const char* kManifest = ".igac-manifest";

// The files an igac output of a version before the manifest could hold
// (a folder with a manifest lists what was written, whatever its name).
bool is_igac_output_name(const std::string& f) {
  for (const char* exact : {"summary.json", "study.json", "study.csv", "study.svg", "pressure.csv", "pressure.svg",
                            "load_curve.csv", "load_curve.svg", "solution.pvd"})
    if (f == exact) return true;
  auto ends_with = [&](const char* tail) {
    const size_t n = std::strlen(tail);
    return f.size() > n && f.compare(f.size() - n, n, tail) == 0;
  };
  for (const char* prefix : {"solution_", "contact_", "multipliers_"})  // contact_<face>_XXXX.vtu too
    if (f.rfind(prefix, 0) == 0 && ends_with(".vtu")) return true;
  // a case with several contacts: pressure_<face>.csv and .svg
  if (f.rfind("pressure_", 0) == 0 && (ends_with(".csv") || ends_with(".svg"))) return true;
  return false;
}

// What in the existing folder `dir` igac did not write (at most a few names).
std::vector<std::string> foreign_entries(const fs::path& dir) {
  std::set<std::string> ours{kManifest};
  bool has_manifest = false;
  std::error_code ec;
  if (fs::exists(fs::symlink_status(dir / kManifest, ec))) try {
      // (a FIFO or a device there is not a manifest, and is foreign below)
      std::istringstream manifest(read_input_file((dir / kManifest).string(), kManifestFile));
      has_manifest = true;
      for (std::string line; std::getline(manifest, line);)
        if (!line.empty()) ours.insert(line);
    } catch (const InputError&) {
    }
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string f = e.path().filename().string();
    const bool listed = has_manifest ? ours.count(f) > 0 : is_igac_output_name(f);
    if (!listed || !e.is_regular_file(ec)) out.push_back(f);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// Staging folders of runs that are no longer alive, beside the folder
// `name` in `parent`.
std::vector<fs::path> dead_staging(const fs::path& parent, const std::string& name) {
  std::vector<fs::path> out;
  std::error_code ec;
  const std::string prefix = "." + name + kStagingTag;
  for (const auto& e : fs::directory_iterator(parent, ec)) {
    const std::string f = e.path().filename().string();
    if (f.rfind(prefix, 0) != 0) continue;
    const std::string pid_text = f.substr(prefix.size());
    char* end = nullptr;
    const long pid = std::strtol(pid_text.c_str(), &end, 10);
    if (pid_text.empty() || *end != '\0') continue;
    if (pid > 0 && pid != long(getpid()) && kill(pid_t(pid), 0) == 0) continue;  // a run still writing
    if (e.is_directory(ec)) out.push_back(e.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

std::vector<std::string> stopped_runs_beside(const std::string& target) {
  std::error_code ec;
  const fs::path abs = fs::absolute(target, ec).lexically_normal();
  const fs::path dir = abs.filename().empty() ? abs.parent_path() : abs;  // "out/" is "out"
  std::vector<std::string> out;
  for (const fs::path& p : dead_staging(dir.parent_path(), dir.filename().string())) out.push_back(p.string());
  return out;
}

OutputFolder::OutputFolder(std::string target) : target_(std::move(target)) {
  auto bad = [&](const std::string& why) {
    return InputError(fmt::format("--out '{}': {}", target_, why));
  };
  if (target_.empty()) throw bad("empty folder name");
  std::error_code ec;
  // A dangling symbolic link (the folder or one above it) would be found
  // only when the results are moved there, after the solve.
  for (fs::path p = fs::absolute(target_, ec).lexically_normal(); p.has_relative_path(); p = p.parent_path())
    if (fs::is_symlink(fs::symlink_status(p, ec)) && !fs::exists(p, ec))
      throw bad(fmt::format("{} is a symbolic link to {}, which does not exist", p.string(),
                            fs::read_symlink(p, ec).string()));
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
  // Only what igac wrote there (its manifest) may be replaced.
  if (fs::is_directory(abs, ec) && !fs::is_empty(abs, ec))
    if (const std::vector<std::string> foreign = foreign_entries(abs); !foreign.empty())
      throw bad(fmt::format("exists and holds what igac did not write ({}{}); it would be replaced: choose a new or "
                            "empty folder", fmt::join(foreign.begin(), foreign.begin() + std::min<size_t>(3, foreign.size()), ", "),
                            foreign.size() > 3 ? fmt::format(" and {} more", foreign.size() - 3) : ""));
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

void OutputFolder::create_staging(const std::string& keep) {
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
  for (const fs::path& p : dead_staging(parent, name))
    if (keep.empty() || !fs::equivalent(p, keep, ec)) fs::remove_all(p, ec);
  staging_ = (parent / ("." + name + kStagingTag + std::to_string(getpid()))).string();
  remove_on_termination(staging_);  // a SIGTERM from here on removes it (app/launcher.hpp)
  fs::remove_all(staging_, ec);
  if (!fs::create_directory(staging_, ec) || ec)
    throw bad(fmt::format("cannot create a folder beside it ({})", ec ? ec.message() : "already exists"));
}

std::string OutputFolder::commit() {
  std::error_code ec;
  {  // the manifest: what this run wrote, the only files a later run may replace
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(staging_, ec)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    std::string text;
    for (const auto& n : names) text += n + "\n";
    write_file_atomically((fs::path(staging_) / kManifest).string(), text);
  }
  if (!fs::exists(target_, ec)) {
    fs::rename(staging_, target_, ec);
    if (ec) throw std::runtime_error(fmt::format("cannot move the results into {}: {}", target_, ec.message()));
  } else {
    if (renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, target_.c_str(), RENAME_EXCHANGE) != 0)
      throw std::runtime_error(fmt::format("cannot move the results into {}: {}", target_, std::strerror(errno)));
    // staging_ now holds the previous output.  Of it, only what igac wrote
    // (its manifest) goes: anything put there since the check at the start
    // goes into the new output (where a later run refuses it as not igac's,
    // so it is never deleted), or, where the new output has a file of its
    // name, stays with the rest in a visible folder beside.
    std::vector<std::string> clashing;
    for (const std::string& f : foreign_entries(staging_)) {
      const fs::path from = fs::path(staging_) / f, to = fs::path(target_) / f;
      if (fs::exists(fs::symlink_status(to, ec)) || (fs::rename(from, to, ec), ec)) clashing.push_back(f);
    }
    if (clashing.empty()) {
      fs::remove_all(staging_, ec);  // now igac's files only
      committed_ = true;
      remove_on_termination("");
      return {};
    }
    // (RENAME_NOREPLACE: a folder of that name, even an empty one, stays as it is)
    std::string kept = staging_;
    for (int k = 0; k < 100 && kept == staging_; ++k) {
      const std::string name = fmt::format("{}.igac-kept-{}{}", target_, getpid(), k ? fmt::format("-{}", k) : "");
      if (renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, name.c_str(), RENAME_NOREPLACE) == 0) kept = name;
    }
    committed_ = true;
    remove_on_termination("");
    return fmt::format("--out '{}': {} put there during the run, where the run wrote a file of the same name: kept in "
                       "{}, with the previous output", target_, fmt::join(clashing, ", "), kept);
  }
  committed_ = true;
  remove_on_termination("");
  return {};
}

void OutputFolder::keep_on_termination() {
  kept_ = true;
  remove_on_termination("");
}

OutputFolder::~OutputFolder() {
  if (committed_ || staging_.empty()) return;
  remove_on_termination("");
  if (kept_) return;  // a stopped run, to restart
  std::error_code ec;
  fs::remove_all(staging_, ec);
  for (const auto& p : created_parents_) fs::remove(p, ec);  // innermost first; only if still empty
}

}  // namespace igac
