// SPDX-License-Identifier: BSD-3-Clause
// Running the igac executable from a test: a fresh temporary folder per
// test, shell quoting, and the exit code with the output (2>&1).
#pragma once

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace igac_test {

// A fresh empty folder for one test, removed at the end.
class TempDir {
 public:
  explicit TempDir(const std::string& tag) {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = std::string(info->test_suite_name()) + "_" + info->name();
    for (char& c : name)
      if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    path_ = std::filesystem::temp_directory_path() / ("igac_test_" + tag + "_" + name + "_" + std::to_string(getpid()));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  const std::filesystem::path& path() const { return path_; }
  bool empty() const { return std::filesystem::is_empty(path_); }

 private:
  std::filesystem::path path_;
};

inline std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

struct Outcome {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

// Runs the shell command COMMAND (stderr joined to stdout) in `cwd`.
inline Outcome run_command(const std::string& command, const std::filesystem::path& cwd) {
  const std::string cmd = "cd " + quote(cwd.string()) + " && " + command + " 2>&1";
  Outcome o;
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) {
    ADD_FAILURE() << "popen failed for " << cmd;
    return o;
  }
  std::array<char, 4096> buf;
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) o.output.append(buf.data(), n);
  const int status = pclose(pipe);
  o.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return o;
}

// Runs `igac ARGS` with the working directory `cwd`, capturing 2>&1;
// `shell` runs first in the same shell (e.g. "ulimit -v N;").
inline Outcome run_igac(const std::string& args, const std::filesystem::path& cwd, const std::string& shell = "") {
  return run_command(shell + " " + quote(IGAC_BINARY) + " " + args, cwd);
}

// `scripts/mpirun.sh N igac ARGS` in `cwd` (the PETSc path on N processes).
inline Outcome run_mpi(int n, const std::string& args, const std::filesystem::path& cwd) {
  return run_command("IGAC_BINARY=" + quote(IGAC_BINARY) + " " +
                         quote(std::string(IGAC_SOURCE_DIR) + "/scripts/mpirun.sh") + " " + std::to_string(n) + " " + args,
                     cwd);
}

// The whole text of a file ("" when it cannot be read).
inline std::string read_file(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// An output folder's summary.json, parsed (throws when it is not JSON).
inline nlohmann::json read_summary(const std::filesystem::path& out) {
  std::ifstream in(out / "summary.json");
  return nlohmann::json::parse(in);
}

// The cells of a CSV file, row by row (a trailing comma is an empty cell).
inline std::vector<std::vector<std::string>> csv_rows(const std::filesystem::path& p) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(read_file(p));
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::string cell;
    std::istringstream ls(line);
    while (std::getline(ls, cell, ',')) cells.push_back(cell);
    if (!line.empty() && line.back() == ',') cells.emplace_back();
    rows.push_back(cells);
  }
  return rows;
}

// The index of the column named `name` in a CSV's header row (0 when absent:
// column 0 is the load factor in igac's CSVs, never a looked-up one).
inline size_t csv_column(const std::vector<std::vector<std::string>>& rows, const std::string& name) {
  if (rows.empty()) return 0;
  for (size_t c = 0; c < rows[0].size(); ++c)
    if (rows[0][c] == name) return c;
  return 0;
}

}  // namespace igac_test
