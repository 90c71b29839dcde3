// SPDX-License-Identifier: BSD-3-Clause
// How a run ended: its outcome, from which the program's exit code follows,
// and the line that says it (the console's `status`, summary.json's
// "status", the Python module's).  A run that has not said how it ended
// has not succeeded: the default is `not_run`, never `converged`.
#pragma once

#include <ostream>
#include <string>
#include <string_view>

#include <fmt/format.h>

namespace igac {

class RunStatus {
 public:
  enum class Outcome {
    not_run,           // nothing said yet: not a success
    converged,         // every step solved
    stopped_as_asked,  // --stop-after-step K: the steps up to K solved, a restart continues
    failed,            // a step, a solve or a check failed; the text says which and why
  };

  RunStatus() = default;
  static RunStatus converged() { return {Outcome::converged, "converged"}; }
  static RunStatus stopped_as_asked(int step) {
    return {Outcome::stopped_as_asked, fmt::format("stopped after step {} (as asked)", step)};
  }
  static RunStatus failed(std::string why) { return {Outcome::failed, std::move(why)}; }

  Outcome outcome() const { return outcome_; }
  bool is_converged() const { return outcome_ == Outcome::converged; }
  bool is_set() const { return outcome_ != Outcome::not_run; }
  // 0 for a run that converged or stopped where it was asked to, 1 otherwise.
  int exit_code() const { return outcome_ == Outcome::converged || outcome_ == Outcome::stopped_as_asked ? 0 : 1; }

  const std::string& text() const { return text_; }
  operator const std::string&() const { return text_; }  // NOLINT: printed and written as its text
  friend bool operator==(const RunStatus& s, std::string_view text) { return s.text_ == text; }
  friend std::ostream& operator<<(std::ostream& out, const RunStatus& s) { return out << s.text_; }

 private:
  RunStatus(Outcome o, std::string text) : outcome_(o), text_(std::move(text)) {}
  Outcome outcome_ = Outcome::not_run;
  std::string text_ = "not run";
};

}  // namespace igac

template <>
struct fmt::formatter<igac::RunStatus> : fmt::formatter<std::string_view> {
  auto format(const igac::RunStatus& s, format_context& ctx) const {
    return fmt::formatter<std::string_view>::format(s.text(), ctx);
  }
};
