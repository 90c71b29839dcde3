// SPDX-License-Identifier: BSD-3-Clause
#include "app/restart.hpp"

#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>

#include "io/json_out.hpp"
#include "io/state_file.hpp"

namespace igac {
namespace fs = std::filesystem;

std::vector<StepState> read_earlier_steps(const std::string& case_path, const RestartOptions& o) {
  const fs::path dir(o.dir);
  const fs::path summary_path = dir / "summary.json";
  std::ifstream in(summary_path);
  if (!in) throw InputError(fmt::format("--restart {}: no summary.json there (not the output folder of an igac run)", o.dir));
  nlohmann::json summary;
  try {
    summary = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception&) {
    throw InputError(fmt::format("--restart {}: its summary.json is not JSON", o.dir));
  }
  const std::string hash = fnv1a64_of_file(case_path);
  const auto input = summary.find("input");
  const std::string earlier = input != summary.end() && input->contains("fnv1a64") ? (*input)["fnv1a64"].get<std::string>() : "";
  if (earlier != hash)
    throw InputError(fmt::format("--restart {}: that run was of another case file (input hash {}, {} is {}): a restart "
                                 "continues the same case", o.dir, earlier.empty() ? "none" : earlier, case_path, hash));
  int last = 0;  // the last step whose state file is there
  while (fs::exists(dir / state_file_name(last + 1))) ++last;
  if (last == 0)
    throw InputError(fmt::format("--restart {}: no state file (state_0001.bin): the run wrote none (a case solved in "
                                 "one step, or a run with --no-output)", o.dir));
  const int n = o.from_step.value_or(last);
  if (n < 1 || n > last)
    throw InputError(fmt::format("--from-step {}: the run in {} wrote the states of steps 1 to {}", n, o.dir, last));
  std::vector<StepState> steps;
  for (int k = 1; k <= n; ++k) {
    std::string written_with;
    steps.push_back(read_state_file((dir / state_file_name(k)).string(), written_with));
    if (written_with != hash || steps.back().step != k)
      throw InputError(fmt::format("--restart {}: {} is not step {} of this case", o.dir, state_file_name(k), k));
  }
  return steps;
}

std::vector<VtkStep> adopt_earlier_steps(const std::string& dir, const std::string& staging, int n, bool vtk) {
  for (int k = 1; k <= n; ++k)
    fs::copy_file(fs::path(dir) / state_file_name(k), fs::path(staging) / state_file_name(k),
                  fs::copy_options::overwrite_existing);
  std::vector<VtkStep> steps;
  std::ifstream pvd(fs::path(dir) / "solution.pvd");
  if (!vtk || !pvd) return steps;
  // <DataSet timestep="T" part="K" name="NAME" file="FILE_NNNN.vtu"/>, the parts of a step one after the other
  static const std::regex line(R"re(<DataSet timestep="([^"]+)" part="(\d+)" name="([^"]+)" file="([^"]+_(\d{4})\.vtu)"/>)re");
  for (std::string text; std::getline(pvd, text);) {
    std::smatch m;
    if (!std::regex_search(text, m, line)) continue;
    const int step = std::stoi(m[5]);
    if (step > n) continue;
    if (m[2] == "0") steps.push_back({step, std::stod(m[1]), {}, {}});
    if (steps.empty()) continue;
    steps.back().files.push_back(m[4]);
    steps.back().parts.push_back(m[3]);
    fs::copy_file(fs::path(dir) / std::string(m[4]), fs::path(staging) / std::string(m[4]),
                  fs::copy_options::overwrite_existing);
  }
  return steps;
}

}  // namespace igac
