#include "engine/structure/structure_model.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "engine/structure/disp_beam_column.h"
#include "engine/structure/elastic_beam_column.h"
#include "engine/structure/validation.h"

namespace pfem::structure {

namespace {
int global_dof(const std::array<int, 2>& nodes, int a) {
  return kDofsPerNode * nodes[a / kDofsPerNode] + a % kDofsPerNode;
}

void scatter_matrix(const std::array<int, 2>& nodes, const Mat6& k, double factor,
                    const AddEntry& add) {
  for (int a = 0; a < 6; ++a)
    for (int b = 0; b < 6; ++b)
      if (k(a, b) != 0.0) add(global_dof(nodes, a), global_dof(nodes, b), factor * k(a, b));
}
}  // namespace

StructureModel::StructureModel(const StructureModel& other)
    : nodes_(other.nodes_),
      damping_(other.damping_),
      num_parameters_(other.num_parameters_),
      u_trial_(other.u_trial_),
      u_committed_(other.u_committed_) {
  elements_.reserve(other.elements_.size());
  for (const auto& e : other.elements_) elements_.push_back(e->clone());
}

int StructureModel::add_node(double x, double y) {
  if (!std::isfinite(x) || !std::isfinite(y)) throw_invalid("x", "node coordinates must be finite");
  Node n;
  n.x << x, y;
  nodes_.push_back(n);
  u_trial_.conservativeResize(num_dofs());
  u_committed_.conservativeResize(num_dofs());
  u_trial_.tail(kDofsPerNode).setZero();
  u_committed_.tail(kDofsPerNode).setZero();
  return num_nodes() - 1;
}

void StructureModel::check_node(int n, const char* what) const {
  if (n < 0 || n >= num_nodes())
    throw_invalid(what, "node " + std::to_string(n) + " does not exist (" +
                            std::to_string(num_nodes()) + " nodes)");
}

void StructureModel::fix(int node, bool ux, bool uy, bool rz) {
  check_node(node, "node");
  nodes_[node].fixed = {ux, uy, rz};
}

void StructureModel::add_nodal_mass(int node, double mx, double my, double mrz) {
  check_node(node, "node");
  require_non_negative(mx, "mass");
  require_non_negative(my, "mass");
  require_non_negative(mrz, "mass");
  nodes_[node].mass += Vec3(mx, my, mrz);
}

void StructureModel::add_nodal_load(int node, double fx, double fy, double mz) {
  check_node(node, "node");
  nodes_[node].load += Vec3(fx, fy, mz);
}

void StructureModel::set_nodal_load(int node, double fx, double fy, double mz) {
  check_node(node, "node");
  nodes_[node].load = Vec3(fx, fy, mz);
}

int StructureModel::add_element(std::unique_ptr<Element> element) {
  if (!element) throw_invalid("element", "must not be null");
  for (int n : element->nodes()) check_node(n, "nodes");
  element->set_num_parameters(num_parameters_);
  elements_.push_back(std::move(element));
  return num_elements() - 1;
}

int StructureModel::add_elastic_beam(int i, int j, const ElasticSectionProperties& section,
                                     const BeamOptions& options,
                                     const Seeds<ElasticSectionProperties>& section_seeds) {
  check_node(i, "nodes");
  check_node(j, "nodes");
  return add_element(std::make_unique<ElasticBeamColumn2d>(
      std::array<int, 2>{i, j}, nodes_[i].x, nodes_[j].x, section, options, section_seeds));
}

int StructureModel::add_disp_beam(int i, int j, const Section& section, const BeamOptions& options,
                                  int integration_points) {
  check_node(i, "nodes");
  check_node(j, "nodes");
  return add_element(std::make_unique<DispBeamColumn2d>(
      std::array<int, 2>{i, j}, nodes_[i].x, nodes_[j].x, section, options, integration_points));
}

void StructureModel::set_rayleigh(const RayleighDamping& damping) {
  require_non_negative(damping.a0, "a0");
  require_non_negative(damping.a1, "a1");
  damping_ = damping;
}

Vec6 StructureModel::gather(const Eigen::VectorXd& u, const Element& e) const {
  const auto n = e.nodes();
  Vec6 ue;
  ue << u.segment<3>(kDofsPerNode * n[0]), u.segment<3>(kDofsPerNode * n[1]);
  return ue;
}

template <typename F>
void StructureModel::add_element_vectors(const Eigen::VectorXd& x, F&& f,
                                         Eigen::VectorXd& out) const {
  for (const auto& e : elements_) {
    const auto n = e->nodes();
    const Vec6 y = f(*e, gather(x, *e));
    out.segment<3>(kDofsPerNode * n[0]) += y.head<3>();
    out.segment<3>(kDofsPerNode * n[1]) += y.tail<3>();
  }
}

void StructureModel::check_vector(const Eigen::VectorXd& x, const char* what) const {
  if (x.size() != num_dofs())
    throw std::invalid_argument(std::string(what) + " vector has " + std::to_string(x.size()) +
                                " entries, the model " + std::to_string(num_dofs()) + " dofs");
}

void StructureModel::check_parameter(int k) const {
  if (k < 0 || k >= num_parameters_)
    throw std::out_of_range("parameter " + std::to_string(k) + " of " +
                            std::to_string(num_parameters_));
}

void StructureModel::set_trial_displacement(const Eigen::VectorXd& u) {
  check_vector(u, "displacement");
  u_trial_ = u;
  for (auto& e : elements_) e->set_trial_displacement(gather(u, *e));
}

void StructureModel::commit() {
  for (auto& e : elements_) e->commit();
  u_committed_ = u_trial_;
}

void StructureModel::revert_to_last_commit() {
  for (auto& e : elements_) e->revert_to_last_commit();
  u_trial_ = u_committed_;
}

Eigen::VectorXd StructureModel::resisting_force() const {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(num_dofs());
  add_element_vectors(
      u_trial_, [](const Element& e, const Vec6&) { return e.resisting_force(); }, f);
  return f;
}

void StructureModel::add_tangent(const AddEntry& add, double factor) const {
  for (const auto& e : elements_) scatter_matrix(e->nodes(), e->tangent_stiffness(), factor, add);
}

void StructureModel::add_initial_stiffness(const AddEntry& add, double factor) const {
  for (const auto& e : elements_) scatter_matrix(e->nodes(), e->initial_stiffness(), factor, add);
}

void StructureModel::add_mass(const AddEntry& add, double factor) const {
  for (const auto& e : elements_) scatter_matrix(e->nodes(), e->mass_matrix(), factor, add);
  for (int n = 0; n < num_nodes(); ++n)
    for (int k = 0; k < kDofsPerNode; ++k)
      if (nodes_[n].mass(k) != 0.0) {
        const int dof = kDofsPerNode * n + k;
        add(dof, dof, factor * nodes_[n].mass(k));
      }
}

void StructureModel::add_damping(const AddEntry& add, double factor) const {
  if (damping_.a0 != 0.0) add_mass(add, factor * damping_.a0);
  if (damping_.a1 != 0.0) add_initial_stiffness(add, factor * damping_.a1);
}

Eigen::VectorXd StructureModel::mass_times(const Eigen::VectorXd& a) const {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(num_dofs());
  add_element_vectors(
      a, [](const Element& e, const Vec6& ae) -> Vec6 { return e.mass_matrix() * ae; }, out);
  for (int n = 0; n < num_nodes(); ++n)
    out.segment<3>(kDofsPerNode * n) += nodes_[n].mass.cwiseProduct(a.segment<3>(kDofsPerNode * n));
  return out;
}

Eigen::VectorXd StructureModel::damping_times(const Eigen::VectorXd& v) const {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(num_dofs());
  if (damping_.a0 != 0.0) out += damping_.a0 * mass_times(v);
  if (damping_.a1 != 0.0) {
    const double a1 = damping_.a1;
    add_element_vectors(
        v,
        [a1](const Element& e, const Vec6& ve) -> Vec6 {
          return a1 * (e.initial_stiffness() * ve);
        },
        out);
  }
  return out;
}

bool StructureModel::mass_is_lumped() const {
  for (const auto& e : elements_)
    if (!e->has_lumped_mass()) return false;
  return true;
}

Eigen::VectorXd StructureModel::lumped_mass() const {
  if (!mass_is_lumped()) throw std::logic_error("lumped_mass(): some element has consistent mass");
  Eigen::VectorXd m = Eigen::VectorXd::Zero(num_dofs());
  add_mass([&m](int i, int j, double value) {
    if (i == j) m(i) += value;
  });
  return m;
}

Eigen::VectorXd StructureModel::external_load() const {
  Eigen::VectorXd f(num_dofs());
  for (int n = 0; n < num_nodes(); ++n) f.segment<3>(kDofsPerNode * n) = nodes_[n].load;
  return f;
}

void StructureModel::set_num_parameters(int P) {
  if (P < 0) throw_invalid("parameters", "the number must be >= 0 (got " + std::to_string(P) + ")");
  num_parameters_ = P;
  for (auto& e : elements_) e->set_num_parameters(P);
}

Eigen::VectorXd StructureModel::resisting_force_sensitivity(int k) const {
  check_parameter(k);
  Eigen::VectorXd df = Eigen::VectorXd::Zero(num_dofs());
  add_element_vectors(
      u_trial_, [k](const Element& e, const Vec6&) { return e.conditional_force_sensitivity(k); },
      df);
  return df;
}

Eigen::VectorXd StructureModel::mass_sensitivity_times(int k, const Eigen::VectorXd& a) const {
  check_parameter(k);
  check_vector(a, "acceleration");
  Eigen::VectorXd out = Eigen::VectorXd::Zero(num_dofs());
  add_element_vectors(
      a, [k](const Element& e, const Vec6& ae) -> Vec6 { return e.mass_sensitivity(k) * ae; }, out);
  return out;
}

Eigen::VectorXd StructureModel::damping_sensitivity_times(int k, const Eigen::VectorXd& v) const {
  check_parameter(k);
  check_vector(v, "velocity");
  const double a0 = damping_.a0, a1 = damping_.a1;
  Eigen::VectorXd out = Eigen::VectorXd::Zero(num_dofs());
  add_element_vectors(
      v,
      [=](const Element& e, const Vec6& ve) -> Vec6 {
        return (a0 * e.mass_sensitivity(k) + a1 * e.initial_stiffness_sensitivity(k)) * ve;
      },
      out);
  return out;
}

void StructureModel::set_displacement_sensitivity(int k, const Eigen::VectorXd& du) {
  check_parameter(k);
  check_vector(du, "displacement sensitivity");
  for (auto& e : elements_) e->set_displacement_sensitivity(k, gather(du, *e));
}

void StructureModel::archive(StateArchive& a) {
  a.expect(static_cast<std::uint64_t>(num_dofs()), "structure dofs");
  a.expect(elements_.size(), "structure elements");
  a.expect(static_cast<std::uint64_t>(num_parameters_), "structure parameters");
  a(u_trial_), a(u_committed_);
  for (auto& e : elements_) e->archive(a);
}

}  // namespace pfem::structure
