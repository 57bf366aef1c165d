// Improved HL-RF (Zhang & Der Kiureghian 1995): the HL-RF direction
//   d = [(grad G . u - G) / ||grad G||^2] grad G - u
// with an Armijo line search on the merit function m(u) = ||u||^2 / 2 + c |G(u)| / |G(u0)|,
// c = 2 ||u|| / ||grad G / G(u0)|| + 10 (> ||u|| / ||grad G / G(u0)||, which makes d a descent
// direction). G is scaled by its value at the start point so that the merit function does not
// depend on the units of g: unscaled, a g of order 1e-3 (a deflection in metres) gives
// c |G| << ||u||^2 / 2 and the line search creeps towards the design point in small steps.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "clients/reliability/form_search.h"

namespace pfem::reliability::detail {

namespace {
constexpr double kShortestProgress = 1.0 / 1024.0;  // of the HL-RF step

// How far g(u + du) departs from g(u) + du.(grad(u) + grad(u + du)) / 2. The trapezoid rule is
// exact to second order, so what is left is g's jumps (a PFEM response's remeshing decisions)
// and third-order terms.
double trapezoid_departure(double g, const Eigen::VectorXd& grad, double g_new, const Eigen::VectorXd& grad_new,
                           const Eigen::VectorXd& du) {
  return std::abs(g_new - g - 0.5 * du.dot(grad + grad_new));
}

// Where g jumps by up to `resolution` |grad G| along the search direction, the limit state's
// place along the normal is known to that distance in u and no better. The design point is then
// as good as g allows when |G| is within the tolerance (the first design-point test), that
// distance is within the tolerance on beta, and u's misalignment with alpha (the second test)
// costs beta less than it: ||u|| - alpha.u, the part of the HL-RF step's change of beta that
// does not come from G.
bool converged_to_resolution(const Eigen::VectorXd& u, double g, const Eigen::VectorXd& gradient, double g_scale,
                             double resolution, double tolerance) {
  const double misalignment = u.norm() + gradient.dot(u) / gradient.norm();
  return std::abs(g) <= tolerance * g_scale && resolution <= tolerance * std::max(1.0, u.norm()) &&
         misalignment <= resolution;
}
}  // namespace

bool design_point_converged(const Eigen::VectorXd& u, double g, const Eigen::VectorXd& gradient,
                            double g_scale, double tol_g, double tol_alignment) {
  const double gn = gradient.norm();
  if (!(gn > 0)) return false;
  const Eigen::VectorXd alpha = -gradient / gn;
  const double e1 = std::abs(g) / g_scale;
  const double e2 = (u - alpha.dot(u) * alpha).norm() / std::max(1.0, u.norm());
  return e1 <= tol_g && e2 <= tol_alignment;
}

SearchOutcome search_ihlrf(StandardSpaceFunction& G, const Eigen::VectorXd& u0,
                           const FormOptions& options) {
  SearchOutcome out;
  out.u = u0;
  Eigen::VectorXd grad;
  double g = G.value_and_gradient(out.u, grad);
  if (!std::isfinite(g)) {
    out.message = "g is not finite at the start point";
    return out;
  }
  const double g_scale = std::abs(g) > 0 ? std::abs(g) : 1.0;
  bool stalled = false;  // the last line search found no decrease
  for (int k = 0;; ++k) {
    out.iterations = k;
    out.has_gradient = true;
    out.g = g;
    out.gradient = grad;
    if (options.progress) {
      options.progress({k, out.u.norm(), g, k == 0 ? 0.0 : 1.0, G.evaluations()});
    }
    const double gn = grad.norm();
    if (!(gn > 0) || !grad.allFinite()) {
      out.message = "the gradient of g vanished or is not finite at iteration " + std::to_string(k);
      return out;
    }
    if (design_point_converged(out.u, g, grad, g_scale, options.tolerance, options.tolerance)) {
      out.converged = true;
      out.message = "converged: |G| and the design-point condition within the tolerance";
      return out;
    }
    if (k >= options.max_iterations) {
      out.message = "no convergence in " + std::to_string(options.max_iterations) + " iterations";
      return out;
    }
    const Eigen::VectorXd& u = out.u;
    const Eigen::VectorXd d = ((grad.dot(u) - g) / (gn * gn)) * grad - u;
    const double c = 2.0 * u.norm() / (gn / g_scale) + 10.0;
    const double merit = 0.5 * u.squaredNorm() + c * std::abs(g) / g_scale;
    const double sign = g > 0 ? 1.0 : (g < 0 ? -1.0 : 0.0);
    const double slope = (u + (c / g_scale) * sign * grad).dot(d);  // < 0 by the choice of c
    double step = 1.0;
    Eigen::VectorXd u_new;
    Eigen::VectorXd grad_new;
    double g_new = 0.0;
    bool accepted = false;
    double jump = 0.0;  // of g along d, beside what its gradients account for
    for (int j = 0; j < options.max_line_search_steps; ++j, step *= options.armijo_b) {
      u_new = u + step * d;
      g_new = G.value_and_gradient(u_new, grad_new);
      if (!std::isfinite(g_new)) continue;
      jump = std::max(jump, trapezoid_departure(g, grad, g_new, grad_new, step * d));
      const double merit_new = 0.5 * u_new.squaredNorm() + c * std::abs(g_new) / g_scale;
      // (The rounding allowance lets the full step through once the merit function is flat to
      // machine precision, near convergence, instead of stalling on shrinking steps.)
      const double rounding = 8.0 * std::numeric_limits<double>::epsilon() * merit;
      if (merit_new - merit <= options.armijo_a * step * slope + rounding) {
        accepted = true;
        break;
      }
    }
    // A step accepted only below 1/1024 of the HL-RF step is no progress either: the
    // linearisation held over no more than that, g is piecewise smooth on a finer scale than the
    // search's (a PFEM response between remeshing decisions), and such steps crept on.
    if (accepted && step < kShortestProgress) accepted = false;
    // Where the full step failed, the points tried have measured g's jumps along d.
    if (!(accepted && step == 1.0)) {
      const double resolution = jump / gn;
      if (converged_to_resolution(u, g, grad, g_scale, resolution, options.tolerance)) {
        out.converged = true;
        out.beta_resolution = resolution;
        char text[64];
        std::snprintf(text, sizeof text, "%.3g", resolution);
        out.message = std::string("converged to the resolution of g: |G| within the tolerance, and u's "
                                  "misalignment with alpha costs beta less than g's jumps along the search direction "
                                  "move the limit state (") +
                      text + " in u)";
        return out;
      }
    }
    if (!accepted) {
      if (!std::isfinite(g_new)) {
        out.message = "g is not finite along the search direction at iteration " + std::to_string(k);
        return out;
      }
      // A second search in a row without decrease: g varies more than its gradient says at
      // every step tried (a PFEM response jumps where a remeshing decision changes), so the
      // point cannot be refined; stop rather than creep with ever smaller steps.
      if (stalled) {
        out.message = "the line search found no decrease of the merit function (none beyond 1/1024 of the "
                      "HL-RF step) at iterations " +
                      std::to_string(k - 1) + " and " + std::to_string(k) +
                      " (g is not smooth at this scale); the tolerance is tighter than g allows";
        return out;
      }
      // Take the smallest step tried: the merit function is flat to rounding here.
    }
    stalled = !accepted;
    out.u = u_new;
    g = g_new;
    grad = grad_new;
  }
}

}  // namespace pfem::reliability::detail
