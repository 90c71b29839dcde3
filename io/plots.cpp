#include "io/plots.hpp"

#include <cstdlib>
#include <filesystem>
#include <fmt/format.h>

namespace igac {

bool draw_plot(const std::string& script, const std::string& args, bool quiet) {
  const std::string path = std::string(IGAC_SOURCE_DIR) + "/scripts/" + script;
  // Debian's interpreter, where python3-matplotlib is installed.
  const char* python = std::filesystem::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  const std::string cmd = fmt::format("{} '{}' {} > /dev/null 2>&1", python, path, args);
  const int rc = std::system(cmd.c_str());
  if (rc != 0 && !quiet) fmt::print(stderr, "igac: warning: could not draw a plot ({} failed)\n", script);
  return rc == 0;
}

}  // namespace igac
