// SPDX-License-Identifier: BSD-3-Clause
#include "io/json_out.hpp"
#include "model/memory_estimate.hpp"
#include "io/input_file.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <cstdint>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <stdexcept>
#include <sys/resource.h>
#include <unistd.h>

namespace igac {

std::string why_not_written(const std::string& path, int err) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path folder = fs::path(path).has_parent_path() ? fs::path(path).parent_path() : fs::path(".");
  if (!fs::exists(folder, ec)) return fmt::format("the folder {} does not exist", folder.string());
  if (!fs::is_directory(folder, ec)) return fmt::format("{} is not a folder", folder.string());
  if (access(folder.c_str(), W_OK | X_OK) != 0) return fmt::format("the folder {} is not writable", folder.string());
  return err != 0 ? std::string(std::strerror(err)) : std::string("disk full?");
}

void write_file_atomically(const std::string& path, const std::string& text) {
  const std::string tmp = fmt::format("{}.tmp{}", path, getpid());
  bool ok = false;
  errno = 0;
  {
    std::ofstream out(tmp, std::ios::binary);
    if (out) {
      out << text;
      out.close();  // the last buffer reaches the disk here: a full disk fails now
      ok = !out.fail();
    }
  }
  int err = ok ? 0 : errno;
  std::error_code ec;
  if (ok && std::filesystem::file_size(tmp, ec) == text.size() && !ec) {
    std::filesystem::rename(tmp, path, ec);
    if (!ec) return;
    err = ec.value();
  }
  std::filesystem::remove(tmp, ec);  // never a short file in place of a good one
  throw std::runtime_error(fmt::format("cannot write {}: {}", path, why_not_written(path, err)));
}

Json finite_or_null(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

bool has_null_value(const Json& j) {
  if (j.is_null()) return true;
  if (j.is_structured())
    for (const auto& v : j)
      if (has_null_value(v)) return true;
  return false;
}

std::vector<std::string> contact_file_tags(const Model& m) {
  if (m.contacts.size() == 1) return {""};
  std::vector<std::string> out;
  for (size_t i = 0; i < m.contacts.size(); ++i) {
    std::string tag = m.contacts[i].face_name;
    for (char& ch : tag)
      if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '-' && ch != '_' && ch != '.') ch = '_';
    if (std::find(out.begin(), out.end(), tag) != out.end()) tag += fmt::format("_{}", i + 1);  // the same face twice
    out.push_back(tag);
  }
  return out;
}

std::vector<std::string> pressure_file_stems(const Model& m) {
  std::vector<std::string> out;
  for (const std::string& tag : contact_file_tags(m)) out.push_back(tag.empty() ? "pressure" : "pressure_" + tag);
  return out;
}

namespace {
// One contact's numbers in summary.json: its pressed multipliers, extent,
// peak and force.  The extent is the half width where the zone grows from
// a point, the pressed area where the face starts flat on the obstacle.
Json contact_numbers(const RunResult& r, const ContactResult& cr) {
  const PressureReport& rep = cr.report;
  Json c;
  c["active"] = rep.active;
  if (!cr.has_half_width) c["contact_area"] = finite_or_null(cr.contact_area);
  if (r.load_steps) {  // large deformation: deformed extent, nominal and Cauchy pressure
    if (cr.has_half_width) {
      c["half_width"] = finite_or_null(cr.half_width_deformed);
      c["half_width_reference"] = finite_or_null(rep.half_width);
    }
    c["max_pressure"] = finite_or_null(rep.max_pressure);
    c["max_pressure_cauchy"] = finite_or_null(cr.max_pressure_cauchy);
  } else {
    if (cr.has_half_width) c["half_width"] = finite_or_null(rep.half_width);
    c["max_pressure"] = finite_or_null(rep.max_pressure);
  }
  c["total_force"] = finite_or_null(rep.total_force);
  if (cr.resultant.size() > 0) {
    Json f = Json::array();
    for (int i = 0; i < cr.resultant.size(); ++i) f.push_back(finite_or_null(cr.resultant[i]));
    c["resultant"] = f;
    if (const std::optional<double> along = cr.resultant_along_normal())
      c["resultant_along_normal"] = finite_or_null(*along);
  }
  return c;
}
// Every [[dirichlet]] face set's reaction: [{"face": NAME, "force": [x, y(, z)]}].
Json reactions_json(const std::vector<FaceReaction>& reactions) {
  Json out = Json::array();
  for (const FaceReaction& r : reactions) {
    Json f = Json::array();
    for (int i = 0; i < r.force.size(); ++i) f.push_back(finite_or_null(r.force[i]));
    out.push_back({{"face", r.face}, {"force", f}});
  }
  return out;
}
}  // namespace

std::string fnv1a64_of_file(const std::string& path) {
  try {
    return fmt::format("{:016x}", fnv1a64(read_input_file(path, kCaseFile)));
  } catch (const InputError&) {
    return "";
  }
}

Json run_summary(const Model& m, const RunResult& r) {
  const Body& body = m.body;
  Json j;
  j["case"] = m.spec.name;
  j["igac_version"] = IGAC_VERSION;
  if (const std::string hash = fnv1a64_of_file(m.spec.path); !hash.empty())
    j["input"] = {{"path", std::filesystem::absolute(m.spec.path).lexically_normal().string()}, {"fnv1a64", hash}};
  {  // [units]: labels only
    const UnitsSpec& u = m.spec.units;
    Json units = {{"system", u.declared() ? (u.system.empty() ? "declared" : u.system) : "consistent units"}};
    if (!u.length.empty()) units["length"] = u.length;
    if (!u.force.empty()) units["force"] = u.force;
    if (!u.stress.empty()) units["stress"] = u.stress;
    j["units"] = units;
  }
  j["dim"] = body.space_dim();
  if (body.space_dim() == 2) j["kind"] = std::string(name_of(m.spec.kind));  // [model] kind
  j["degree"] = body.degree();
  j["elements"] = body.num_elements();
  j["patches"] = body.num_patches();
  j["dofs"] = m.dofs->num_free();
  j["multipliers"] = m.num_multipliers();
  j["mesh_size"] = m.mesh_size;
  if (m.parts.size() > 1) {  // [[body]] tables: each body's patches, elements and material
    Json bodies = Json::array();
    const std::vector<BodySpec> specs = m.spec.body_list();
    for (size_t i = 0; i < m.parts.size(); ++i) {
      const Model::Part& part = m.parts[i];
      long elements = 0;  // the knot spans of its patches
      for (int k = part.first_patch; k < part.first_patch + part.num_patches; ++k) {
        long spans = 1;
        for (int d = 0; d < body.param_dim(); ++d) spans *= long(body.patch(k).knots(d).breakpoints().size()) - 1;
        elements += spans;
      }
      bodies.push_back({{"name", part.name},
                        {"patches", part.num_patches},
                        {"elements", elements},
                        {"model", specs[i].model},
                        {"E", specs[i].E},
                        {"nu", specs[i].nu}});
    }
    j["bodies"] = bodies;
  }
  if (!m.reoriented_patches.empty()) j["reoriented_patches"] = m.reoriented_patches;
  if (!m.joined_sides.empty()) {
    Json joined = Json::array();
    for (const PatchInterface& itf : m.joined_sides) joined.push_back({side_label(itf.first), side_label(itf.second)});
    j["joined_sides"] = joined;
  }
  if (!m.interface_knots.empty()) {
    Json knots = Json::array();
    for (const InsertedKnots& k : m.interface_knots)
      knots.push_back({{"patch", k.patch}, {"direction", std::string(1, "uvw"[k.direction])}, {"knots", k.count}});
    j["interface_knots_inserted"] = knots;
  }
  j["status"] = r.status.text();
  if (!m.warnings.empty() || !r.warnings.empty()) {  // what build_model and the solve found doubtful
    j["warnings"] = m.warnings;
    for (const auto& w : r.warnings) j["warnings"].push_back(w);
  }
  if (r.load_steps) {
    Json steps = Json::array();
    const bool per_step = r.load_curve.size() == r.load_steps->steps.size();  // one point per converged step
    for (const auto& st : r.load_steps->steps) {
      Json step;
      step["load_factor"] = finite_or_null(st.load_factor);
      if (m.spec.has_load_curves()) step["time"] = finite_or_null(st.load_factor);  // (the load factor is the time)
      step["newton_iterations"] = st.newton_iterations;
      Json norms = Json::array();
      for (double v : st.residual_norms) norms.push_back(finite_or_null(v));
      step["residual_norms"] = norms;
      step["active_set_sizes"] = st.active_set_sizes;
      step["cut_backs"] = st.cut_backs;
      if (st.augmentations > 0) step["augmentations"] = st.augmentations;  // the incompressible limit's rounds
      if (per_step && !m.spec.dirichlet.empty())
        step["dirichlet_reactions"] = reactions_json(r.load_curve[steps.size()].dirichlet_reactions);
      steps.push_back(step);
    }
    j["load_steps"] = steps;
    // A failed run: the attempts it cut back after its last converged step.
    if (r.load_steps->unfinished_cut_backs > 0) j["cut_backs_before_stopping"] = r.load_steps->unfinished_cut_backs;
  } else {
    Json step;
    step["load_factor"] = 1.0;
    step["newton_iterations"] = 0;  // small deformation: no Newton loop
    step["residual_norms"] = Json::array();
    step["active_set_sizes"] = r.contact ? Json(r.contact->solution.active_set_sizes) : Json::array();
    step["cut_backs"] = 0;
    j["load_steps"] = Json::array({step});
  }
  if (!r.fluids.empty()) {
    Json fluids = Json::array();
    for (const FluidReport& f : r.fluids)
      fluids.push_back({{"faces", f.faces},
                        {"pressure", finite_or_null(f.pressure)},
                        {"wet_elements", f.wet_elements},
                        {"elements", f.elements},
                        {"force", std::vector<double>(f.force.data(), f.force.data() + f.force.size())},
                        {"peak_contact_pressure", finite_or_null(f.peak_contact_pressure)}});
    j["fluid_pressures"] = fluids;
  }
  if (!r.contacts.empty()) {
    const std::vector<std::string> files = pressure_file_stems(m);
    const bool several = r.contacts.size() > 1;
    // One contact: its numbers in "contact".  Several: "contact" holds what
    // belongs to the run, "contacts" each one's numbers (and its pressure file).
    Json c = several ? Json::object() : contact_numbers(r, r.contacts.front());
    c["applied_force"] = finite_or_null(r.applied_force);
    if (!r.load_steps) c["active_set_iterations"] = r.contact->solution.active_set_sizes.size();
    if (!r.contact->solution.step_iterations.empty())  // friction: per load step (the press, then each drag)
      c["friction_step_iterations"] = r.contact->solution.step_iterations;
    if (const auto part = modelled_part(m)) c["model_part"] = *part;
    if (!several) c["obstacle"] = m.contacts.front().obstacle->describe();
    j["contact"] = c;
    if (several) {
      Json each = Json::array();
      for (size_t i = 0; i < r.contacts.size(); ++i) {
        Json e = {{"face", r.contacts[i].face}, {"obstacle", m.contacts[i].obstacle->describe()}};
        e.update(contact_numbers(r, r.contacts[i]));
        e["pressure_csv"] = files[i] + ".csv";
        each.push_back(e);
      }
      j["contacts"] = each;
    }
    Json obstacles = Json::array();  // every contact: the force its obstacle exerts
    for (const auto& rr : r.reactions)
    {
      Json o = {{"face", rr.face}, {"obstacle", rr.obstacle}, {"normal_force", finite_or_null(rr.normal_force)},
                {"active", rr.active}};
      if (rr.tangential_force.size())  // friction: along the obstacle's tangents, and its size
        o["tangential_force"] = {{"components", std::vector<double>(rr.tangential_force.begin(), rr.tangential_force.end())},
                                 {"magnitude", finite_or_null(rr.tangential_force.norm())}};
      if (rr.extrusion) o["extrusion"] = finite_or_null(*rr.extrusion);  // against an edge: the reach past it
      obstacles.push_back(o);
    }
    j["obstacles"] = obstacles;
  }
  if (!r.dirichlet_reactions.empty()) j["dirichlet_reactions"] = reactions_json(r.dirichlet_reactions);
  if (r.hertz) j["analytic"] = {{"half_width", r.hertz->a}, {"max_pressure", r.hertz->p0}};
  Json e = Json::object();
  if (r.displacement_errors) {
    const auto& d = *r.displacement_errors;
    e["displacement_l2"] = finite_or_null(d.l2);
    e["displacement_h1"] = finite_or_null(d.h1);
    // A relative error against a zero reference (a zero load) is absent, not NaN.
    if (d.ref_l2 > 0) e["displacement_l2_rel"] = finite_or_null(d.l2 / d.ref_l2);
    if (d.ref_h1 > 0) e["displacement_h1_rel"] = finite_or_null(d.h1 / d.ref_h1);
  }
  if (r.pressure_error) {
    e["pressure_l2"] = finite_or_null(r.pressure_error->first);
    if (r.pressure_error->second > 0)
      e["pressure_l2_rel"] = finite_or_null(r.pressure_error->first / r.pressure_error->second);
  }
  if (!e.empty()) j["errors"] = e;
  if (r.load_steps) j["newton_seconds"] = r.load_steps->newton_seconds;
  {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);  // ru_maxrss in KiB on Linux
    j["memory_gib"] = {{"estimated", estimated_peak_bytes(m.spec) / double(1 << 30)},
                       {"peak_resident", double(usage.ru_maxrss) / double(1 << 20)}};
  }
  {
    const LinearSolverRecord& ls = r.linear_solver;
    Json solver = {{"type", ls.type}, {"ranks", ls.ranks}};
    if (!ls.method.empty()) solver["method"] = ls.method;
    if (!m.spec.solver.choice.empty()) solver["choice"] = m.spec.solver.choice;  // preconditioner = "auto"
    if (ls.condition_estimate > 0) solver["condition_estimate"] = finite_or_null(ls.condition_estimate);
    if (ls.type != "direct") {
      solver["krylov_iterations"] = ls.iterations;
      solver["peak_resident_all_ranks_gib"] = finite_or_null(ls.peak_resident_all_ranks_gib);
    }
    j["solver"] = solver;
  }
  j["timing_s"] = {{"assembly", r.timing.assembly},         {"factorization", r.timing.factorization},
                   {"linear_solve", r.timing.linear_solve}, {"contact", r.timing.contact},
                   {"postprocess", r.timing.postprocess},   {"total", r.timing.total}};
  return j;
}

std::string csv_number(double v, int digits) {
  return std::isfinite(v) ? fmt::format("{:.{}g}", v, digits) : std::string();
}

std::string load_curve_csv(const Model& m, const RunResult& r) {
  // One contact: contact_force.  Several: contact_force_<face> for each.
  const std::vector<std::string> tags = contact_file_tags(m);
  // With load curves the first column is their time.  The reactions of
  // the [[dirichlet]] face sets follow the other columns, one per component.
  const bool history = m.spec.has_load_curves();
  std::string s = history ? "time" : "load_factor";
  if (tags.size() > 1)
    for (const std::string& tag : tags) s += fmt::format(",contact_force_{}", tag);
  else
    s += ",contact_force";
  s += ",face_displacement,obstacle_displacement";
  // Friction: each contact's tangential force, a column per tangent
  // (tangential_force in 2D, tangential_force_1, _2 in 3D; _<face> with several contacts).
  const std::vector<Eigen::VectorXd> no_tangents;
  const std::vector<Eigen::VectorXd>& t0 = r.load_curve.empty() ? no_tangents : r.load_curve.front().tangential_forces;
  for (size_t i = 0; i < t0.size(); ++i)
    for (int j = 0; j < t0[i].size(); ++j)
      s += fmt::format(",tangential_force{}{}", tags.size() > 1 ? "_" + tags[i] : "",
                       t0[i].size() > 1 ? fmt::format("_{}", j + 1) : "");
  if (!r.load_curve.empty())
    for (const FaceReaction& f : r.load_curve.front().dirichlet_reactions)
      for (int c = 0; c < f.force.size(); ++c) s += fmt::format(",reaction_{}_{}", f.face, "xyz"[c]);
  s += "\n";
  for (const auto& p : r.load_curve) {
    s += csv_number(p.load_factor);
    if (tags.size() > 1)
      for (size_t i = 0; i < tags.size(); ++i)
        s += fmt::format(",{}", csv_number(i < p.contact_forces.size() ? p.contact_forces[i] : std::nan("")));
    else
      s += fmt::format(",{}", csv_number(p.contact_force()));
    s += fmt::format(",{},{}", csv_number(p.face_displacement), csv_number(p.obstacle_displacement));
    for (size_t i = 0; i < t0.size(); ++i)
      for (int j = 0; j < t0[i].size(); ++j)
        s += "," + csv_number(i < p.tangential_forces.size() && j < p.tangential_forces[i].size() ? p.tangential_forces[i][j]
                                                                                                 : std::nan(""));
    for (const FaceReaction& f : p.dirichlet_reactions)
      for (int c = 0; c < f.force.size(); ++c) s += "," + csv_number(f.force[c]);
    s += "\n";
  }
  return s;
}

std::string pressure_csv(const RunResult& r, size_t contact) {
  std::string s = "kind,r,pressure,r_over_a,p_over_p0,hertz_p_over_p0";
  const auto& rep = r.contacts.at(contact).report;
  // Friction: per multiplier its state, the tangential traction -lambda_t
  // and the slip accumulated over the steps, per obstacle tangent.
  const ContactSolution* fr = r.contact && r.contact->solution.lambda_t.size() ? &r.contact->solution : nullptr;
  const int nt = fr ? int(fr->lambda_t.size() / fr->lambda.size()) : 0;
  for (const char* col : {",tangential_traction", ",slip"})
    for (int j = 0; j < nt; ++j) s += nt == 1 ? std::string(col) : fmt::format("{}_{}", col, j + 1);
  s += fr ? ",state\n" : "\n";
  auto row = [&](const char* kind, PressureSample p, int K) {
    p.pressure += 0.0;  // an inactive multiplier's -0 prints as 0
    if (has_hertz_scale(r))
      s += fmt::format("{},{},{},{},{},{}", kind, csv_number(p.r), csv_number(p.pressure), csv_number(p.r / r.hertz->a),
                       csv_number(p.pressure / r.hertz->p0), csv_number(r.hertz->pressure(p.r) / r.hertz->p0));
    else
      s += fmt::format("{},{},{},,,", kind, csv_number(p.r), csv_number(p.pressure));
    if (fr && K >= 0) {
      for (int j = 0; j < nt; ++j) s += "," + csv_number(-fr->lambda_t[K * nt + j] + 0.0);
      for (int j = 0; j < nt; ++j) s += "," + csv_number(fr->slip[K * nt + j]);
      s += std::string(",") + std::array{"open", "stick", "slip"}[fr->friction_state[K]];
    } else if (fr) {
      s += std::string(2 * nt + 1, ',');
    }
    s += "\n";
  };
  const int first = r.contacts.at(contact).first_multiplier;
  for (size_t i = 0; i < rep.multipliers.size(); ++i) row("multiplier", rep.multipliers[i], first + int(i));
  for (const auto& p : rep.p1) row("p1", p, -1);
  return s;
}

}  // namespace igac
