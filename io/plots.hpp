// PNG plots drawn by the Python scripts in scripts/ with Debian's
// python3-matplotlib.  A missing plotting tool is a warning, not a failure:
// the CSV next to the plot holds the same numbers.
#pragma once

#include <string>

namespace igac {

// Runs scripts/<script> with the arguments; returns false (and prints a
// warning unless quiet) when the plot could not be drawn.
bool draw_plot(const std::string& script, const std::string& args, bool quiet);

}  // namespace igac
