// SPDX-License-Identifier: BSD-3-Clause
// Progress lines of a long solve, on stderr (beside the load steps'): a
// line when a phase begins ("factorising ..."), the lines the solve prints
// as it goes (an active-set iteration), and while one call runs long (a
// factorisation of a minute) a heartbeat "... still <phase> (N s)" after
// every `period` seconds without a line (4 s: a line at least every 5 s,
// the bar, with room for a busy machine).  Where the solve knows
// how far it is (fraction(): the load steps' load factor over the last)
// and stderr is a terminal, the heartbeat line ends with a bar
// (engine/progress_bar.hpp), as the step lines do; plain lines otherwise
// (a log, a pipe).
// Quiet: nothing, and no thread.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

#include <fmt/format.h>

#include "engine/progress_bar.hpp"
#include "engine/stopwatch.hpp"

namespace igac {

class Progress {
 public:
  // `offset_s`: seconds already spent (the times printed count from the run's start).
  explicit Progress(bool quiet, double offset_s = 0.0, double period_s = 4.0)
      : quiet_(quiet), offset_(offset_s), period_(period_s) {
    if (!quiet_) heartbeat_ = std::thread([this] { beat(); });
  }
  ~Progress() {
    if (!heartbeat_.joinable()) return;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    heartbeat_.join();
  }
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  // A phase begins: "<what> (<elapsed> s)"; the heartbeat names it.
  void phase(const std::string& what) {
    std::lock_guard<std::mutex> lock(mutex_);
    phase_ = what;
    print(fmt::format("{} ({:.1f} s)", what, seconds()));
  }
  // A line of the solve's own; `next`, when given, names what runs now
  // (for the heartbeat; not printed).
  void line(const std::string& text, const std::string& next = "") {
    std::lock_guard<std::mutex> lock(mutex_);
    print(text);
    if (!next.empty()) phase_ = next;
  }
  // What runs now, after a line printed elsewhere (the load steps'): named
  // for the heartbeat, nothing printed.
  void now(const std::string& what) {
    std::lock_guard<std::mutex> lock(mutex_);
    phase_ = what;
    if (!quiet_) mark_line();
  }
  // Held: nothing printed (the heartbeat neither) until released; e.g.
  // until PETSc has read its options in the first solve, so that a wrong
  // one stays a one-line input error.
  // Holding or releasing prints nothing, so the silence the heartbeat
  // counts goes on (a quiet inner solve, such as a coarser mesh's start,
  // released before the run has printed a line, must not restart it).
  void hold(bool held) {
    std::lock_guard<std::mutex> lock(mutex_);
    held_ = held;
    on_release_ = nullptr;
    late_release_ = false;
  }
  // Held while the work is short, released once it has run a period
  // without a line: `on_release` is called then (from the heartbeat's
  // thread, e.g. to print the run's header) and the heartbeat goes on.  A
  // long run is never silent for more than the period (issue 25: a line at
  // least every 5 s), a short one stays quiet (a wrong PETSc option found
  // in the first solve is one line).
  void hold_until_late(std::function<void()> on_release = {}) {
    std::lock_guard<std::mutex> lock(mutex_);
    held_ = true;
    late_release_ = true;
    on_release_ = std::move(on_release);
  }
  // How much of the whole is done, in [0, 1] (negative: not known).
  void fraction(double done) {
    std::lock_guard<std::mutex> lock(mutex_);
    fraction_ = done;
  }
  double seconds() const { return offset_ + clock_.seconds(); }
  bool quiet() const { return quiet_; }

 private:
  // The last line any Progress printed (or was told of, now()): the
  // heartbeat counts the silence from there, so that one Progress after
  // another (step 0's, then the solve's) does not add up their periods.
  static std::mutex& line_mutex() {
    static std::mutex m;
    return m;
  }
  static std::chrono::steady_clock::time_point& last_line() {  // under line_mutex()
    static std::chrono::steady_clock::time_point t = std::chrono::steady_clock::now();
    return t;
  }
  static void mark_line() {
    std::lock_guard<std::mutex> lock(line_mutex());
    last_line() = std::chrono::steady_clock::now();
  }
  static double since_line() {
    std::lock_guard<std::mutex> lock(line_mutex());
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - last_line()).count();
  }
  void print(const std::string& text) {  // under mutex_
    if (quiet_ || held_) return;
    fmt::print(stderr, "{}\n", text);
    mark_line();
  }
  void beat() {
    std::unique_lock<std::mutex> lock(mutex_);
    while (!stop_) {
      const double left = period_ - since_line();
      if (left <= 0) {  // (held or without a phase: nothing printed, but the period starts again)
        if (held_ && late_release_) {
          held_ = late_release_ = false;
          if (std::function<void()> release = std::move(on_release_)) {
            lock.unlock();
            release();
            lock.lock();
          }
        }
        if (!phase_.empty())
          print(fmt::format("  ... still {} ({:.0f} s){}", phase_, seconds(),
                            fraction_ >= 0 ? progress_suffix(fraction_) : std::string()));
        mark_line();
        continue;
      }
      wake_.wait_for(lock, std::chrono::duration<double>(left));
    }
  }

  bool quiet_;
  double offset_, period_;
  Stopwatch clock_;
  std::string phase_;
  double fraction_ = -1;                             // not known
  bool stop_ = false, held_ = false, late_release_ = false;
  std::function<void()> on_release_;  // of hold_until_late
  std::mutex mutex_;
  std::condition_variable wake_;
  std::thread heartbeat_;
};

}  // namespace igac
