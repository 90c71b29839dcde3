// PNG plots drawn by the Python scripts in scripts/ with Debian's
// python3-matplotlib.  A missing plotting tool is a warning, not a failure:
// the CSV next to the plot holds the same numbers.
#pragma once

#include <string>
#include <vector>

namespace igac {

// Runs a program with this argument vector (argv[0] looked up in PATH), no
// shell in between, its output discarded; its exit code, or -1 when it could
// not be started or did not exit normally.
int run_program(const std::vector<std::string>& argv);

// Runs scripts/<script> CSV PNG TITLE; the picture replaces PNG only when it
// was drawn completely.  Returns false (and prints a warning unless quiet)
// when the plot could not be drawn.
bool draw_plot(const std::string& script, const std::string& csv, const std::string& png, const std::string& title,
               bool quiet);

}  // namespace igac
