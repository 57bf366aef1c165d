#include "engine/analysis/functional.h"

#include <algorithm>
#include <cmath>

namespace pfem {
namespace {

// The row of the sensitivity histories recorded at responses.time[row]. Both histories are
// sampled at the same steps, so the row index normally matches; the time decides otherwise.
std::size_t sensitivity_row(const Histories& responses, const Histories& sensitivities,
                            std::size_t row) {
  const double t = responses.time[row];
  if (row < sensitivities.time.size() && sensitivities.time[row] == t) return row;
  const auto it = std::find(sensitivities.time.begin(), sensitivities.time.end(), t);
  if (it == sensitivities.time.end()) {
    throw FunctionalError("sensitivities",
                          "no sensitivity sample at t = " + std::to_string(t));
  }
  return static_cast<std::size_t>(it - sensitivities.time.begin());
}

}  // namespace

FunctionalValue evaluate_functional(const Histories& responses, const Histories& sensitivities,
                                    std::span<const std::string> params,
                                    const FunctionalSpec& spec) {
  if (auto bad = check_functional_window(spec)) throw FunctionalError(bad->first, bad->second);
  const int col = responses.column(spec.recorder);
  if (col < 0) throw FunctionalError("recorder", "no recorder '" + spec.recorder + "'");
  const std::size_t n = responses.time.size();
  if (n == 0 || responses.rows.size() != n) {
    throw FunctionalError("recorder", "the run recorded no samples");
  }
  std::vector<int> sens_cols;
  for (const auto& p : params) {
    const std::string name = "d" + spec.recorder + "/d" + p;
    const int c = sensitivities.column(name);
    if (c < 0) throw FunctionalError("sensitivities", "no sensitivity column '" + name + "'");
    sens_cols.push_back(c);
  }
  const auto value = [&](std::size_t row) { return responses.rows[row][col]; };
  const auto gradient_at = [&](std::size_t row, double sign) {
    std::vector<double> g;
    if (sens_cols.empty()) return g;
    const auto& srow = sensitivities.rows[sensitivity_row(responses, sensitivities, row)];
    for (int c : sens_cols) g.push_back(sign * srow[c]);
    return g;
  };

  FunctionalValue out;
  switch (spec.kind) {
    case FunctionalKind::kFinal: {
      out.value = value(n - 1);
      out.time = responses.time[n - 1];
      out.gradient = gradient_at(n - 1, 1.0);
      return out;
    }
    case FunctionalKind::kMax:
    case FunctionalKind::kMin:
    case FunctionalKind::kMaxAbs: {
      const double tol = 1e-9 * std::max(1.0, std::abs(responses.time.back()));
      const auto in_window = [&](std::size_t row) {
        const double t = responses.time[row];
        return (!spec.window_start || t >= *spec.window_start - tol) &&
               (!spec.window_end || t <= *spec.window_end + tol);
      };
      std::size_t best = n;
      const auto key = [&](std::size_t row) {
        const double v = value(row);
        return spec.kind == FunctionalKind::kMax   ? v
               : spec.kind == FunctionalKind::kMin ? -v
                                                   : std::abs(v);
      };
      for (std::size_t i = 0; i < n; ++i) {
        if (in_window(i) && (best == n || key(i) > key(best))) best = i;
      }
      if (best == n) {
        throw FunctionalError(spec.window_start ? "window_start" : "window_end",
                              "no recorded sample in the window (recorded times [" +
                                  std::to_string(responses.time.front()) + ", " +
                                  std::to_string(responses.time.back()) + "])");
      }
      const double v = value(best);
      const double sign = (spec.kind == FunctionalKind::kMaxAbs && v < 0.0) ? -1.0 : 1.0;
      out.value = spec.kind == FunctionalKind::kMaxAbs ? std::abs(v) : v;
      out.time = responses.time[best];
      out.gradient = gradient_at(best, sign);
      return out;
    }
    case FunctionalKind::kValueAt: {
      const double t = spec.time;
      const auto& time = responses.time;
      const double tol = 1e-9 * std::max(1.0, std::abs(time.back()));
      if (!std::isfinite(t) || t < time.front() - tol || t > time.back() + tol) {
        throw FunctionalError("time", "must be within the recorded times [" +
                                          std::to_string(time.front()) + ", " +
                                          std::to_string(time.back()) + "]");
      }
      out.time = t;
      // An exact (or within-tolerance) sample is taken as it is.
      for (std::size_t i = 0; i < n; ++i) {
        if (std::abs(time[i] - t) <= tol) {
          out.value = value(i);
          out.gradient = gradient_at(i, 1.0);
          return out;
        }
      }
      const auto upper = std::upper_bound(time.begin(), time.end(), t);
      const std::size_t j = static_cast<std::size_t>(upper - time.begin());
      const std::size_t i = j - 1;
      const double w = (t - time[i]) / (time[j] - time[i]);
      out.value = (1.0 - w) * value(i) + w * value(j);
      const auto gi = gradient_at(i, 1.0);
      const auto gj = gradient_at(j, 1.0);
      out.gradient.resize(gi.size());
      for (std::size_t k = 0; k < gi.size(); ++k) out.gradient[k] = (1.0 - w) * gi[k] + w * gj[k];
      return out;
    }
  }
  throw FunctionalError("kind", "unknown functional kind");
}

std::optional<std::pair<std::string, std::string>> check_functional_window(
    const FunctionalSpec& spec) {
  const bool extreme = spec.kind == FunctionalKind::kMax || spec.kind == FunctionalKind::kMin ||
                       spec.kind == FunctionalKind::kMaxAbs;
  for (const auto& [field, bound] : {std::pair{"window_start", spec.window_start},
                                     std::pair{"window_end", spec.window_end}}) {
    if (!bound) continue;
    if (!extreme) return std::pair{field, std::string("only used with max, min and max_abs")};
    if (!std::isfinite(*bound)) return std::pair{field, std::string("must be finite")};
  }
  if (spec.window_start && spec.window_end && *spec.window_end < *spec.window_start) {
    return std::pair{std::string("window_end"), std::string("must be >= window_start")};
  }
  return std::nullopt;
}

std::optional<FunctionalKind> parse_functional_kind(std::string_view name) {
  if (name == "at" || name == "value_at") return FunctionalKind::kValueAt;
  if (name == "max") return FunctionalKind::kMax;
  if (name == "min") return FunctionalKind::kMin;
  if (name == "max_abs" || name == "absmax") return FunctionalKind::kMaxAbs;
  if (name == "final") return FunctionalKind::kFinal;
  return std::nullopt;
}

std::string functional_kind_name(FunctionalKind kind) {
  switch (kind) {
    case FunctionalKind::kValueAt: return "value_at";
    case FunctionalKind::kMax: return "max";
    case FunctionalKind::kMin: return "min";
    case FunctionalKind::kMaxAbs: return "max_abs";
    case FunctionalKind::kFinal: return "final";
  }
  return "unknown";
}

}  // namespace pfem
