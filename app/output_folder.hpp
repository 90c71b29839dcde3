// SPDX-License-Identifier: BSD-3-Clause
// An output folder that is never seen half-written.  A run writes into a
// fresh hidden sibling (".NAME.igac-tmp-PID") and, when it ends, swaps it
// with the target in one atomic rename (renameat2 RENAME_EXCHANGE), then
// removes the old contents.  A run killed at any moment therefore leaves the
// target as the previous complete run left it; its staging folder is removed
// at once when a termination signal (SIGTERM, SIGINT, SIGHUP) ends the run,
// and by the next run that writes beside it when nothing could (SIGKILL).
#pragma once

#include <string>
#include <vector>

namespace igac {

class OutputFolder {
 public:
  // Checks `target` (the --out folder) before any work, writing nothing: it
  // must not be a file, nor lie under /proc, /sys or /dev, nor be the current
  // folder or above it; if it exists it must be empty or an earlier igac
  // output (summary.json or study.json), since it is replaced as a whole; the
  // folder it would be created in must be writable.  Throws InputError naming --out.
  explicit OutputFolder(std::string target);
  // Creates the staging folder (and the target's parents); call it once the
  // input is known to be good.  Throws InputError naming --out.
  void create_staging();
  ~OutputFolder();  // removes the staging folder unless committed
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  // Where the run writes its files.
  const std::string& staging() const { return staging_; }
  const std::string& target() const { return target_; }
  // Puts the staged files in place of the target, atomically.  Throws
  // std::runtime_error naming the folder when the file system refuses.
  void commit();

 private:
  std::string target_, staging_;
  std::vector<std::string> created_parents_;  // created for the staging folder, innermost first
  bool committed_ = false;
};

}  // namespace igac
