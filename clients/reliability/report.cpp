#include "clients/reliability/report.h"

#include "clients/reliability/json_writer.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <vector>

namespace pfem::reliability {

namespace {

void named_values(JsonWriter& w, const std::string& k, const std::vector<std::string>& names,
                  const Eigen::VectorXd& values) {
  w.key(k).begin_object();
  for (std::size_t i = 0; i < names.size(); ++i) {
    w.field(names[i], static_cast<Eigen::Index>(i) < values.size() ? values(i) : NAN);
  }
  w.end_object();
}

void sampling(JsonWriter& w, const std::string& k, const SamplingResult& s, std::uint64_t seed) {
  w.key(k).begin_object();
  w.field("samples", static_cast<long long>(s.samples));
  w.field("failures", static_cast<long long>(s.failures));
  w.field("pf", s.pf).field("cov", s.cov).field("beta", s.beta);
  w.field("seed", static_cast<long long>(seed));
  w.end_object();
}

}  // namespace

std::string time_window_text(std::optional<double> start, std::optional<double> end) {
  if (!start && !end) return "";
  std::string text = ", ";
  if (start) text += JsonWriter::number(*start) + " <= ";
  text += "t";
  if (end) text += " <= " + JsonWriter::number(*end);
  return text;
}

namespace {

std::string limit_state_text(const Problem& problem) {
  if (problem.limit_state_kind != LimitStateKind::kModel) return "expression limit state";
  const auto& m = problem.message.limit_state().model();
  std::string text = "model limit state g = " + JsonWriter::number(m.threshold()) + " - " +
                     m.functional() + "(" + m.recorder();
  if (m.functional() == "at_time") text += ", t = " + JsonWriter::number(m.time());
  text += time_window_text(m.has_window_start() ? std::optional(m.window_start()) : std::nullopt,
                           m.has_window_end() ? std::optional(m.window_end()) : std::nullopt);
  return text + ")";
}

std::string fmt(const char* format, double v) {
  if (!std::isfinite(v)) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

}  // namespace

std::string result_json(const Problem& problem, const AnalysisResult& result,
                        const AnalysisOptions& options) {
  const FormResult& f = result.form;
  const auto& names = problem.names;
  JsonWriter w;
  w.begin_object();
  w.field("problem", problem.name).field("description", problem.description);
  w.field("method", std::string(to_string(f.method)));
  w.field("converged", f.converged).field("message", f.message);
  w.field("beta", f.beta).field("pf", f.pf).field("beta_resolution", f.beta_resolution);
  w.field("iterations", f.iterations).field("evaluations", f.evaluations);
  w.field("gradient_evaluations", f.gradient_evaluations);
  w.field("gradient_source", f.gradient_source);
  w.field("g_at_design_point", f.g);
  w.key("variables").begin_array();
  for (std::size_t i = 0; i < names.size(); ++i) {
    const Distribution& d = problem.marginals[i];
    w.begin_object();
    w.field("name", names[i]).field("distribution", std::string(to_string(d.kind())));
    w.field("mean", d.mean()).field("stddev", d.stddev());
    w.key("parameters").begin_object();
    for (const auto& [k, v] : d.parameters()) w.field(k, v);
    w.end_object();
    w.end_object();
  }
  w.end_array();
  w.key("design_point").begin_object();
  named_values(w, "x", names, f.x);
  named_values(w, "u", names, f.u);
  w.end_object();
  named_values(w, "alpha", names, f.alpha);
  named_values(w, "importance_factors", names, f.alpha.cwiseAbs2());
  named_values(w, "gamma", names, f.gamma);
  if (!result.sensitivities.empty()) {
    w.key("sensitivities").begin_object();
    for (std::size_t i = 0; i < names.size(); ++i) {
      const auto& s = result.sensitivities[i];
      w.key(names[i]).begin_object();
      w.field("dbeta_dmean", s.dbeta_dmean).field("dbeta_dstddev", s.dbeta_dstddev);
      w.field("dpf_dmean", s.dpf_dmean).field("dpf_dstddev", s.dpf_dstddev);
      w.end_object();
    }
    w.end_object();
  }
  if (result.sorm) {
    const SormResult& s = *result.sorm;
    w.key("sorm").begin_object();
    w.field("valid", s.valid).field("message", s.message);
    w.numbers("curvatures", s.curvatures);
    w.field("evaluations", s.evaluations);
    w.key("breitung").begin_object().field("pf", s.pf_breitung).field("beta", s.beta_breitung).end_object();
    w.key("hohenbichler_rackwitz").begin_object();
    w.field("pf", s.pf_hohenbichler_rackwitz).field("beta", s.beta_hohenbichler_rackwitz);
    w.end_object();
    w.key("tvedt").begin_object().field("pf", s.pf_tvedt).field("beta", s.beta_tvedt).end_object();
    w.end_object();
  }
  if (result.importance_sampling) {
    sampling(w, "importance_sampling", *result.importance_sampling, options.seed);
  }
  if (result.monte_carlo) sampling(w, "monte_carlo", *result.monte_carlo, options.seed);
  if (result.subset_simulation) {
    const SubsetResult& s = *result.subset_simulation;
    w.key("subset_simulation").begin_object();
    w.field("converged", s.converged).field("message", s.message);
    w.field("samples_per_level", static_cast<long long>(options.subset_simulation));
    w.field("pf", s.pf).field("cov", s.cov).field("beta", s.beta);
    w.field("evaluations", static_cast<long long>(s.evaluations));
    w.field("seed", static_cast<long long>(options.seed));
    w.key("levels").begin_array();
    for (const auto& l : s.levels) {
      w.begin_object().field("threshold", l.threshold).field("probability", l.probability);
      w.field("acceptance", l.acceptance).field("gamma", l.gamma).end_object();
    }
    w.end_array();
    w.end_object();
  }
  if (result.simulations) {
    const SimulationStats& s = *result.simulations;
    w.key("simulations").begin_object();
    w.field("evaluations", s.evaluations).field("gradient_evaluations", s.gradient_evaluations);
    w.field("runs", s.simulations).field("cached", s.cached).field("retries", s.retries);
    w.field("seconds", s.seconds).field("concurrency", options.concurrency);
    w.end_object();
  }
  w.field("wall_seconds", result.wall_seconds);
  w.end_object();
  return w.take();
}

std::string summary_text(const Problem& problem, const AnalysisResult& result,
                         const AnalysisOptions& options) {
  const FormResult& f = result.form;
  std::ostringstream out;
  out << "pfem-form: " << (problem.name.empty() ? "(unnamed problem)" : problem.name) << " - "
      << problem.names.size() << " variables, " << limit_state_text(problem) << ", method "
      << to_string(f.method) << "\n";
  out << "FORM  " << (f.converged ? "converged" : "NOT CONVERGED") << " after " << f.iterations
      << " iterations, " << f.evaluations << " evaluations of g (gradients: " << f.gradient_source
      << ")\n";
  if (!f.converged || f.beta_resolution > 0) out << "      " << f.message << "\n";
  if (result.simulations) {
    const SimulationStats& s = *result.simulations;
    // The model's evaluations include those made after FORM (SORM's curvatures, sampling).
    out << "      " << s.simulations << " PFEM simulations for " << s.evaluations << " evaluations of the model (";
    if (s.evaluations > f.evaluations)
      out << f.evaluations << " by FORM, " << s.evaluations - f.evaluations << " after it by SORM or sampling; ";
    out << s.gradient_evaluations << " with gradients";
    if (s.cached > 0) out << ", " << s.cached << " answered from the server's cache";
    if (s.retries > 0) out << ", " << s.retries << " calls retried after UNAVAILABLE";
    out << "), " << fmt("%.1f", s.seconds) << " s in the simulations\n";
  }
  if (!std::isfinite(f.beta)) {
    out << "      no design point: beta and pf are undefined\n";
    return out.str();
  }
  out << "      beta = " << fmt("%.6g", f.beta);
  if (f.beta_resolution > 0) out << " (to about " << fmt("%.2g", f.beta_resolution) << ")";
  out << "   pf = " << fmt("%.6e", f.pf) << "\n\n";
  char line[256];
  std::snprintf(line, sizeof line, "  %-10s %-16s %11s %11s %12s %9s %8s %12s %12s\n", "variable",
                "distribution", "mean", "stddev", "x*", "u*", "alpha", "dbeta/dmean",
                "dbeta/dsd");
  out << line;
  for (std::size_t i = 0; i < problem.names.size(); ++i) {
    const Distribution& d = problem.marginals[i];
    const bool has_s = i < result.sensitivities.size();
    std::snprintf(line, sizeof line, "  %-10s %-16s %11s %11s %12s %9s %8s %12s %12s\n",
                  problem.names[i].c_str(), std::string(to_string(d.kind())).c_str(),
                  fmt("%.5g", d.mean()).c_str(), fmt("%.5g", d.stddev()).c_str(),
                  fmt("%.6g", f.x(i)).c_str(), fmt("%.4f", f.u(i)).c_str(),
                  fmt("%.4f", f.alpha(i)).c_str(),
                  has_s ? fmt("%.4e", result.sensitivities[i].dbeta_dmean).c_str() : "-",
                  has_s ? fmt("%.4e", result.sensitivities[i].dbeta_dstddev).c_str() : "-");
    out << line;
  }
  if (result.sorm) {
    const SormResult& s = *result.sorm;
    out << "\nSORM  curvatures:";
    for (double k : s.curvatures) out << " " << fmt("%.4g", k);
    out << "\n";
    if (!s.valid) out << "      " << s.message << "\n";
    out << "      Breitung               pf = " << fmt("%.6e", s.pf_breitung)
        << "   beta = " << fmt("%.6g", s.beta_breitung) << "\n";
    out << "      Hohenbichler-Rackwitz  pf = " << fmt("%.6e", s.pf_hohenbichler_rackwitz)
        << "   beta = " << fmt("%.6g", s.beta_hohenbichler_rackwitz) << "\n";
    out << "      Tvedt                  pf = " << fmt("%.6e", s.pf_tvedt)
        << "   beta = " << fmt("%.6g", s.beta_tvedt) << "\n";
  }
  const auto sampled = [&](const char* label, const SamplingResult& s) {
    out << label << s.samples << " samples (seed " << options.seed << "): pf = "
        << fmt("%.6e", s.pf) << "   c.o.v. = " << fmt("%.4f", s.cov)
        << "   beta = " << fmt("%.6g", s.beta) << "\n";
  };
  if (result.importance_sampling || result.monte_carlo || result.subset_simulation) out << "\n";
  if (result.importance_sampling) sampled("IS    ", *result.importance_sampling);
  if (result.monte_carlo) sampled("MC    ", *result.monte_carlo);
  if (result.subset_simulation) {
    const SubsetResult& s = *result.subset_simulation;
    out << "SuS   " << options.subset_simulation << " samples x " << s.levels.size()
        << " levels (seed " << options.seed << "): pf = " << fmt("%.6e", s.pf)
        << "   c.o.v. = " << fmt("%.4f", s.cov) << "   beta = " << fmt("%.6g", s.beta) << "\n";
    if (!s.converged) out << "      " << s.message << "\n";
  }
  return out.str();
}

}  // namespace pfem::reliability
