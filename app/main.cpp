// SPDX-License-Identifier: BSD-3-Clause
// igac — command line.
//   igac run CASE.toml [--out DIR] [--refine N] [--degree P] [--quiet] [--no-output]
//            [--solver direct|petsc] [--petsc-options "-ksp_type cg ..."]
//   mpirun -n N igac run CASE.toml --solver petsc   (scripts/mpirun.sh)
//   igac study CASE.toml --levels N [--degree P] [--out DIR] [--quiet] [--solver petsc ...] (one process)
//   igac geometry CASE.toml --out BODY.xml
// Exit codes: 0 converged, 1 the solve failed (summary.json says why),
// 2 bad input (one line on stderr naming file, key and reason), 3 an
// internal error ("igac: internal error: ...", a bug in igac).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <omp.h>

#include "engine/spline/knot_vector.hpp"
#include "model/case_body.hpp"
#include "io/case_file.hpp"
#include "model/model.hpp"
#include "model/progress.hpp"
#include "model/solve.hpp"
#include "contact/friction_state.hpp"
#include "app/launcher.hpp"
#include "engine/stopwatch.hpp"
#include "io/gismo_xml.hpp"
#include "io/json_out.hpp"
#include "app/output_folder.hpp"
#include "app/restart.hpp"
#include "io/state_file.hpp"
#include "io/plots.hpp"
#include "app/study.hpp"
#include "io/vtk_output.hpp"
#ifdef IGAC_WITH_PETSC
#include "solvers/petsc_contact.hpp"
#endif

using namespace igac;

namespace {

// Under mpirun every process runs this program; only the first one prints
// and writes files.
int process_rank() { return launcher_rank(); }
int process_count() { return launcher_size(); }

// [solver] from the case, then the command line's --solver and
// --petsc-options (added after the case's options: they win).
void apply_solver_options(CaseSpec& spec, const std::string& solver, const std::string& petsc_options,
                          const std::string& preconditioner) {
  if (!solver.empty()) spec.solver.type = solver_type_named(solver).value();  // (CLI11 checked the name)
  spec.solver.processes = process_count();  // the memory estimate's process count
  if (!preconditioner.empty()) {
    if (!set_preconditioner(spec.solver, preconditioner))
      throw InputError(fmt::format("--preconditioner {}: {}", preconditioner, unknown_preconditioner(preconditioner)));
  }
  if (const std::string why = check_preconditioner(spec.solver); !why.empty())
    throw InputError(fmt::format("--preconditioner {}: {}",
                                 spec.solver.automatic ? "auto" : name_of(spec.solver.preconditioner), why));
  if (!petsc_options.empty()) {
    if (!spec.solver.petsc()) throw InputError("--petsc-options: needs --solver petsc (or [solver] type = \"petsc\")");
    spec.solver.options += " " + petsc_options;
  }
  if (spec.solver.petsc())  // (a case file's [solver] type = "petsc" has passed the same check)
    if (const std::string why = check_petsc_case(spec); !why.empty())
      throw InputError(fmt::format("{}: --solver petsc: {}", spec.path, why));
  if (process_count() > 1 && !spec.solver.petsc())
    throw InputError(fmt::format("{}: {} processes (mpirun): the direct solver runs on one; use --solver petsc",
                                 spec.path, process_count()));
}

// `igac geometry --out PATH` writes a new file or replaces an earlier
// export (its second line says igac wrote it); anything else at PATH (a
// user's file, the case file itself, a folder, a symlink, a FIFO, a device)
// is refused rather than renamed over.
void check_geometry_destination(const std::string& out, const std::string& case_path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(out, ec);
  if (!fs::exists(st)) return;
  if (fs::is_symlink(st) || !fs::is_regular_file(st))
    throw InputError(fmt::format("--out {}: exists and is not a regular file (a folder, symlink, FIFO or device); "
                                 "give the name of a new file", out));
  if (fs::equivalent(out, case_path, ec))
    throw InputError(fmt::format("--out {}: is the case file itself; give the name of a new file", out));
  std::ifstream in(out, std::ios::binary);
  std::string head(256, '\0');
  in.read(head.data(), std::streamsize(head.size()));
  head.resize(std::size_t(in.gcount()));
  if (head.find("<!-- written by igac") == std::string::npos)
    throw InputError(fmt::format("--out {}: exists and was not written by igac geometry; igac replaces only its own "
                                 "exports: give the name of a new file", out));
}

std::string percent(double v, double ref) {
  return ref != 0 ? fmt::format("{:+.2f} %", 100 * (v - ref) / ref) : std::string("no relative difference to 0");
}

std::vector<std::string> body_names(const Model& m) {
  std::vector<std::string> out;
  for (const Model::Part& p : m.parts) out.push_back(p.name);
  return out;
}

// The first line of a run, printed before it solves (and flushed: the
// progress lines that follow go to stderr).
void print_header(const Model& m) {
  const Body& b = m.body;
  fmt::print("igac: {} — {}D{}, degree {}, {} elements{}, {} dofs, {} multipliers\n", m.spec.name, b.space_dim(),
             m.spec.plane_stress() ? " plane stress" : m.spec.axisymmetric() ? " axisymmetric" : "",
             b.degree(), b.num_elements(), m.parts.size() > 1 ? fmt::format(" in {} bodies ({})", m.parts.size(), fmt::join(body_names(m), ", "))
                                           : b.num_patches() > 1 ? fmt::format(" in {} patches", b.num_patches()) : "",
             m.dofs->num_free(), m.num_multipliers());
  const UnitsSpec& u = m.spec.units;
  if (u.declared())
    fmt::print("  units         length {}, force {}, stress {} (labels only: igac converts nothing)\n",
               u.length.empty() ? "-" : u.length, u.force.empty() ? "-" : u.force, u.stress.empty() ? "-" : u.stress);
  else
    fmt::print("  units         consistent units (none declared: [units] names them)\n");
  if (!m.spec.solver.choice.empty()) fmt::print("  solver        {}\n", m.spec.solver.choice);
  std::fflush(stdout);
}

void print_summary(const Model& m, const RunResult& r, const std::string& out, double wall_seconds) {
  const Body& b = m.body;
  std::string status = r.status;
  // Small deformation along load curves: steps of active-set iterations, no Newton.
  const bool stepped_linear = r.load_steps && !m.spec.finite_strain();
  if (stepped_linear) {
    size_t iterations = 0;
    for (const auto& st : r.load_steps->steps) iterations += st.active_set_sizes.size();
    status += r.contact ? fmt::format(" ({} load steps, {} active-set iterations)", r.load_steps->steps.size(), iterations)
                        : fmt::format(" ({} load steps)", r.load_steps->steps.size());
  } else if (r.load_steps) {
    int newton = 0, cuts = r.load_steps->unfinished_cut_backs;  // (a failed run's last attempts too)
    for (const auto& st : r.load_steps->steps) {
      newton += st.newton_iterations;
      cuts += st.cut_backs;
    }
    status += fmt::format(" ({} load steps, {} Newton iterations, {} cut-backs)", r.load_steps->steps.size(), newton, cuts);
  } else if (r.contact) {
    std::string sizes;
    for (int s : r.contact->solution.active_set_sizes) sizes += (sizes.empty() ? "" : " -> ") + std::to_string(s);
    status += fmt::format(" (active set sizes per iteration: {})", sizes);
  }
  if (!m.reoriented_patches.empty())
    fmt::print("  geometry      patch(es) {} reoriented: left-handed (in the file, or mirrored), run with u backwards "
               "(face names as the file or the shape gives them)\n", fmt::join(m.reoriented_patches, ", "));
  if (!m.joined_sides.empty()) {
    std::vector<std::string> pairs;
    for (const PatchInterface& itf : m.joined_sides) pairs.push_back(side_label(itf.first) + " = " + side_label(itf.second));
    fmt::print("  geometry      coincident sides joined: {} (the file does not join them)\n", fmt::join(pairs, ", "));
  }
  if (!m.interface_knots.empty()) {
    std::vector<std::string> where;
    for (const InsertedKnots& k : m.interface_knots)
      where.push_back(fmt::format("patch {} {} +{}", k.patch, "uvw"[k.direction], k.count));
    fmt::print("  geometry      knots inserted so that interfaces conform: {}\n", fmt::join(where, ", "));
  }
  fmt::print("  status        {}\n", status);
  const bool several = r.contacts.size() > 1;
  for (size_t i = 0; i < r.contacts.size(); ++i) {
    const ContactResult& c = r.contacts[i];
    const auto& rep = c.report;
    // One contact: its lines.  Several: a heading per contact and its lines indented.
    const std::string in = several ? "  " : "";
    if (several)
      fmt::print("  contact       face '{}' ({}): {} active multipliers\n", c.face, m.contacts[i].obstacle->describe(),
                 rep.active);
    if (!c.has_half_width)
      fmt::print("  {}contact area  {:.6g}{}\n", in, c.contact_area,
                 m.spec.axisymmetric() ? " (the area of the revolved contact zone)"
                 : b.space_dim() == 2  ? " (length per unit thickness)"
                                       : "");
    if (r.load_steps && !stepped_linear) {
      if (c.has_half_width)
        fmt::print("  {}half width    {:.6g} deformed, {:.6g} on the reference face\n", in, c.half_width_deformed,
                   rep.half_width);
      fmt::print("  {}max pressure  {:.6g} nominal, {:.6g} Cauchy\n", in, rep.max_pressure, c.max_pressure_cauchy);
    }
    if (r.hertz) {
      fmt::print("  half width    {:.6g}  (Hertz {:.6g}, {})\n", rep.half_width, r.hertz->a, percent(rep.half_width, r.hertz->a));
      fmt::print("  max pressure  {:.6g}  (Hertz {:.6g}, {})\n", rep.max_pressure, r.hertz->p0, percent(rep.max_pressure, r.hertz->p0));
    } else if (!r.load_steps || stepped_linear) {
      if (c.has_half_width) fmt::print("  {}half width    {:.6g}\n", in, rep.half_width);
      fmt::print("  {}max pressure  {:.6g}\n", in, rep.max_pressure);
    }
    if (several)
      fmt::print("    total force   {:.10g}\n", rep.total_force);
    else if (m.contacts[i].self_contact)  // the load does not pass through it to another body
      fmt::print("  total force   {:.10g}  (self-contact: the body presses on itself)\n", rep.total_force);
    else if (const std::optional<double> along_normal = c.resultant_along_normal();
             r.applied_force > 0 && along_normal &&
             std::abs(*along_normal - rep.total_force) > 1e-9 * std::abs(rep.total_force)) {
      // against a curved or deformed partner the pressure turns with its
      // normal: the resultant, not the integral of p, balances the load
      const double along = *along_normal;
      fmt::print("  total force   {:.10g}, resultant along the normal {:.10g}  (applied {:.10g}, relative "
                 "difference {:.2e})\n", rep.total_force, along, r.applied_force,
                 std::abs(std::abs(along) - r.applied_force) / r.applied_force);
    } else if (r.applied_force > 0)
      // (the applied force is a magnitude; a tie's contact force is negative where it pulls)
      fmt::print("  total force   {:.10g}  (applied {:.10g}, relative difference {:.2e}{})\n", rep.total_force,
                 r.applied_force, std::abs(std::abs(rep.total_force) - r.applied_force) / r.applied_force,
                 rep.total_force < 0 ? "; negative: the tie pulls" : "");
    else  // no pressure load nor prescribed displacement: a moving obstacle, or nothing
      fmt::print("  total force   {:.10g}  ({})\n", rep.total_force,
                 m.contacts[i].motion.size() > 0 && m.contacts[i].motion.norm() > 0
                     ? "driven by the obstacle's motion; the supports' reactions below"
                     : "no load applied");
    if (i < r.reactions.size() && r.reactions[i].tangential_force.size() && m.contacts[i].friction > 0) {
      const std::vector<char>& st = r.contact->solution.friction_state;
      const auto first = st.begin() + c.first_multiplier, last = first + c.num_multipliers;
      fmt::print("  {}friction      tangential force {:.10g} (f N = {:.10g}); {} multipliers stick, {} slip\n", in,
                 r.reactions[i].tangential_force.norm(), m.contacts[i].friction * r.reactions[i].normal_force,
                 std::count(first, last, char(kStick)), std::count(first, last, char(kSlip)));
    }
    if (i < r.reactions.size() && r.reactions[i].extrusion)
      fmt::print("  {}extrusion     {:.6g}{} past the edge, over its second face\n", in, *r.reactions[i].extrusion,
                 m.spec.units.length.empty() ? "" : " " + m.spec.units.length);
  }
  if (several && r.applied_force > 0) fmt::print("  applied force {:.10g}\n", r.applied_force);
  for (const FluidReport& f : r.fluids) {
    fmt::print("  fluid         pressure {:.6g} on '{}': wets {} of {} face elements, force ({:.6g})\n", f.pressure,
               fmt::join(f.faces, "', '"), f.wet_elements, f.elements, fmt::join(f.force, ", "));
    if (f.pressure > 0 && f.peak_contact_pressure > 0)
      fmt::print("  seal          peak contact pressure {:.6g} = {:.3g} x the fluid's: {}\n", f.peak_contact_pressure,
                 f.peak_contact_pressure / f.pressure,
                 f.peak_contact_pressure > f.pressure ? "the contact holds it" : "below it, the seal leaks");
  }
  for (const FaceReaction& f : r.dirichlet_reactions)
    fmt::print("  reaction      face '{}': ({:.6g})\n", f.face, fmt::join(f.force, ", "));
  if (r.pressure_error && r.pressure_error->second > 0)
    fmt::print("  pressure L2   {:.4e}  (relative {:.4e}, against Hertz)\n", r.pressure_error->first,
               r.pressure_error->first / r.pressure_error->second);
  else if (r.pressure_error)
    fmt::print("  pressure L2   {:.4e}  (against Hertz, whose pressure is zero)\n", r.pressure_error->first);
  if (r.displacement_errors)
    fmt::print("  displacement  L2 error {:.4e}, H1 error {:.4e} (relative {:.3e}, {:.3e})\n", r.displacement_errors->l2,
               r.displacement_errors->h1, r.displacement_errors->l2 / r.displacement_errors->ref_l2,
               r.displacement_errors->h1 / r.displacement_errors->ref_h1);
  // The whole run (reading, building, solving, writing), then the solve's own split.
  if (r.load_steps && !stepped_linear)
    fmt::print("  time          {:.3f} s in all; the solve {:.3f} (Newton and load steps {:.3f})\n", wall_seconds,
               r.timing.total, r.load_steps->newton_seconds);
  else
    fmt::print("  time          {:.3f} s in all; the solve {:.3f} (assembly {:.3f}, factorisation {:.3f}, solve {:.3f}, "
               "contact {:.3f})\n", wall_seconds, r.timing.total, r.timing.assembly, r.timing.factorization,
               r.timing.linear_solve, r.timing.contact);
  if (!out.empty()) fmt::print("  output        {}/summary.json\n", out);
}

// A run that asks for PETSc (--solver petsc, or [solver] type = "petsc"):
// igac hands it to igac-petsc beside it (app/launcher.hpp); where there is
// none (./run.sh builds igac only, and PETSc may not be installed) one line
// says how to get it, before anything runs.  igac-petsc itself goes on.
void petsc_or_refuse([[maybe_unused]] const CaseSpec& spec, [[maybe_unused]] const std::string& solver,
                     [[maybe_unused]] char** argv) {
#ifndef IGAC_WITH_PETSC
  if ((solver.empty() ? spec.solver.type : solver_type_named(solver).value_or(SolverType::direct)) != SolverType::petsc)
    return;
  hand_over_to_petsc_build(argv);
  throw InputError(fmt::format("{}: {}: this igac has no PETSc solver (no igac-petsc beside it): "
                               "`scripts/bootstrap.sh petsc` installs PETSc and Open MPI (Debian's libpetsc-real-dev "
                               "and openmpi-bin) and builds it",
                               spec.path, solver.empty() ? "[solver] type = \"petsc\"" : "--solver petsc"));
#endif
}

int run_command(const std::string& path, std::string out, std::optional<int> refine, std::optional<int> degree,
                bool quiet, bool no_output, const std::string& solver, const std::string& petsc_options,
                const std::string& preconditioner, const RestartOptions& restart, char** argv) {
  const Stopwatch wall;  // the "time ... in all" of the console
  CaseSpec spec = read_case(path);
  petsc_or_refuse(spec, solver, argv);
  apply_solver_options(spec, solver, petsc_options, preconditioner);
  apply_overrides(spec, degree, refine);
  if (process_rank() > 0) {  // the first process writes and prints
    no_output = true;
    quiet = true;
  }
#ifdef IGAC_WITH_PETSC
  std::optional<PetscSession> petsc;
  if (spec.solver.petsc()) petsc.emplace(spec.solver.options);
#endif
  if (no_output) out.clear();
  else if (out.empty()) out = "out/" + spec.name;
  // Checked (and staged) before anything is computed; the files appear in
  // `out` together, when the run ends.
  std::optional<OutputFolder> folder;
  if (!out.empty()) folder.emplace(out);
  // A long set-up (a large mesh refined, its dof maps, step 0 of the
  // ParaView files) is not silent: lines held, and released after 4 s
  // without one (model/progress.hpp); a short one prints nothing.
  std::optional<Progress> setup;
  if (!quiet) {
    setup.emplace(false);
    setup->hold_until_late();
    setup->phase("building the model");
  }
  Model model = build_model(spec);
  RunControl control;
  control.quiet = quiet;
  // A run in steps writes its state after each one (state_NNNN.bin, beside
  // the step's .vtu); --restart continues from there (app/restart.hpp).
  const bool stepped = spec.finite_strain() || spec.has_load_curves();
  if ((!restart.dir.empty() || restart.stop_after_step > 0) && !stepped)
    throw InputError(fmt::format("{}: --restart and --stop-after-step need a run in steps (large deformation or load "
                                 "curves); this case is solved in one step", path));
  // The state files say which case file and options wrote them: a restart
  // continues the same (app/restart.hpp).
  const StateOrigin origin{fnv1a64_of_file(path), run_options(spec)};
  EarlierRun earlier;
  if (!restart.dir.empty()) {
    earlier = read_earlier_run(model.spec, origin.options, restart);
    control.resume = earlier.steps;
  }
  control.stop_after_step = restart.stop_after_step;
  bool header = false;  // printed once the solve accepts the case (bad input stays one line)
  if (!quiet) control.on_solve_start = [&] { print_header(model), header = true; };
  if (!quiet)
    for (const auto& w : model.warnings) fmt::print(stderr, "igac: warning: {}\n", w);
  if (folder) folder->create_staging(earlier.stopped ? earlier.folder : std::string());
  const std::string dir = folder ? folder->staging() : std::string();
  const bool vtk = folder && spec.write_vtk;
  VtkSeries series(dir);
  if (!quiet && earlier.stopped)
    fmt::print(stderr, "igac: continuing after step {} of the run stopped in {}\n", control.resume.size(), earlier.folder);
  // Step 0: the undeformed body, at load factor 0, and its contact faces
  // (no pressure, the initial gaps). A run solved once whose contacts do
  // not change with the load writes it after the solve, from the solve's
  // own contact operator: assembling it again repeated a two-body case's
  // whole segmented set-up (docs/benchmarks.md, "Two unequal spheres").
  const bool step_zero_after_the_solve =
      !stepped && std::none_of(model.contacts.begin(), model.contacts.end(), changes_with_the_load);
  auto write_step_zero = [&](const WeightedGapOperator* reference) {
    // (quiet unless it runs long: a large mesh's step 0 took half a minute without a word)
    if (setup) setup->phase("writing step 0 of the ParaView files (the undeformed body)");
    RunResult undeformed;
    undeformed.u = Eigen::MatrixXd::Zero(model.body.num_control_points(), model.body.space_dim());
    if (!model.contacts.empty()) {  // and its contact faces: no pressure, the initial gaps
      // (the large-deformation obstacles stand at their reference position: factor 1 keeps them there)
      ContactSolve& c = undeformed.contact.emplace();
      c.op = reference ? *reference : assemble_contact_operator(model, model.spec.finite_strain() ? 1.0 : 0.0);
      c.solution.lambda = Eigen::VectorXd::Zero(c.op.weights.size());
      c.solution.weighted_gap = c.op.g0.cwiseQuotient(c.op.weights);
      c.solution.active.assign(size_t(c.op.weights.size()), 0);
      int first = 0;
      for (const Model::Contact& mc : model.contacts) {
        ContactResult& cr = undeformed.contacts.emplace_back();
        cr.face = mc.face_name;
        cr.first_multiplier = first;
        cr.num_multipliers = mc.face->num_multipliers();
        first += cr.num_multipliers;
      }
    }
    series.write_step(model, undeformed, 0.0);
  };
  if (folder && !control.resume.empty()) {  // the earlier run's steps 0..N, as it wrote them
    series.resume(adopt_earlier_steps(earlier, dir, vtk));
    if (vtk) write_pvd(dir, series.steps());
    // Our staging folder now holds the steps: it is the stopped run if this one stops too.
    folder->keep_on_termination();
    if (earlier.stopped) std::filesystem::remove_all(earlier.folder);
  } else if (vtk && !step_zero_after_the_solve) {
    write_step_zero(nullptr);
  }
  // Large deformation and load curves: one ParaView step per converged load
  // step, at its time, and the state to restart from.
  if (folder && stepped)
    control.on_step = [&](const RunResult& step, double t) {
      if (vtk && step.u.allFinite()) series.write_step(model, step, t);
      if (step.step_state) {
        write_state_file(dir + "/" + state_file_name(step.step_state->step), origin, *step.step_state);
        folder->keep_on_termination();  // killed or stopped from here on, the run can be continued
      }
    };
  setup.reset();  // the solve's own lines from here
  RunResult r = solve_model(model, control);
  if (!quiet)
    for (const auto& w : r.warnings) fmt::print(stderr, "igac: warning: {}\n", w);
  Json summary = run_summary(model, r);
  // Every number of the summary went through finite_or_null: a null value
  // (not the text "null", which a case name may contain) is a non-finite result.
  const bool finite = !has_null_value(summary) && r.u.allFinite();
  if (!finite && r.status.is_converged()) {
    r.status = RunStatus::failed("failed: a result is not finite");
    summary["status"] = r.status.text();
  }
  if (folder) {
    Progress progress(quiet, wall.seconds());
    if (vtk) progress.phase("writing the output (the ParaView files recover the stress)");
    // One contact: pressure.csv and .svg; several: pressure_<face>.csv and .svg each.
    const std::vector<std::string> stems = pressure_file_stems(model);
    for (size_t i = 0; i < r.contacts.size(); ++i) {
      const std::string title = r.contacts.size() > 1 ? fmt::format("{}: face '{}'", spec.name, r.contacts[i].face) : spec.name;
      write_file_atomically(dir + "/" + stems[i] + ".csv", pressure_csv(r, i));
      write_file_atomically(dir + "/" + stems[i] + ".svg", svg::render(pressure_figure(r, title, i, spec.units)));
    }
    if (!r.load_curve.empty()) {
      write_file_atomically(dir + "/load_curve.csv", load_curve_csv(model, r));
      std::vector<std::string> faces;
      if (r.contacts.size() > 1)
        for (const ContactResult& c : r.contacts) faces.push_back(c.face);
      write_file_atomically(dir + "/load_curve.svg", svg::render(load_curve_figure(r, spec.name, faces, spec.units, spec.axisymmetric() ? 3 : model.body.space_dim(),
                                                                        spec.has_load_curves())));
    }
    // ParaView files (and the stress recovery they need) only when asked for.
    if (vtk && step_zero_after_the_solve) {
      const bool same_faces = r.contact && r.contact->op.weights.size() == model.num_multipliers();
      write_step_zero(same_faces ? &r.contact->op : nullptr);
    }
    if (vtk && !stepped && finite) series.write_step(model, r, 1.0);
    write_file_atomically(dir + "/summary.json", summary.dump(2) + "\n");
    if (const std::string note = folder->commit(); !note.empty()) fmt::print(stderr, "igac: warning: {}\n", note);
  }
  if (!quiet && !header) print_header(model);
  if (!quiet) print_summary(model, r, folder ? folder->target() : std::string(), wall.seconds());
  // (a run stopped where --stop-after-step asked has done what it was asked)
  return r.status.exit_code();
}

}  // namespace

int main(int argc, char** argv) {
  block_termination_signals_in_every_thread(argv);  // app/launcher.hpp
  // A file-size limit (ulimit -f) makes a write fail with EFBIG, which the
  // writers report in one line, instead of killing the run with SIGXFSZ.
  signal(SIGXFSZ, SIG_IGN);
  end_on_termination_signals();
  // Threads adapt to the cores that are free, region by region
  // (engine/free_cores.hpp), not by libgomp's dynamic mode, which reads the
  // 15-minute load average.  CHOLMOD's own OpenMP loops run on one thread
  // (engine/cholesky.cpp).
  omp_set_dynamic(0);
  CLI::App app{"igac: isogeometric contact mechanics (NURBS bodies pressed on rigid obstacles)"};
  app.set_version_flag("--version", std::string("igac ") + IGAC_VERSION);
  app.require_subcommand(1);
  std::string case_path, out;
  std::optional<int> refine, degree;
  bool quiet = false, no_output = false;
  int levels = 4;
  std::string solver, petsc_options, preconditioner;

  auto* run = app.add_subcommand("run", "run one case");
  run->add_option("case", case_path, "case file (TOML)")->required();
  run->add_option("--out", out, "output folder (default out/<case name>)");
  run->add_option("--refine", refine, "extra uniform refinements (each halves every span)");
  run->add_option("--degree", degree, "NURBS degree p (contact needs p >= 2)");
  run->add_flag("--quiet", quiet, "print nothing but errors");
  run->add_flag("--no-output", no_output, "write no files (and compute nothing only output needs)");
  run->add_option("--solver", solver, "linear solver: direct (CHOLMOD, one process) or petsc (also under mpirun)")
      ->check(CLI::IsMember({"direct", "petsc"}));
  run->add_option("--petsc-options", petsc_options, "PETSc options, e.g. \"-ksp_type fgmres -pc_type fieldsplit\"");
  run->add_option("--preconditioner", preconditioner,
                  "PETSc: options (as the PETSc options say; default MUMPS), spline_multigrid, algebraic_multigrid or "
                  "auto (the faster of MUMPS and spline_multigrid for the mesh)");
  RestartOptions restart;
  run->add_option("--restart", restart.dir,
                  "continue the run whose output is in this folder (same case file) after its last step");
  // (CLI::PositiveNumber's message printed the range up to DBL_MAX, 309 digits)
  const CLI::Validator step_number(
      [](std::string& s) {
        int v = 0;
        const auto [end, err] = std::from_chars(s.data(), s.data() + s.size(), v);
        return err == std::errc() && end == s.data() + s.size() && v >= 1
                   ? std::string()
                   : fmt::format("{:?} is not a step number (1, 2, ...)", s);
      },
      "STEP");
  run->add_option("--from-step", restart.from_step, "with --restart: continue after this step instead of the last")
      ->needs("--restart")
      ->check(step_number);
  run->add_option("--stop-after-step", restart.stop_after_step, "stop once this many load steps are done")
      ->check(step_number);

  auto* study = app.add_subcommand("study", "refinement study on nested meshes");
  study->add_option("case", case_path, "case file (TOML)")->required();
  study->add_option("--levels", levels, "number of refinement levels")->required();
  study->add_option("--degree", degree, "NURBS degree p");
  study->add_option("--out", out, "output folder for study.json, study.csv, study.svg (default out/<case name>_study)");
  study->add_flag("--quiet", quiet, "print only the table");
  study->add_option("--solver", solver, "linear solver: direct (CHOLMOD) or petsc (one process)")
      ->check(CLI::IsMember({"direct", "petsc"}));
  study->add_option("--petsc-options", petsc_options, "PETSc options");
  study->add_option("--preconditioner", preconditioner, "PETSc: options, spline_multigrid, algebraic_multigrid or auto");

  auto* geometry = app.add_subcommand("geometry", "write the case's body (before refinement) as a G+Smo XML file");
  geometry->add_option("case", case_path, "case file (TOML)")->required();
  geometry->add_option("--out", out, "the XML file to write")->required();

  // Errors: one line, from the first process only (input errors are the
  // same on every process); a failure may strike one process alone, so every
  // process reports it, naming itself.
  const auto say = [](const std::string& line) {
    if (process_rank() == 0) fmt::print(stderr, "{}\n", line);
  };
  // Input errors are met by every process alike: the first reports it and
  // exits 2; the others end quietly with 0, or mpirun, seeing a process end
  // with 2 first, may stop the first one before it has said why.
  const auto input_error_status = [] { return process_rank() == 0 ? 2 : 0; };
  const auto say_any = [](const std::string& line) {
    if (process_rank() == 0) fmt::print(stderr, "{}\n", line);
    else fmt::print(stderr, "{} (process {})\n", line, process_rank());
  };
  // A first word that is no command (and no option such as --help): CLI11
  // would say only "A subcommand is required".
  bool command = argc < 2 || argv[1][0] == '-';
  for (const CLI::App* c : {run, study, geometry}) command = command || c->check_name(argv[1]);
  if (!command) {  // a slip ("igac rn case.toml") gets the command meant
    const auto near = nearest_name(argv[1], {"run", "study", "geometry"});
    say(fmt::format("igac: error: unknown command '{}'{} (run, study or geometry; see igac --help)", argv[1],
                    near ? fmt::format("; did you mean '{}'?", *near) : ""));
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help
    // The help of the command that was given, when there is one.
    std::string help = "igac --help";
    for (const CLI::App* sub : app.get_subcommands())
      if (sub->parsed()) help = "igac " + sub->get_name() + " --help";
    say(fmt::format("igac: error: {} (see {})", e.what(), help));
    return 2;
  }
  // An empty --out (an unset shell variable) is no folder: refused, rather
  // than read as "no --out given" and written to out/<name>.
  for (auto* sub : {run, study, geometry})
    if (sub->parsed() && sub->get_option("--out")->count() > 0 && out.empty()) {
      say("igac: error: --out: an empty folder name (give a folder, or leave --out out for out/<name>)");
      return 2;
    }
  // The same for --restart: an empty one started the run afresh, silently.
  if (run->parsed() && run->get_option("--restart")->count() > 0 && restart.dir.empty()) {
    say("igac: error: --restart: an empty folder name (give the output folder of the run to continue)");
    return 2;
  }
  try {
    if (run->parsed()) return run_command(case_path, out, refine, degree, quiet, no_output, solver, petsc_options,
                                          preconditioner, restart, argv);
    if (geometry->parsed()) {
      check_geometry_destination(out, case_path);
      const MultiPatch body = case_body(read_case(case_path));
      write_gismo_xml(body, out);
      fmt::print("igac: wrote {}: {} patch(es), {} interface(s), before refinement\n", out, body.patches.size(),
                 body.interfaces.size());
      return 0;
    }
    CaseSpec spec = read_case(case_path);
    petsc_or_refuse(spec, solver, argv);
    apply_solver_options(spec, solver, petsc_options, preconditioner);
    apply_overrides(spec, degree, {});
    // A study writes and prints as one program: PETSc on one process (its
    // levels beyond the direct solver's memory, e.g. the 3D study's 1.8M
    // reference with the spline multigrid).
    if (spec.solver.petsc() && launcher_size() > 1)
      throw InputError(fmt::format("{}: igac study runs on one process (the PETSc solver too); use igac run under "
                                   "mpirun for one level", case_path));
#ifdef IGAC_WITH_PETSC
    std::optional<PetscSession> petsc;
    if (spec.solver.petsc()) petsc.emplace(spec.solver.options);
#endif
    // Without --out a study writes beside the runs, out/<name>_study (not
    // out/<name>: that would replace the case's own run output).
    return run_study(spec, StudyOptions{levels, out.empty() ? "out/" + spec.name + "_study" : out, quiet});
  } catch (const InputError& e) {
    say(fmt::format("igac: error: {}", e.what()));
    return input_error_status();
  } catch (const SplineError& e) {
    say(fmt::format("igac: error: {}: {}", case_path, e.what()));
    return input_error_status();
  } catch (const MaterialError& e) {
    say(fmt::format("igac: error: {}: [material] {}", case_path, e.what()));
    return input_error_status();
  } catch (const std::bad_alloc&) {
    say_any(fmt::format("igac: error: {}: out of memory (reduce refine or degree)", case_path));
    return 1;
  } catch (const std::logic_error& e) {  // a bug in igac, not the case or the solve: exit 3
    say_any(fmt::format("igac: internal error: {}", e.what()));
    return 3;
  } catch (const std::exception& e) {
    say_any(fmt::format("igac: error: {}: {}", case_path, e.what()));
    return 1;
  }
}
