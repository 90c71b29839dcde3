// SPDX-License-Identifier: BSD-3-Clause
// An output folder that is never seen half-written.  A run writes into a
// fresh hidden sibling (".NAME.igac-tmp-PID") and, when it ends, swaps it
// with the target in one atomic rename (renameat2 RENAME_EXCHANGE), then
// removes the old contents.  A run killed at any moment therefore leaves the
// target as the previous complete run left it.  Its staging folder, until
// the run has written a state to restart from (keep_on_termination), is
// removed at once when a termination signal (SIGTERM, SIGINT, SIGHUP) ends
// the run, and by the next run that writes beside it when nothing could
// (SIGKILL).  From then on it stays when the run is stopped or killed: a
// stopped run, no summary.json in it, that `igac run --restart NAME`
// continues (app/restart.hpp); the next run into NAME removes it.
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
  // Creates the staging folder (and the target's parents), and removes the
  // staging folders of stopped runs beside the target but `keep` (the one a
  // restart continues); call it once the input is known to be good.  Throws
  // InputError naming --out.
  void create_staging(const std::string& keep = "");
  // From now on a termination signal, or an error that ends the run before
  // commit, leaves the staging folder in place (it holds a state to restart
  // from).
  void keep_on_termination();
  ~OutputFolder();  // removes the staging folder unless committed or kept
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  // Where the run writes its files.
  const std::string& staging() const { return staging_; }
  const std::string& target() const { return target_; }
  // Puts the staged files in place of the target, atomically, and removes
  // of the previous output only the files igac wrote (its manifest): what
  // anyone put into the target during the run is moved into the new output,
  // or, where the run wrote a file of its name, kept with the previous
  // output in a folder beside, TARGET.igac-kept-PID.  Returns "" or, then, a
  // line saying so.  Throws std::runtime_error naming the folder when the
  // file system refuses the swap.
  std::string commit();

 private:
  std::string target_, staging_;
  std::vector<std::string> created_parents_;  // created for the staging folder, innermost first
  bool committed_ = false, kept_ = false;
};

// The staging folders beside `target` (an output folder) of runs that are no
// longer alive, stopped or killed before they ended.
std::vector<std::string> stopped_runs_beside(const std::string& target);

}  // namespace igac
