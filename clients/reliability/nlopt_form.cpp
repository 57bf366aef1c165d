// The design point as an NLopt problem: min ||u||^2 / 2 s.t. G(u) / |G(u0)| = 0, by
// LD_SLSQP (with gradients) or LN_COBYLA (without).
#include <cmath>
#include <exception>
#include <string>
#include <vector>

#include <nlopt.hpp>

#include "clients/reliability/form_search.h"

namespace pfem::reliability::detail {

namespace {

struct Context {
  StandardSpaceFunction* G;
  double g_scale;
  const FormOptions* options;
  int calls = 0;
  std::exception_ptr error;
};

double objective(const std::vector<double>& u, std::vector<double>& grad, void*) {
  double f = 0.0;
  for (std::size_t i = 0; i < u.size(); ++i) {
    f += 0.5 * u[i] * u[i];
    if (!grad.empty()) grad[i] = u[i];
  }
  return f;
}

double constraint(const std::vector<double>& u, std::vector<double>& grad, void* data) {
  auto* ctx = static_cast<Context*>(data);
  try {
    const Eigen::VectorXd uu = Eigen::Map<const Eigen::VectorXd>(u.data(), u.size());
    double g;
    if (grad.empty()) {
      g = ctx->G->value(uu);
    } else {
      Eigen::VectorXd gu;
      g = ctx->G->value_and_gradient(uu, gu);
      for (std::size_t i = 0; i < u.size(); ++i) grad[i] = gu(i) / ctx->g_scale;
    }
    ++ctx->calls;
    if (ctx->options->progress) {
      ctx->options->progress({ctx->calls, uu.norm(), g, 1.0, ctx->G->evaluations()});
    }
    return g / ctx->g_scale;
  } catch (...) {
    ctx->error = std::current_exception();
    throw nlopt::forced_stop();
  }
}

std::string describe(nlopt::result r) {
  switch (r) {
    case nlopt::SUCCESS: return "success";
    case nlopt::STOPVAL_REACHED: return "stop value reached";
    case nlopt::FTOL_REACHED: return "function tolerance reached";
    case nlopt::XTOL_REACHED: return "step tolerance reached";
    case nlopt::MAXEVAL_REACHED: return "evaluation limit reached";
    case nlopt::MAXTIME_REACHED: return "time limit reached";
    default: return "stopped (code " + std::to_string(static_cast<int>(r)) + ")";
  }
}

}  // namespace

SearchOutcome search_nlopt(StandardSpaceFunction& G, const Eigen::VectorXd& u0,
                           const FormOptions& options) {
  SearchOutcome out;
  const int n = G.size();
  const double g0 = G.value(u0);
  if (!std::isfinite(g0)) {
    out.u = u0;
    out.message = "g is not finite at the start point";
    return out;
  }
  Context ctx{&G, std::abs(g0) > 0 && std::isfinite(g0) ? std::abs(g0) : 1.0, &options, 0, nullptr};
  const bool slsqp = options.method == FormMethod::kSlsqp;
  nlopt::opt opt(slsqp ? nlopt::LD_SLSQP : nlopt::LN_COBYLA, static_cast<unsigned>(n));
  opt.set_min_objective(objective, nullptr);
  opt.add_equality_constraint(constraint, &ctx, 0.1 * options.tolerance);
  opt.set_xtol_rel(0.1 * options.tolerance);
  opt.set_xtol_abs(0.1 * options.tolerance);
  opt.set_maxeval(50 * options.max_iterations);
  if (!slsqp) opt.set_initial_step(0.5);
  std::vector<double> u(u0.data(), u0.data() + n);
  double fmin = 0.0;
  std::string how;
  try {
    how = describe(opt.optimize(u, fmin));
  } catch (const nlopt::forced_stop&) {
    if (ctx.error) std::rethrow_exception(ctx.error);
    how = "forced stop";
  } catch (const nlopt::roundoff_limited&) {
    how = "round-off limited";
  } catch (const std::exception& e) {
    if (ctx.error) std::rethrow_exception(ctx.error);
    how = std::string("failed: ") + e.what();
  }
  out.u = Eigen::Map<const Eigen::VectorXd>(u.data(), n);
  out.iterations = opt.get_numevals();
  out.g = G.value_and_gradient(out.u, out.gradient);
  out.has_gradient = true;
  // The optimiser's own stopping rule is not the design-point condition: check that too.
  // The objective is flat along the surface near u*, so the optimisers stop with the
  // alignment of u and alpha only ~sqrt of what beta has; allow 100x the tolerance there
  // (beta is then still accurate to about the tolerance squared).
  out.converged = design_point_converged(out.u, out.g, out.gradient, ctx.g_scale,
                                         options.tolerance, 100 * options.tolerance);
  out.message = std::string(slsqp ? "SLSQP " : "COBYLA ") + how +
                (out.converged ? "; design-point condition met"
                               : "; design-point condition NOT met");
  return out;
}

}  // namespace pfem::reliability::detail
