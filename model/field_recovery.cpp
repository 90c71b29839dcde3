// SPDX-License-Identifier: BSD-3-Clause
#include "model/field_recovery.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <fmt/format.h>
#include <limits>
#include <memory>
#include <stdexcept>

#include "engine/assembly.hpp"
#include "engine/pressure_space.hpp"
#include "engine/quadrature.hpp"
#include "engine/spline/refinement.hpp"
#include "engine/volumetric_projection.hpp"
#include "engine/free_cores.hpp"

namespace igac {


StressLaw cauchy_stress(std::shared_ptr<const HyperelasticLaw> law, bool small_strain) {
  return [law = std::move(law), small_strain](const Eigen::Matrix3d& grad_u) {
    const Eigen::Matrix3d F = Eigen::Matrix3d::Identity() + grad_u;
    Eigen::Matrix3d P;
    if (!law->evaluate(F, P, nullptr)) return Eigen::Matrix3d::Constant(std::numeric_limits<double>::quiet_NaN()).eval();
    // Small strain: P of the linear law is sigma itself; else sigma = P F^T / J.
    return small_strain ? P : Eigen::Matrix3d(P * F.transpose() / F.determinant());
  };
}

StressLaw linear_elastic_stress(double lambda, double mu) {
  // The one linear-elastic law of materials/, from its Lame constants.
  const MaterialParameters p{mu * (3 * lambda + 2 * mu) / (lambda + mu), lambda / (2 * (lambda + mu)), {}};
  return cauchy_stress(std::shared_ptr<const HyperelasticLaw>(make_law("linear_elastic", p)), true);
}

double von_mises(const Eigen::Matrix3d& s) {
  const Eigen::Matrix3d dev = s - s.trace() / 3.0 * Eigen::Matrix3d::Identity();
  return std::sqrt(1.5 * dev.cwiseProduct(dev).sum());
}

namespace {

int max_degree(const BezierMesh& m) { return std::max({m.degree(0), m.degree(1), m.degree(2)}); }

// Measure of the map dX/ds (space_dim x param_dim): |det| for volumes, the
// length / area of the tangents for curves and surfaces.
double measure(const Eigen::MatrixXd& J) {
  if (J.rows() == J.cols()) return std::abs(J.determinant());
  return std::sqrt((J.transpose() * J).determinant());
}

// One quadrature point of a Bezier element: its rational basis R, grad u
// (3 x 3, zero outside the space dimensions) and its weight w |det J|.
struct ProjectionPoint {
  Eigen::VectorXd R;
  Eigen::Matrix3d grad;
  double hoop = 0;  // 2D: u_x / x, the hoop strain of the axisymmetric model
  double weight = 0;
};

// The first 12 columns of a projected row: sigma's 6 Voigt components, then
// the strain's (small strain eps = sym grad u; large deformation
// E = (F^T F - I) / 2).
void put_stress_and_strain(const Eigen::Matrix3d& sigma, const Eigen::Matrix3d& grad, bool green_lagrange,
                           Eigen::RowVectorXd& f) {
  const Eigen::Matrix3d eps = green_lagrange ? Eigen::Matrix3d(0.5 * (grad + grad.transpose() + grad.transpose() * grad))
                                             : Eigen::Matrix3d(0.5 * (grad + grad.transpose()));
  for (int c = 0; c < 6; ++c) {
    f[c] = sigma(kVoigt[c][0], kVoigt[c][1]);
    f[6 + c] = eps(kVoigt[c][0], kVoigt[c][1]);
  }
}

// The element-local L2 projection, onto each element's rational Bezier basis
// R_i, of `columns` values per quadrature point (max(p) + 2 Gauss points per
// direction): sum_j (int_e R_i R_j) c_j = int_e R_i f.  values(e, q, point,
// row) fills the row of f at point q of element e.  Elements run in
// parallel (each writes only its own rows); the first exception thrown in
// one is rethrown after the loop.  The one kernel of the body's recovered
// fields (stress and strain, J and the pressure).
template <class Values>
Eigen::MatrixXd project_on_elements(const BezierMesh& mesh, int columns, Values&& values) {
  const int dim = mesh.space_dim(), nl = mesh.num_local(), ne = mesh.num_elements();
  const TensorGaussRule rule = tensor_gauss_rule(mesh.param_dim(), max_degree(mesh) + 2);
  const int nq = int(rule.points.size());
  Eigen::MatrixXd out(mesh.num_points(), columns);
  std::exception_ptr error;
#pragma omp parallel num_threads(free_cores())
  {
    ProjectionPoint point;
    Eigen::MatrixXd dR, M(nl, nl), B(nl, columns);
    Eigen::RowVectorXd f(columns);
    // dX/ds and du/ds padded to 3 x 3 (J with 1 on the unused diagonal): the
    // closed-form inverse of a fixed-size matrix, no allocation per point
    Eigen::Matrix3d J, G;
#pragma omp for schedule(dynamic, 16)
    for (int e = 0; e < ne; ++e) {
      try {
        const BezierElement& el = mesh.element(e);
        M.setZero();
        B.setZero();
        for (int q = 0; q < nq; ++q) {
          mesh.basis(el, rule.points[size_t(q)], point.R, &dR);
          J.setIdentity();
          G.setZero();
          J.topLeftCorner(dim, dim).noalias() = el.points.transpose() * dR;     // dX/ds
          G.topLeftCorner(dim, dim).noalias() = el.fields[0].transpose() * dR;  // du/ds
          point.grad.noalias() = G * J.inverse();
          if (dim == 2) point.hoop = el.fields[0].col(0).dot(point.R) / el.points.col(0).dot(point.R);
          point.weight = rule.weights[size_t(q)] * std::abs(J.determinant());
          values(e, q, point, f);
          M.selfadjointView<Eigen::Lower>().rankUpdate(point.R, point.weight);
          for (int c = 0; c < columns; ++c) B.col(c) += (point.weight * f[c]) * point.R;
        }
        out.middleRows(Eigen::Index(e) * nl, nl) = M.selfadjointView<Eigen::Lower>().llt().solve(B);
      } catch (...) {
#pragma omp critical(igac_projection_error)
        if (!error) error = std::current_exception();
      }
    }
  }
  if (error) std::rethrow_exception(error);
  return out;
}

}  // namespace

RecoveredStress recover_stress(const BezierMesh& mesh, const StressLaw& law, bool green_lagrange) {
  if (mesh.param_dim() != mesh.space_dim()) throw std::invalid_argument("stress recovery needs a volume mesh");
  if (mesh.num_elements() > 0 && mesh.element(0).fields.empty())
    throw std::invalid_argument("stress recovery needs the displacement as field 0");
  const Eigen::MatrixXd C = project_on_elements(mesh, 12, [&](int, int, const ProjectionPoint& x, Eigen::RowVectorXd& f) {
    put_stress_and_strain(law(x.grad), x.grad, green_lagrange, f);
  });
  RecoveredStress out;
  out.stress = C.leftCols(6);
  out.strain = C.rightCols(6);
  fill_stress_scalars(out);
  return out;
}

void fill_stress_scalars(RecoveredStress& s) {
  const Eigen::Index n = s.stress.rows();
  s.von_mises.resize(n);
  s.magnitude.resize(n);
  s.principal.resize(n, 3);
  for (Eigen::Index i = 0; i < n; ++i) {  // coefficient by coefficient (see the header)
    const Eigen::Matrix3d sigma = symmetric_tensor(s.stress.row(i));
    s.von_mises[i] = von_mises(sigma);
    s.magnitude[i] = sigma.norm();
    const Eigen::Vector3d ev = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(sigma, Eigen::EigenvaluesOnly).eigenvalues();
    s.principal.row(i) << ev[2], ev[1], ev[0];  // largest first
  }
}

BezierMesh body_bezier_mesh(const Body& body, const Eigen::MatrixXd& u, int first_patch, int num_patches,
                            std::vector<int>* patch_of) {
  if (num_patches < 0) num_patches = body.num_patches() - first_patch;
  BezierMesh mesh;
  if (patch_of) patch_of->clear();
  for (int k = first_patch; k < first_patch + num_patches; ++k) {
    const NurbsPatch& patch = body.patch(k);
    const Eigen::MatrixXd field = body.patch_field(k, u);
    bool elevate = false;
    for (int d = 0; d < patch.param_dim(); ++d) elevate = elevate || patch.degree(d) < body.degree();
    if (!elevate) {
      mesh.append(BezierMesh(patch, {field}));
      if (patch_of) patch_of->resize(size_t(mesh.num_elements()), k);
      continue;
    }
    // The field rides along as more coordinates of the same rational map:
    // elevating [X u] keeps both exactly.
    std::vector<KnotVector> knots;
    for (int d = 0; d < patch.param_dim(); ++d) knots.push_back(patch.knots(d));
    Eigen::MatrixXd both(patch.num_control_points(), patch.space_dim() + field.cols());
    both << patch.points(), field;
    const NurbsPatch high = elevate_to(NurbsPatch(std::move(knots), both, patch.weights()), body.degree());
    std::vector<KnotVector> high_knots;
    for (int d = 0; d < high.param_dim(); ++d) high_knots.push_back(high.knots(d));
    const NurbsPatch geometry(std::move(high_knots), high.points().leftCols(patch.space_dim()), high.weights());
    mesh.append(BezierMesh(geometry, {high.points().rightCols(field.cols())}));
    if (patch_of) patch_of->resize(size_t(mesh.num_elements()), k);
  }
  return mesh;
}

namespace {

// The volumetric part of a mixed patch's stress: the formulation's pressure
// (`volume`, recover_volume's hydrostatic pressure -tr sigma / 3 on the same
// Bezier basis) in place of the pointwise law's.  Coefficient by
// coefficient, sigma - (tr sigma / 3) I - p_hyd I: exact for the projected
// fields, both being L2 projections with the same rule and the trace linear.
// The stress scalars (von Mises, principal, magnitude) are the caller's to fill.
void take_formulation_pressure(const Model& model, const BezierMesh& mesh, const RecoveredVolume& volume,
                               RecoveredStress& s) {
  const std::vector<Formulation> formulations = model.patch_formulations();
  if (std::none_of(formulations.begin(), formulations.end(), is_mixed)) return;
  const Body& body = model.body;
  const int nl = mesh.num_local();
  if (volume.pressure.size() != s.stress.rows() || s.stress.rows() != Eigen::Index(mesh.num_points()))
    throw std::invalid_argument("stress recovery: the pressure field is not on the stress's points");
  int e = 0;
  for (int k = 0; k < body.num_patches(); ++k) {
    const int n = body.patch(k).num_elements();
    if (is_mixed(formulations[formulations.size() == 1 ? 0 : size_t(k)]))
      for (Eigen::Index i = Eigen::Index(e) * nl; i < Eigen::Index(e + n) * nl; ++i) {
        const double shift = -volume.pressure[i] - (s.stress(i, 0) + s.stress(i, 1) + s.stress(i, 2)) / 3;
        for (int c = 0; c < 3; ++c) s.stress(i, c) += shift;
      }
    e += n;
  }
}

}  // namespace

Eigen::Matrix3d symmetric_tensor(const Eigen::Ref<const Eigen::RowVectorXd>& v) {
  Eigen::Matrix3d s;
  for (int c = 0; c < 6; ++c) s(kVoigt[c][0], kVoigt[c][1]) = s(kVoigt[c][1], kVoigt[c][0]) = v[c];
  return s;
}

StressLaw model_stress_law(const Model& model) {
  // Large deformation: Cauchy stress sigma = P F^T / J of the case's law
  // (plane strain in 2D is the 3D law with F_33 = 1).
  return model.law ? cauchy_stress(std::shared_ptr<const HyperelasticLaw>(model.law.get(), [](const HyperelasticLaw*) {}),
                                   !model.spec.finite_strain())
                   : linear_elastic_stress(model.material.lambda(), model.material.mu());  // a Model made in code
}

namespace {
// recover_volume, and with `with_stress` the stress and strain in the same
// projection (one pass over the elements, the law evaluated once per point;
// the stress of a mixed patch then takes the formulation's pressure).
RecoveredFields project_body_fields(const BezierMesh& mesh, const Model& model, const Eigen::VectorXd& element_pressures,
                                    bool with_stress) {
  const int pd = mesh.param_dim(), dim = mesh.space_dim();
  if (pd != dim) throw std::invalid_argument("volume recovery needs a volume mesh");
  const BodyQuadrature quad(model.body, gauss_points_for(model.body.degree()));
  if (mesh.num_elements() != quad.num_elements())
    throw std::invalid_argument(fmt::format("volume recovery: a mesh of {} elements for a body of {}",
                                            mesh.num_elements(), quad.num_elements()));
  const bool small = !model.spec.finite_strain();
  const bool axisymmetric = model.spec.axisymmetric();
  const std::vector<Formulation> formulations = model.patch_formulations();
  const std::vector<LinearElastic> materials = model.patch_materials();
  const std::vector<const HyperelasticLaw*> laws = model.patch_laws();
  const auto per_patch = [](const auto& v, int k) { return v[v.size() == 1 ? 0 : size_t(k)]; };
  // The pointwise law of each patch (the displacement formulation's -tr sigma / 3).
  std::vector<StressLaw> stress_laws;
  if (model.parts.size() <= 1) {
    stress_laws.push_back(model_stress_law(model));
  } else {
    for (const Model::Part& part : model.parts)
      stress_laws.insert(stress_laws.end(), size_t(part.num_patches), cauchy_stress(part.law, small));
  }
  const PressureSpace space = mixed_pressure_space(quad, formulations);
  const int n_functions = space.num_functions();
  const TensorGaussRule rule = tensor_gauss_rule(pd, max_degree(mesh) + 2);
  const int nq = int(rule.points.size());
  Eigen::VectorXd R;
  Eigen::MatrixXd dR, Jm(dim, dim), G(dim, dim);
  // grad u at point q of element e, and its weight
  const auto gradient = [&](const BezierElement& el, int q, double& weight) {
    mesh.basis(el, rule.points[size_t(q)], R, &dR);
    Jm.noalias() = el.points.transpose() * dR;
    G.noalias() = el.fields[0].transpose() * dR;
    Eigen::Matrix3d grad = Eigen::Matrix3d::Zero();
    grad.topLeftCorner(dim, dim) = G * Jm.inverse();
    if (axisymmetric) grad(2, 2) = el.fields[0].col(0).dot(R) / el.points.col(0).dot(R);
    weight = rule.weights[size_t(q)] * std::abs(Jm.determinant());
    return grad;
  };
  // The pressure functions N_A of element e at point q: the Bezier
  // element's reference point is the element's local coordinate of the
  // pressure space (both map [0, 1]^d linearly onto the element's parameter
  // box, first direction first; tests/unit/model/test_pressure_field.cpp).
  PressureSpace::Scratch scratch;
  std::vector<double> N;
  const auto functions = [&](int e, int q) { space.values_local(e, rule.points[size_t(q)].data(), N, scratch); };
  // Pass 1: theta_A = (1/m_A) int N_A J dX (small strain: tr eps), m_A =
  // int N_A dX, over every element of every mixed patch.
  std::vector<double> integral(size_t(n_functions), 0.0), mass(size_t(n_functions), 0.0);
  for (int e = 0; e < mesh.num_elements(); ++e) {
    if (!is_mixed(per_patch(formulations, quad.patch_of(e)))) continue;
    for (int q = 0; q < nq; ++q) {
      double w = 0;
      const Eigen::Matrix3d grad = gradient(mesh.element(e), q, w);
      const double value = small ? grad.trace() : (Eigen::Matrix3d::Identity() + grad).determinant();
      functions(e, q);
      const int* a = space.functions_begin(e);
      for (size_t i = 0; i < N.size(); ++i) {
        integral[size_t(a[i])] += w * N[i] * value;
        mass[size_t(a[i])] += w * N[i];
      }
    }
  }
  // The pressures p_A: the run's own (the incompressible limit's
  // multipliers: one per pressure function; one per element from a run
  // that numbered them so), or U'(theta_A) (small strain K theta_A); shown
  // as the hydrostatic pressure -tr sigma / 3, so with the sign turned.
  const bool given_per_function = element_pressures.size() == n_functions;
  const bool given_per_element = !given_per_function && element_pressures.size() == mesh.num_elements();
  if (element_pressures.size() > 0 && !given_per_function && !given_per_element)
    throw std::invalid_argument(fmt::format("volume recovery: {} run pressures for {} pressure functions and {} elements",
                                            element_pressures.size(), n_functions, mesh.num_elements()));
  std::vector<double> function_pressure(size_t(n_functions), 0.0);
  for (int a = 0; a < n_functions; ++a) {
    if (mass[size_t(a)] == 0) continue;  // not mixed
    const int k = space.patch_of_function(a);
    const double theta = integral[size_t(a)] / mass[size_t(a)];
    if (given_per_function) {
      function_pressure[size_t(a)] = -element_pressures[a];
    } else if (small) {
      const LinearElastic& mat = per_patch(materials, k);
      function_pressure[size_t(a)] = -(mat.lambda() + 2 * mat.mu() / 3) * theta;
    } else {
      VolumetricValues v;
      function_pressure[size_t(a)] =
          per_patch(laws, k)->volumetric(theta, v) ? -v.dU : std::numeric_limits<double>::quiet_NaN();
    }
  }
  // Pass 2: J and the pressure (and the stress and strain) projected onto
  // each element's Bezier basis.
  const bool green_lagrange = !small;
  const int first = with_stress ? 12 : 0;  // the columns of J and the pressure
  const Eigen::MatrixXd C =
      project_on_elements(mesh, first + 2, [&](int e, int q, const ProjectionPoint& x, Eigen::RowVectorXd& f) {
        const int k = quad.patch_of(e);
        const StressLaw& law = stress_laws[stress_laws.size() == 1 ? 0 : size_t(k)];  // (not copied: elements run in parallel)
        const bool mixed = is_mixed(formulations[formulations.size() == 1 ? 0 : size_t(k)]);
        // grad u with its out-of-plane entry: the law's F_33 - 1 in 2D (0 in
        // plane strain; plane stress solves sigma_zz = 0), so the strain, J and
        // the stress are the plate's; axisymmetric: the hoop strain u_r / r.
        Eigen::Matrix3d grad = x.grad;
        if (axisymmetric)
          grad(2, 2) = x.hoop;
        else if (const HyperelasticLaw* patch_law = per_patch(laws, k); dim == 2 && patch_law)
          grad(2, 2) = patch_law->out_of_plane_stretch(Eigen::Matrix2d::Identity() + grad.topLeftCorner<2, 2>()) - 1;
        Eigen::Matrix3d sigma;
        if (with_stress || !mixed) sigma = law(grad);
        if (with_stress) put_stress_and_strain(sigma, grad, green_lagrange, f);
        double pressure = 0;
        if (!mixed) {
          pressure = -sigma.trace() / 3;
        } else if (given_per_element) {
          pressure = -element_pressures[e];
        } else {
          // p(x) = sum_A N_A(x) p_A; the stabilisation's mu_s (J - Pi_e J)
          // is not part of the field (see the header).
          PressureSpace::Scratch own_scratch;  // (per call: elements run in parallel)
          std::vector<double> values;
          space.values_local(e, rule.points[size_t(q)].data(), values, own_scratch);
          const int* a = space.functions_begin(e);
          for (size_t i = 0; i < values.size(); ++i) pressure += values[i] * function_pressure[size_t(a[i])];
        }
        f[first] = (Eigen::Matrix3d::Identity() + grad).determinant();
        f[first + 1] = pressure;
      });
  RecoveredFields out;
  out.volume.jacobian = C.col(first);
  out.volume.pressure = C.col(first + 1);
  if (with_stress) {
    out.stress.stress = C.leftCols(6);
    out.stress.strain = C.middleCols(6, 6);
    take_formulation_pressure(model, mesh, out.volume, out.stress);
    fill_stress_scalars(out.stress);
  }
  return out;
}
}  // namespace

RecoveredVolume recover_volume(const BezierMesh& mesh, const Model& model, const Eigen::VectorXd& element_pressures) {
  return project_body_fields(mesh, model, element_pressures, false).volume;
}

RecoveredFields recover_body_fields(const BezierMesh& mesh, const Model& model, const Eigen::VectorXd& element_pressures) {
  return project_body_fields(mesh, model, element_pressures, true);
}

ContactPartner contact_partner(const Model& model, size_t k, const Eigen::MatrixXd& u, double t) {
  const Model::Contact& c = model.contacts.at(k);
  if (c.master) {
    auto moved = std::make_shared<MasterSurface>(*c.master);
    moved->update(u);
    return [moved](const Eigen::VectorXd& x) {
      const std::optional<MasterPoint> mp = moved->project(x);
      if (!mp) throw std::invalid_argument("a contact's master surface has no elements");
      return ObstacleProbe{mp->gap, mp->normal, {}};
    };
  }
  Eigen::VectorXd shift;
  if (c.motion.size() > 0 && model.spec.finite_strain()) shift = c.curve(t) * c.motion;
  else if (c.motion.size() > 0)  // (without curves: step 0 before the motion, step 1 after it)
    shift = (c.curve(t) - 1.0) * c.motion;
  const Obstacle* obstacle = c.obstacle.get();
  return [obstacle, shift](const Eigen::VectorXd& x) {
    return obstacle->probe(shift.size() == x.size() ? Eigen::VectorXd(x - shift) : x);
  };
}

ContactPartFields recover_contact_fields(const BezierMesh& mesh, const std::vector<const ContactSide*>& side_of,
                                         const ContactSolution& sol, const ContactPartner& partner) {
  const int nl = mesh.num_local(), ne = mesh.num_elements(), sd = mesh.space_dim();
  const int nf = 2 + sd;  // projected: pressure, traction, gap
  ContactPartFields out;
  out.point_pressure.resize(mesh.num_points());
  out.point_traction.resize(mesh.num_points(), sd);
  out.point_gap.resize(mesh.num_points());
  out.cell_pressure.resize(ne);
  out.cell_weighted_gap.resize(ne);
  out.cell_gap.resize(ne);
  out.cell_active.assign(ne, false);
  const TensorGaussRule rule = tensor_gauss_rule(mesh.param_dim(), max_degree(mesh) + 3);
  // Each element on its own (the partner's closest-point search at every
  // point is most of a two-body output): on the free cores, each element's
  // result the same on any thread. What one throws is rethrown here (none
  // may leave an OpenMP region).
  std::exception_ptr failure;
#pragma omp parallel num_threads(free_cores()) if (ne >= 64)
  {
    Eigen::VectorXd R;
    Eigen::MatrixXd dR, M(nl, nl), b(nl, nf);
    Eigen::RowVectorXd f(nf);
    std::vector<int> idx;
    std::vector<double> val;
#pragma omp for schedule(dynamic, 8)
    for (int e = 0; e < ne; ++e) {
      try {
        const BezierElement& el = mesh.element(e);
        const ContactSide& side = *side_of[e];
        M.setZero();
        b.setZero();
        double area = 0, p_int = 0, g_int = 0, gap_int = 0;
        bool active = false;
        for (size_t q = 0; q < rule.points.size(); ++q) {
          mesh.basis(el, rule.points[q], R, &dR);
          const double wt = rule.weights[q] * measure(el.points.transpose() * dR);
          const Eigen::VectorXd xi = el.parameter(rule.points[q]);
          side.space.basis(xi, idx, val);
          for (int& K : idx) K += side.first_multiplier;
          double p = 0, g = 0;
          for (size_t k = 0; k < idx.size(); ++k) {
            p -= sol.lambda[idx[k]] * val[k];
            g += sol.weighted_gap[idx[k]] * val[k];
            if (val[k] != 0.0 && sol.active[idx[k]]) active = true;
          }
          // The contact pushes along the partner's normal at the deformed point.
          const ObstacleProbe probe = partner(el.points.transpose() * R + el.fields[0].transpose() * R);
          f[0] = p;
          f.segment(1, sd) = p * probe.normal.transpose();
          f[nf - 1] = probe.gap;
          M.noalias() += wt * R * R.transpose();
          b.noalias() += (wt * R) * f;
          area += wt;
          p_int += wt * p;
          g_int += wt * g;
          gap_int += wt * probe.gap;
        }
        const Eigen::MatrixXd c = M.llt().solve(b);
        out.point_pressure.segment(e * nl, nl) = c.col(0);
        out.point_traction.middleRows(e * nl, nl) = c.middleCols(1, sd);
        out.point_gap.segment(e * nl, nl) = c.col(nf - 1);
        out.cell_pressure[e] = p_int / area;
        out.cell_weighted_gap[e] = g_int / area;
        out.cell_gap[e] = gap_int / area;
        out.cell_active[e] = active;
      } catch (...) {
#pragma omp critical(igac_contact_fields)
        if (!failure) failure = std::current_exception();
      }
    }
  }
  if (failure) std::rethrow_exception(failure);
  return out;
}

}  // namespace igac
