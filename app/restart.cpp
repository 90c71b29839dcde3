// SPDX-License-Identifier: BSD-3-Clause
#include "app/restart.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <map>
#include <regex>
#include <sstream>

#include "app/output_folder.hpp"
#include "io/input_file.hpp"
#include "io/json_out.hpp"
#include "io/state_file.hpp"
#include "model/resumed_steps.hpp"

namespace igac {
namespace fs = std::filesystem;

std::string run_options(const CaseSpec& spec) {
  std::vector<int> degrees{spec.degree};
  for (const BodySpec& b : spec.bodies) degrees.push_back(b.degree);
  return fmt::format("refine={}\ndegree={}\nsolver={}\nsolver options={}\npreconditioner={}\nprocesses={}\n", spec.refine,
                     fmt::join(degrees, ","), name_of(spec.solver.type), spec.solver.options, name_of(spec.solver.preconditioner),
                     spec.solver.processes);
}

namespace {

int last_state_in(const fs::path& dir) {
  int last = 0;
  while (fs::exists(dir / state_file_name(last + 1))) ++last;
  return last;
}

std::map<std::string, std::string> option_lines(const std::string& text) {
  std::map<std::string, std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (const auto eq = line.find('='); eq != std::string::npos) out[line.substr(0, eq)] = line.substr(eq + 1);
  return out;
}

// The options that decide the discretisation (the unknowns a state file
// holds): a restart must keep them.  The solver, its options and the
// process count may change (a run continued on PETSc, on more processes):
// they change a result by round-off only (tests/cli/test_petsc_cases.cpp,
// PetscRestart).
bool is_discretisation(const std::string& key) { return key == "refine" || key == "degree"; }

// "refine 1 there, 0 here (--refine)", one per discretisation option that differs.
std::string options_that_differ(const std::string& earlier, const std::string& now) {
  static const std::map<std::string, std::string> flag{{"refine", "--refine"},           {"degree", "--degree"},
                                                       {"solver", "--solver"},           {"solver options", "--petsc-options"},
                                                       {"preconditioner", "--preconditioner"}, {"processes", "mpirun -n"}};
  const auto a = option_lines(earlier), b = option_lines(now);
  std::vector<std::string> out;
  for (const auto& [key, value] : b) {
    if (!is_discretisation(key)) continue;
    const auto it = a.find(key);
    const std::string was = it == a.end() ? "none" : it->second;
    if (was == value) continue;
    const auto f = flag.find(key);
    out.push_back(fmt::format("{} '{}' there, '{}' here ({})", key, was, value, f == flag.end() ? key : f->second));
  }
  return fmt::format("{}", fmt::join(out, "; "));
}

// An entry of the earlier run's .pvd is one of the files igac wrote there:
// a plain name in that folder (never "../x" nor "/x": those files are linked
// into the new output, and the name there is removed first), a regular file.
void check_pvd_entry(const fs::path& folder, const std::string& where, const std::string& file) {
  static const std::regex igac_name(R"re([A-Za-z0-9_.-]+_\d{4,}\.vtu)re");
  if (!std::regex_match(file, igac_name))
    throw InputError(fmt::format("{}: file={:?} is not the name of a ParaView file igac writes (NAME_NNNN.vtu in the "
                                 "run's own folder)", where, file));
  std::error_code ec;
  if (!fs::is_regular_file(fs::symlink_status(folder / file, ec)))
    throw InputError(fmt::format("{}: {} is not there, or not a regular file", where, (folder / file).string()));
}

// The steps 0..n of the earlier run's solution.pvd (none when it has none).
std::vector<VtkStep> read_pvd(const fs::path& folder, int n) {
  std::vector<VtkStep> steps;
  const fs::path path = folder / "solution.pvd";
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(path, ec))) return steps;
  std::istringstream pvd(read_input_file(path.string(), kPvdFile));
  // <DataSet timestep="T" part="K" name="NAME" file="FILE_NNNN.vtu"/>, the parts of a step one after the other
  static const std::regex line(R"re(<DataSet timestep="([^"]*)" part="(\d+)" name="([^"]*)" file="([^"]*)"/>)re");
  int number = 0;
  for (std::string text; std::getline(pvd, text);) {
    const std::string where = fmt::format("{}:{}", path.string(), ++number);
    std::smatch m;
    if (!std::regex_search(text, m, line)) {
      if (text.find("<DataSet") != std::string::npos)
        throw InputError(fmt::format("{}: not a <DataSet .../> line igac writes", where));
      continue;
    }
    const std::string t = m[1], file = m[4];
    check_pvd_entry(folder, where, file);
    double time = 0;
    const auto [end, err] = std::from_chars(t.data(), t.data() + t.size(), time);
    if (err != std::errc() || end != t.data() + t.size() || !std::isfinite(time))
      throw InputError(fmt::format("{}: timestep={:?} is not a number", where, t));
    const std::string digits = file.substr(file.rfind('_') + 1, file.size() - file.rfind('_') - 5);
    if (digits.size() > 9) throw InputError(fmt::format("{}: {} is beyond any step", where, file));
    const int step = std::stoi(digits);
    if (step > n) continue;
    if (m[2] == "0") steps.push_back({step, time, {}, {}});
    if (steps.empty()) continue;
    steps.back().files.push_back(file);
    steps.back().parts.push_back(m[3]);
  }
  return steps;
}

}  // namespace

EarlierRun read_earlier_run(const CaseSpec& spec, const std::string& options, const RestartOptions& o) {
  EarlierRun run{o.dir, false, {}, {}};
  // A run into the folder that was stopped before it ended (its staging
  // folder, kept for this): the later one, with the most steps.
  int last = 0;
  for (const std::string& s : stopped_runs_beside(o.dir))
    if (const int n = last_state_in(s); n > last) run = {s, true, {}, {}}, last = n;
  const fs::path dir(run.folder);
  if (!run.stopped) last = last_state_in(dir);
  const std::string& case_path = spec.path;
  const std::string hash = fnv1a64_of_file(case_path);
  if (last == 0) {
    if (!fs::exists(dir / "summary.json"))
      throw InputError(fmt::format("--restart {}: no summary.json there, nor a stopped run's state beside it (not the "
                                   "output folder of an igac run)", o.dir));
    throw InputError(fmt::format("--restart {}: no state file (state_0001.bin): the run wrote none (a case solved in "
                                 "one step, or a run with --no-output)", o.dir));
  }
  StateOrigin origin;
  read_state_file((dir / state_file_name(1)).string(), origin);
  if (origin.case_hash != hash)
    throw InputError(fmt::format("--restart {}: that run was of another case file (input hash {}, {} is {}): a restart "
                                 "continues the same case", o.dir, origin.case_hash, case_path, hash));
  if (!options_that_differ(origin.options, options).empty())
    throw InputError(fmt::format("--restart {}: that run had other options: {}; a restart continues a run with the "
                                 "options it had: give the same ones", o.dir, options_that_differ(origin.options, options)));
  const int n = o.from_step.value_or(last);
  if (n < 1 || n > last)
    throw InputError(fmt::format("--from-step {}: the run in {} wrote the states of steps 1 to {}", n, run.folder, last));
  for (int k = 1; k <= n; ++k) {
    StateOrigin written_with;
    run.steps.push_back(read_state_file((dir / state_file_name(k)).string(), written_with));
    if (written_with.case_hash != hash || !options_that_differ(written_with.options, options).empty() ||
        run.steps.back().step != k)
      throw InputError(fmt::format("--restart {}: {} is not step {} of this run", o.dir, state_file_name(k), k));
  }
  if (const auto off = off_schedule(spec, run.steps))
    throw InputError(fmt::format("{}: not a state of this case: {}", (dir / state_file_name(off->step)).string(),
                                 off->why));
  if (spec.write_vtk) run.vtk_steps = read_pvd(dir, n);
  return run;
}

namespace {
// A file of the earlier run into the new output: a hard link (nothing is
// copied, and the earlier folder may go), a copy where that fails.  Both
// names are plain names in their folders (read_pvd, state_file_name).
void adopt_file(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  fs::remove(to, ec);
  fs::create_hard_link(from, to, ec);
  if (ec) fs::copy_file(from, to, fs::copy_options::overwrite_existing);
}
}  // namespace

std::vector<VtkStep> adopt_earlier_steps(const EarlierRun& run, const std::string& staging, bool vtk) {
  const fs::path from(run.folder), to(staging);
  for (const StepState& s : run.steps) adopt_file(from / state_file_name(s.step), to / state_file_name(s.step));
  if (!vtk) return {};
  for (const VtkStep& step : run.vtk_steps)
    for (const std::string& f : step.files) adopt_file(from / f, to / f);
  return run.vtk_steps;
}

}  // namespace igac
