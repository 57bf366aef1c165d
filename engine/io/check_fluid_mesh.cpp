#include "engine/io/section_checks.h"

#include <cmath>
#include <string>

#include "engine/io/model_checks.h"
#include "engine/io/model_size.h"

namespace pfem {

bool is_incompressible(const pfem::v1::Model& model) { return model.analysis().formulation() == "incompressible"; }

void check_fluid(const pfem::v1::Model& model, FieldChecker& out) {
  if (!model.has_fluid()) return out.error("fluid", "is required (rho, mu, kappa)");
  out.positive("fluid.rho", model.fluid().rho());
  out.non_negative("fluid.mu", model.fluid().mu());
  if (!is_incompressible(model)) out.positive("fluid.kappa", model.fluid().kappa());  // else a warning if set
}

void check_mesh(const pfem::v1::Model& model, FieldChecker& out) {
  if (!model.has_mesh()) return out.error("mesh", "is required (h, alpha)");
  out.positive("mesh.h", model.mesh().h());
  if (const long particles = estimate_particles(model); particles > kMaxParticles)
    out.error("mesh.h", "gives about " + std::to_string(particles) + " fluid particles, more than the " +
                            std::to_string(kMaxParticles) + " a run may take");
  if (const long nodes = count_wall_nodes(model); nodes > kMaxWallNodes)
    out.error("mesh.h", "gives " + std::to_string(nodes) + " wall nodes (wall length / mesh.h), more than the " +
                            std::to_string(kMaxWallNodes) + " a model may have");
  if (model.mesh().has_alpha()) {
    const double a = model.mesh().alpha();
    if (!std::isfinite(a) || a < 0.8 || a > 3.0) out.error("mesh.alpha", "must be in [0.8, 3]");
  }
  if (model.mesh().has_removal_distance()) {
    const double d = model.mesh().removal_distance();
    if (!std::isfinite(d) || d < 0.0 || d > 0.5) out.error("mesh.removal_distance", "must be in [0, 0.5]");
  }
  const auto& m = model.mesh();
  if (m.has_insertion_length())
    out.zero_or_within("mesh.insertion_length", m.insertion_length(), 1.5, 3.0, "must be 0 (off) or in [1.5, 3]");
  if (m.has_interior_insertion_length())
    out.zero_or_within("mesh.interior_insertion_length", m.interior_insertion_length(), 1.5, 3.0,
                       "must be 0 (same as insertion_length) or in [1.5, 3]");
  if (m.has_boundary_alpha())
    out.zero_or_within("mesh.boundary_alpha", m.boundary_alpha(), 0.6, 3.0, "must be 0 (same as alpha) or in [0.6, 3]");
  if (m.has_volume_relaxation_steps())
    out.zero_or_within("mesh.volume_relaxation_steps", m.volume_relaxation_steps(), 1.0, 1000.0,
                       "must be 0 (off) or in [1, 1000]");
}

void check_analysis(const pfem::v1::Model& model, FieldChecker& out) {
  if (!model.has_analysis()) return out.error("analysis", "is required (dt, t_end)");
  const auto& a = model.analysis();
  out.positive("analysis.dt", a.dt());
  out.positive("analysis.t_end", a.t_end());
  if (std::isfinite(a.dt()) && std::isfinite(a.t_end()) && a.dt() > a.t_end())
    out.error("analysis.dt", "must not exceed analysis.t_end");
  if (const std::string why = too_many_steps(a.t_end(), a.dt(), "analysis.dt"); !why.empty())
    out.error("analysis.t_end", why);
  if (a.has_newton_tolerance()) {
    const double tol = a.newton_tolerance();
    if (!std::isfinite(tol) || tol <= 0 || tol >= 1) out.error("analysis.newton_tolerance", "must be in (0, 1)");
  }
  if (a.has_newton_max_iterations() && a.newton_max_iterations() < 1)
    out.error("analysis.newton_max_iterations", "must be >= 1");
  if (a.has_record_every() && a.record_every() < 1) out.error("analysis.record_every", "must be >= 1");
  if (a.has_vtk_every() && a.vtk_every() < 1) out.error("analysis.vtk_every", "must be >= 1");
  if (a.has_solver() && a.solver() != "condensed-bubble" && a.solver() != "unified-fractional-step")
    out.error("analysis.solver",
              "unknown solver '" + a.solver() + "'; expected condensed-bubble or unified-fractional-step");
  if (a.has_formulation() && a.formulation() != "quasi-incompressible" && a.formulation() != "incompressible")
    out.error("analysis.formulation", "must be quasi-incompressible or incompressible (got '" + a.formulation() + "')");
  else if (is_incompressible(model) && a.has_solver())
    out.error("analysis.solver",
              "solves the quasi-incompressible Newton system; the incompressible formulation "
              "has its own fractional step (leave analysis.solver out)");
}

}  // namespace pfem
