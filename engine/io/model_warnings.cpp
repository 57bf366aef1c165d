#include "engine/io/model_warnings.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <string>

#include "engine/io/model_checks.h"

namespace pfem {

namespace {

using pfem::v1::Model;
using pfem::v1::Vec2;

std::string num(double v) {
  std::ostringstream o;
  o.precision(3);
  o << v;
  return o.str();
}

double gravity(const Model& m) {
  return m.has_gravity() ? std::hypot(m.gravity().x(), m.gravity().y()) : 9.81;
}

// Lowest and highest y of the fluid regions; {inf, -inf} without any.
std::pair<double, double> fluid_y_range(const Model& m) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& r : m.fluid_regions()) {
    if (r.has_rectangle()) {
      lo = std::min(lo, r.rectangle().min().y()), hi = std::max(hi, r.rectangle().max().y());
    } else {
      for (const auto& p : r.polygon().points()) lo = std::min(lo, p.y()), hi = std::max(hi, p.y());
    }
  }
  return {lo, hi};
}

double segment_distance(const Vec2& p, double ax, double ay, double bx, double by) {
  const double dx = bx - ax, dy = by - ay, len2 = dx * dx + dy * dy;
  const double s = len2 > 0 ? std::clamp(((p.x() - ax) * dx + (p.y() - ay) * dy) / len2, 0.0, 1.0) : 0.0;
  return std::hypot(p.x() - ax - s * dx, p.y() - ay - s * dy);
}

// Distance from p to a fluid region (0 inside).
double region_distance(const Vec2& p, const pfem::v1::FluidRegion& r) {
  if (r.has_rectangle()) {
    const auto& a = r.rectangle();
    const double dx = std::max({a.min().x() - p.x(), 0.0, p.x() - a.max().x()});
    const double dy = std::max({a.min().y() - p.y(), 0.0, p.y() - a.max().y()});
    return std::hypot(dx, dy);
  }
  const auto& q = r.polygon().points();
  bool inside = false;
  double d = std::numeric_limits<double>::infinity();
  for (int i = 0, j = q.size() - 1; i < q.size(); j = i++) {
    if ((q[i].y() > p.y()) != (q[j].y() > p.y()) &&
        p.x() < (q[j].x() - q[i].x()) * (p.y() - q[i].y()) / (q[j].y() - q[i].y()) + q[i].x())
      inside = !inside;
    d = std::min(d, segment_distance(p, q[j].x(), q[j].y(), q[i].x(), q[i].y()));
  }
  return inside ? 0.0 : d;
}

// E I of a beam's section, 0 when it cannot be read.
double bending_stiffness(const pfem::v1::Structure& s, const pfem::v1::Beam& b) {
  for (const auto& sec : s.sections()) {
    if (sec.name() != b.section()) continue;
    if (sec.has_elastic()) return sec.elastic().e() * sec.elastic().inertia();
    const auto& f = sec.fiber_rectangle();
    for (const auto& mat : s.materials())
      if (mat.name() == f.material()) {
        const double e = mat.has_elastic() ? mat.elastic().e() : mat.bilinear().e0();
        return e * f.width() * std::pow(f.depth(), 3) / 12.0;
      }
  }
  return 0.0;
}

}  // namespace

std::optional<FieldError> ignored_bulk_modulus(const Model& m) {
  if (!is_incompressible(m) || m.fluid().kappa() == 0.0) return std::nullopt;
  return FieldError{"fluid.kappa",
                    "is ignored: analysis.formulation \"incompressible\" has div v = 0 and no bulk "
                    "modulus (leave fluid.kappa out)"};
}

std::optional<FieldError> fdm_tolerance_warning(double newton_tolerance, double fdm_eps) {
  if (newton_tolerance <= kFdmToleranceToStep * fdm_eps) return std::nullopt;
  return FieldError{"analysis.newton_tolerance",
                    num(newton_tolerance) + " is not far below the FDM step " + num(fdm_eps) +
                        ": central differences divide each run's Newton error by the step (keep it at most " +
                        num(kFdmToleranceToStep) + " x the step, e.g. the default 1e-10)"};
}

std::vector<FieldError> model_warnings(const Model& m) {
  std::vector<FieldError> w;
  const double rho = m.fluid().rho(), kappa = m.fluid().kappa(), h = m.mesh().h();
  if (rho < kMinPlausibleDensity || rho > kMaxPlausibleDensity)
    w.push_back({"fluid.rho", num(rho) + " kg/m^3 is outside the plausible [" + std::to_string(static_cast<int>(kMinPlausibleDensity)) +
                                  ", " + std::to_string(static_cast<int>(kMaxPlausibleDensity)) +
                                  "] kg/m^3 (water: 1000)"});
  const auto [y_lo, y_hi] = fluid_y_range(m);
  const double height = y_hi - y_lo, g = gravity(m);
  const double speed = std::sqrt(2.0 * g * std::max(height, 0.0));  // expected flow speed
  const bool incompressible = is_incompressible(m);
  if (auto ignored = ignored_bulk_modulus(m)) w.push_back(std::move(*ignored));
  if (speed > 0 && rho > 0) {
    const double c = std::sqrt(kappa / rho);
    if (!incompressible && kappa > 0 && c < kMinSoundToFlowSpeed * speed)
      w.push_back({"fluid.kappa", "the speed of sound sqrt(kappa/rho) = " + num(c) + " m/s is below " +
                                      num(kMinSoundToFlowSpeed) + " x the expected flow speed sqrt(2 g H) = " +
                                      num(speed) + " m/s (H = " + num(height) +
                                      " m of water): the fluid is far from incompressible (water: kappa = 2.15e9 Pa)"});
    if (h > 0 && m.analysis().dt() > h / speed)
      w.push_back({"analysis.dt", num(m.analysis().dt()) + " s is above h / sqrt(2 g H) = " + num(h / speed) +
                                      " s: a particle at the expected flow speed crosses more than one spacing per "
                                      "step (remeshing and contact need dt <= that bound)"});
  }
  if (m.has_structure()) {
    const auto& s = m.structure();
    std::map<std::string, Vec2> nodes;
    for (const auto& n : s.nodes()) {
      Vec2 p;
      p.set_x(n.x()), p.set_y(n.y());
      nodes[n.name()] = p;
    }
    for (int i = 0; i < s.beams_size(); ++i) {
      const auto& b = s.beams(i);
      if (!nodes.count(b.from_node()) || !nodes.count(b.to_node()) || !(height > 0)) continue;
      const Vec2 &a = nodes[b.from_node()], &e = nodes[b.to_node()];
      const double length = std::hypot(e.x() - a.x(), e.y() - a.y()), ei = bending_stiffness(s, b);
      // Cantilever under a triangular load, q0 at the root: tip deflection q0 L^4 / (30 E I).
      const double q0 = rho * g * std::min(height, length) * (m.has_thickness() ? m.thickness() : 1.0);
      const double deflection = ei > 0 ? q0 * std::pow(length, 4) / (30.0 * ei) : 0.0;
      if (deflection > length)
        w.push_back({"structure.beams[" + std::to_string(i) + "]",
                     "as a cantilever under the hydrostatic load of " + num(std::min(height, length)) +
                         " m of water it would deflect " + num(deflection) + " m, more than its length " + num(length) +
                         " m: is the section's E (or its size) right?"});
    }
  }
  for (int i = 0; i < m.recorders_size(); ++i) {
    const auto& r = m.recorders(i);
    if (!r.has_point() || !(h > 0)) continue;
    double d = std::numeric_limits<double>::infinity();
    for (const auto& region : m.fluid_regions()) d = std::min(d, region_distance(r.point(), region));
    if (m.has_structure()) {
      std::map<std::string, const pfem::v1::StructureNode*> nodes;
      for (const auto& n : m.structure().nodes()) {
        nodes[n.name()] = &n;
        d = std::min(d, std::hypot(r.point().x() - n.x(), r.point().y() - n.y()));
      }
      for (const auto& b : m.structure().beams())
        if (nodes.count(b.from_node()) && nodes.count(b.to_node())) {
          const auto *a = nodes[b.from_node()], *e = nodes[b.to_node()];
          d = std::min(d, segment_distance(r.point(), a->x(), a->y(), e->x(), e->y()));
        }
    }
    if (d > h)
      w.push_back({"recorders[" + std::to_string(i) + "].point",
                   "is " + num(d) + " m from the water at t = 0 and from the structure (more than h = " + num(h) +
                       " m): it is bound to the nearest node, which may be a wall node or a particle far away"});
  }
  return w;
}

}  // namespace pfem
