#include "clients/reliability/distributions.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include <boost/math/constants/constants.hpp>
#include <boost/math/distributions/beta.hpp>
#include <boost/math/distributions/exponential.hpp>
#include <boost/math/distributions/extreme_value.hpp>
#include <boost/math/distributions/gamma.hpp>
#include <boost/math/distributions/lognormal.hpp>
#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/uniform.hpp>
#include <boost/math/distributions/weibull.hpp>
#include <boost/math/special_functions/gamma.hpp>
#include <boost/math/tools/roots.hpp>

namespace pfem::reliability {

namespace bm = boost::math;

namespace {

// Overflow (a quantile at p = 0 or 1) gives +-infinity instead of throwing, and an inverse
// that does not converge in the far tails (p ~ 1e-300) returns its last iterate; no promotion
// of double to long double (speed; the accuracy of double is what the transform needs).
using Policy = bm::policies::policy<bm::policies::overflow_error<bm::policies::ignore_error>,
                                    bm::policies::evaluation_error<bm::policies::ignore_error>,
                                    bm::policies::promote_double<false>>;
using Normal = bm::normal_distribution<double, Policy>;
using Lognormal = bm::lognormal_distribution<double, Policy>;
using Uniform = bm::uniform_distribution<double, Policy>;
using Gumbel = bm::extreme_value_distribution<double, Policy>;
using Weibull = bm::weibull_distribution<double, Policy>;
using Gamma = bm::gamma_distribution<double, Policy>;
using Exponential = bm::exponential_distribution<double, Policy>;
using Beta = bm::beta_distribution<double, Policy>;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kZMax = 35.0;  // Phi(-35) ~ 1e-268: far tails without denormal probabilities

constexpr std::array<std::pair<DistributionKind, std::string_view>, 10> kNames{{
    {DistributionKind::kNormal, "normal"},
    {DistributionKind::kLognormal, "lognormal"},
    {DistributionKind::kUniform, "uniform"},
    {DistributionKind::kGumbel, "gumbel"},
    {DistributionKind::kFrechet, "frechet"},
    {DistributionKind::kWeibull, "weibull"},
    {DistributionKind::kGamma, "gamma"},
    {DistributionKind::kExponential, "exponential"},
    {DistributionKind::kBeta, "beta"},
    {DistributionKind::kTruncatedNormal, "truncated_normal"},
}};

void require(bool ok, const char* message) {
  if (!ok) throw std::invalid_argument(message);
}
bool finite(double v) { return std::isfinite(v); }

// Truncated normal helpers: the parent N(mu, sigma) restricted to [a, b].
struct TruncatedMoments {
  double mean;
  double stddev;
};
TruncatedMoments truncated_moments(double mu, double sigma, double a, double b) {
  const double alpha = (a - mu) / sigma;
  const double beta = (b - mu) / sigma;
  const double pa = standard_normal_pdf(alpha);
  const double pb = standard_normal_pdf(beta);
  // Z from the tail that keeps its digits.
  const double z = alpha > 0 ? standard_normal_cdf(-alpha) - standard_normal_cdf(-beta)
                             : standard_normal_cdf(beta) - standard_normal_cdf(alpha);
  const double ta = finite(alpha) ? alpha * pa : 0.0;
  const double tb = finite(beta) ? beta * pb : 0.0;
  const double d = (pa - pb) / z;
  const double var = sigma * sigma * (1.0 + (ta - tb) / z - d * d);
  return {mu + sigma * d, std::sqrt(std::max(var, 0.0))};
}

// Solves cov(shape) = target for a family whose squared coefficient of variation is
// exp(h(shape)) - 1 with h decreasing in shape, on [lo, hi].
template <class H>
double solve_shape(H h, double cov, double lo, double hi, const char* range_message) {
  const double target = std::log1p(cov * cov);
  auto f = [&](double k) { return h(k) - target; };
  const double flo = f(lo);
  const double fhi = f(hi);
  if (!(flo > 0 && fhi < 0)) throw std::invalid_argument(range_message);
  std::uintmax_t iterations = 200;
  const auto r = bm::tools::toms748_solve(f, lo, hi, flo, fhi, bm::tools::eps_tolerance<double>(50),
                                          iterations);
  return 0.5 * (r.first + r.second);
}

}  // namespace

std::optional<DistributionKind> parse_distribution_kind(std::string_view name) {
  for (const auto& [kind, n] : kNames) {
    if (n == name) return kind;
  }
  return std::nullopt;
}

std::string_view to_string(DistributionKind kind) {
  for (const auto& [k, n] : kNames) {
    if (k == kind) return n;
  }
  return "unknown";
}

std::string distribution_names() {
  std::string out;
  for (const auto& entry : kNames) {
    if (!out.empty()) out += ", ";
    out += entry.second;
  }
  return out;
}

double standard_normal_cdf(double z) { return bm::cdf(Normal(0.0, 1.0), z); }
double standard_normal_pdf(double z) {
  if (!finite(z)) return 0.0;
  return bm::pdf(Normal(0.0, 1.0), z);
}
double standard_normal_quantile(double p) {
  if (p <= 0.0) return -kInf;
  if (p >= 1.0) return kInf;
  return bm::quantile(Normal(0.0, 1.0), p);
}

Distribution::Distribution(DistributionKind kind, double p0, double p1, double p2, double p3)
    : kind_(kind), p_{p0, p1, p2, p3} {}

Distribution Distribution::normal(double mean, double stddev) {
  require(finite(mean), "mean: must be finite");
  require(finite(stddev) && stddev > 0, "stddev: must be > 0");
  return {DistributionKind::kNormal, mean, stddev};
}

Distribution Distribution::lognormal(double lambda, double zeta) {
  require(finite(lambda), "lambda: must be finite");
  require(finite(zeta) && zeta > 0, "zeta: must be > 0");
  return {DistributionKind::kLognormal, lambda, zeta};
}

Distribution Distribution::uniform(double lower, double upper) {
  require(finite(lower), "lower: must be finite");
  require(finite(upper) && upper > lower, "upper: must be > lower");
  return {DistributionKind::kUniform, lower, upper};
}

Distribution Distribution::gumbel(double location, double scale) {
  require(finite(location), "location: must be finite");
  require(finite(scale) && scale > 0, "scale: must be > 0");
  return {DistributionKind::kGumbel, location, scale};
}

Distribution Distribution::frechet(double scale, double shape) {
  require(finite(scale) && scale > 0, "scale: must be > 0");
  require(finite(shape) && shape > 0, "shape: must be > 0");
  return {DistributionKind::kFrechet, scale, shape};
}

Distribution Distribution::weibull(double scale, double shape) {
  require(finite(scale) && scale > 0, "scale: must be > 0");
  require(finite(shape) && shape > 0, "shape: must be > 0");
  return {DistributionKind::kWeibull, scale, shape};
}

Distribution Distribution::gamma(double shape, double scale) {
  require(finite(shape) && shape > 0, "shape: must be > 0");
  require(finite(scale) && scale > 0, "scale: must be > 0");
  return {DistributionKind::kGamma, shape, scale};
}

Distribution Distribution::exponential(double rate, double lower) {
  require(finite(rate) && rate > 0, "rate: must be > 0");
  require(finite(lower), "lower: must be finite");
  return {DistributionKind::kExponential, rate, lower};
}

Distribution Distribution::beta(double shape_a, double shape_b, double lower, double upper) {
  require(finite(shape_a) && shape_a > 0, "shape_a: must be > 0");
  require(finite(shape_b) && shape_b > 0, "shape_b: must be > 0");
  require(finite(lower), "lower: must be finite");
  require(finite(upper) && upper > lower, "upper: must be > lower");
  return {DistributionKind::kBeta, shape_a, shape_b, lower, upper};
}

Distribution Distribution::truncated_normal(double location, double scale, double lower,
                                            double upper) {
  require(finite(location), "location: must be finite");
  require(finite(scale) && scale > 0, "scale: must be > 0");
  require(!std::isnan(lower) && lower < kInf, "lower: must be a number below +infinity");
  require(!std::isnan(upper) && upper > lower, "upper: must be > lower");
  const double alpha = (lower - location) / scale;
  const double beta = (upper - location) / scale;
  require(std::min(std::abs(alpha), std::abs(beta)) < kZMax || alpha * beta <= 0,
          "lower: the bounds leave no probability mass");
  return {DistributionKind::kTruncatedNormal, location, scale, lower, upper};
}

Distribution Distribution::from_moments(DistributionKind kind, double mean, double stddev,
                                        double lower, double upper) {
  require(finite(mean), "mean: must be finite");
  require(finite(stddev) && stddev > 0, "stddev: must be > 0");
  const double cov = stddev / std::abs(mean);
  switch (kind) {
    case DistributionKind::kNormal:
      return normal(mean, stddev);
    case DistributionKind::kLognormal: {
      require(mean > 0, "mean: must be > 0 for a lognormal variable");
      const double zeta2 = std::log1p(cov * cov);
      return lognormal(std::log(mean) - 0.5 * zeta2, std::sqrt(zeta2));
    }
    case DistributionKind::kUniform: {
      const double half = std::sqrt(3.0) * stddev;
      return uniform(mean - half, mean + half);
    }
    case DistributionKind::kGumbel: {
      const double scale = stddev * std::sqrt(6.0) / bm::constants::pi<double>();
      return gumbel(mean - bm::constants::euler<double>() * scale, scale);
    }
    case DistributionKind::kFrechet: {
      require(mean > 0, "mean: must be > 0 for a frechet variable");
      auto h = [](double k) { return bm::lgamma(1.0 - 2.0 / k) - 2.0 * bm::lgamma(1.0 - 1.0 / k); };
      const double k = solve_shape(h, cov, 2.0 + 1e-9, 1e4,
                                   "stddev: no frechet distribution has this coefficient of variation");
      return frechet(mean / bm::tgamma(1.0 - 1.0 / k), k);
    }
    case DistributionKind::kWeibull: {
      require(mean > 0, "mean: must be > 0 for a weibull variable");
      auto h = [](double k) { return bm::lgamma(1.0 + 2.0 / k) - 2.0 * bm::lgamma(1.0 + 1.0 / k); };
      const double k = solve_shape(h, cov, 0.02, 1e4,
                                   "stddev: no weibull distribution has this coefficient of variation");
      return weibull(mean / bm::tgamma(1.0 + 1.0 / k), k);
    }
    case DistributionKind::kGamma: {
      require(mean > 0, "mean: must be > 0 for a gamma variable");
      return gamma((mean / stddev) * (mean / stddev), stddev * stddev / mean);
    }
    case DistributionKind::kExponential:
      return exponential(1.0 / stddev, mean - stddev);
    case DistributionKind::kBeta: {
      require(finite(lower), "lower: must be finite");
      require(finite(upper) && upper > lower, "upper: must be > lower");
      require(mean > lower && mean < upper, "mean: must lie strictly between lower and upper");
      const double width = upper - lower;
      const double m = (mean - lower) / width;
      const double v = (stddev / width) * (stddev / width);
      require(v < m * (1.0 - m),
              "stddev: too large for a beta variable with this mean and these bounds");
      const double common = m * (1.0 - m) / v - 1.0;
      return beta(m * common, (1.0 - m) * common, lower, upper);
    }
    case DistributionKind::kTruncatedNormal: {
      require(!std::isnan(lower) && !std::isnan(upper) && upper > lower,
              "upper: must be > lower");
      require(mean > lower && mean < upper, "mean: must lie strictly between lower and upper");
      // Newton on (mu, ln sigma) so that the truncated moments match, from the parent = target.
      double mu = mean;
      double ls = std::log(stddev);
      auto residual = [&](double m_, double l_, double r[2]) {
        const auto tm = truncated_moments(m_, std::exp(l_), lower, upper);
        r[0] = (tm.mean - mean) / stddev;
        r[1] = (tm.stddev - stddev) / stddev;
      };
      double r[2];
      residual(mu, ls, r);
      for (int it = 0; it < 200 && std::hypot(r[0], r[1]) > 1e-13; ++it) {
        const double h = 1e-6;
        double rp[2], rm[2], J[2][2];
        residual(mu + h * stddev, ls, rp);
        residual(mu - h * stddev, ls, rm);
        J[0][0] = (rp[0] - rm[0]) / (2 * h * stddev);
        J[1][0] = (rp[1] - rm[1]) / (2 * h * stddev);
        residual(mu, ls + h, rp);
        residual(mu, ls - h, rm);
        J[0][1] = (rp[0] - rm[0]) / (2 * h);
        J[1][1] = (rp[1] - rm[1]) / (2 * h);
        const double det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
        if (!(std::abs(det) > 0) || !finite(det)) break;
        const double dmu = -(J[1][1] * r[0] - J[0][1] * r[1]) / det;
        const double dls = -(-J[1][0] * r[0] + J[0][0] * r[1]) / det;
        double step = 1.0;
        const double norm0 = std::hypot(r[0], r[1]);
        double rn[2] = {r[0], r[1]};
        for (int ls_it = 0; ls_it < 40; ++ls_it, step *= 0.5) {
          residual(mu + step * dmu, ls + std::clamp(step * dls, -2.0, 2.0), rn);
          if (finite(rn[0]) && finite(rn[1]) && std::hypot(rn[0], rn[1]) < norm0) break;
        }
        mu += step * dmu;
        ls += std::clamp(step * dls, -2.0, 2.0);
        r[0] = rn[0];
        r[1] = rn[1];
      }
      if (!(std::hypot(r[0], r[1]) <= 1e-9)) {
        throw std::invalid_argument(
            "stddev: no truncated normal on these bounds has this mean and stddev");
      }
      return truncated_normal(mu, std::exp(ls), lower, upper);
    }
  }
  throw std::invalid_argument("distribution: unknown kind");
}

Distribution Distribution::with_moments(double mean, double stddev) const {
  switch (kind_) {
    case DistributionKind::kBeta:
    case DistributionKind::kTruncatedNormal:
      return from_moments(kind_, mean, stddev, p_[2], p_[3]);
    default:
      return from_moments(kind_, mean, stddev);
  }
}

std::pair<double, double> Distribution::support() const {
  switch (kind_) {
    case DistributionKind::kNormal:
    case DistributionKind::kGumbel:
      return {-kInf, kInf};
    case DistributionKind::kLognormal:
    case DistributionKind::kFrechet:
    case DistributionKind::kWeibull:
    case DistributionKind::kGamma:
      return {0.0, kInf};
    case DistributionKind::kUniform:
      return {p_[0], p_[1]};
    case DistributionKind::kExponential:
      return {p_[1], kInf};
    case DistributionKind::kBeta:
    case DistributionKind::kTruncatedNormal:
      return {p_[2], p_[3]};
  }
  return {-kInf, kInf};
}

double Distribution::cdf(double x) const {
  const auto [lo, hi] = support();
  if (std::isnan(x)) return x;
  if (x <= lo) return 0.0;
  if (x >= hi) return 1.0;
  switch (kind_) {
    case DistributionKind::kNormal:
      return bm::cdf(Normal(p_[0], p_[1]), x);
    case DistributionKind::kLognormal:
      return bm::cdf(Lognormal(p_[0], p_[1]), x);
    case DistributionKind::kUniform:
      return bm::cdf(Uniform(p_[0], p_[1]), x);
    case DistributionKind::kGumbel:
      return bm::cdf(Gumbel(p_[0], p_[1]), x);
    case DistributionKind::kFrechet:
      return bm::cdf(bm::complement(Weibull(p_[1], 1.0 / p_[0]), 1.0 / x));
    case DistributionKind::kWeibull:
      return bm::cdf(Weibull(p_[1], p_[0]), x);
    case DistributionKind::kGamma:
      return bm::cdf(Gamma(p_[0], p_[1]), x);
    case DistributionKind::kExponential:
      return bm::cdf(Exponential(p_[0]), x - p_[1]);
    case DistributionKind::kBeta:
      return bm::cdf(Beta(p_[0], p_[1]), (x - p_[2]) / (p_[3] - p_[2]));
    case DistributionKind::kTruncatedNormal: {
      const double a = (p_[2] - p_[0]) / p_[1];
      const double b = (p_[3] - p_[0]) / p_[1];
      const double xi = (x - p_[0]) / p_[1];
      if (a > 0) {
        const double qa = standard_normal_cdf(-a);
        return (qa - standard_normal_cdf(-xi)) / (qa - standard_normal_cdf(-b));
      }
      const double pa = standard_normal_cdf(a);
      return (standard_normal_cdf(xi) - pa) / (standard_normal_cdf(b) - pa);
    }
  }
  return std::numeric_limits<double>::quiet_NaN();
}

double Distribution::ccdf(double x) const {
  const auto [lo, hi] = support();
  if (std::isnan(x)) return x;
  if (x <= lo) return 1.0;
  if (x >= hi) return 0.0;
  switch (kind_) {
    case DistributionKind::kNormal:
      return bm::cdf(bm::complement(Normal(p_[0], p_[1]), x));
    case DistributionKind::kLognormal:
      return bm::cdf(bm::complement(Lognormal(p_[0], p_[1]), x));
    case DistributionKind::kUniform:
      return bm::cdf(bm::complement(Uniform(p_[0], p_[1]), x));
    case DistributionKind::kGumbel:
      return bm::cdf(bm::complement(Gumbel(p_[0], p_[1]), x));
    case DistributionKind::kFrechet:
      return bm::cdf(Weibull(p_[1], 1.0 / p_[0]), 1.0 / x);
    case DistributionKind::kWeibull:
      return bm::cdf(bm::complement(Weibull(p_[1], p_[0]), x));
    case DistributionKind::kGamma:
      return bm::cdf(bm::complement(Gamma(p_[0], p_[1]), x));
    case DistributionKind::kExponential:
      return bm::cdf(bm::complement(Exponential(p_[0]), x - p_[1]));
    case DistributionKind::kBeta:
      return bm::cdf(bm::complement(Beta(p_[0], p_[1]), (x - p_[2]) / (p_[3] - p_[2])));
    case DistributionKind::kTruncatedNormal: {
      const double a = (p_[2] - p_[0]) / p_[1];
      const double b = (p_[3] - p_[0]) / p_[1];
      const double xi = (x - p_[0]) / p_[1];
      if (a > 0) {
        const double qb = standard_normal_cdf(-b);
        return (standard_normal_cdf(-xi) - qb) / (standard_normal_cdf(-a) - qb);
      }
      const double pb = standard_normal_cdf(b);
      return (pb - standard_normal_cdf(xi)) / (pb - standard_normal_cdf(a));
    }
  }
  return std::numeric_limits<double>::quiet_NaN();
}

double Distribution::pdf(double x) const {
  const auto [lo, hi] = support();
  if (std::isnan(x)) return x;
  if (x < lo || x > hi) return 0.0;
  switch (kind_) {
    case DistributionKind::kNormal:
      return bm::pdf(Normal(p_[0], p_[1]), x);
    case DistributionKind::kLognormal:
      return x <= 0 ? 0.0 : bm::pdf(Lognormal(p_[0], p_[1]), x);
    case DistributionKind::kUniform:
      return bm::pdf(Uniform(p_[0], p_[1]), x);
    case DistributionKind::kGumbel:
      return bm::pdf(Gumbel(p_[0], p_[1]), x);
    case DistributionKind::kFrechet:
      return x <= 0 ? 0.0 : bm::pdf(Weibull(p_[1], 1.0 / p_[0]), 1.0 / x) / (x * x);
    case DistributionKind::kWeibull:
      return bm::pdf(Weibull(p_[1], p_[0]), x);
    case DistributionKind::kGamma:
      return bm::pdf(Gamma(p_[0], p_[1]), x);
    case DistributionKind::kExponential:
      return bm::pdf(Exponential(p_[0]), x - p_[1]);
    case DistributionKind::kBeta:
      return bm::pdf(Beta(p_[0], p_[1]), (x - p_[2]) / (p_[3] - p_[2])) / (p_[3] - p_[2]);
    case DistributionKind::kTruncatedNormal: {
      const double a = (p_[2] - p_[0]) / p_[1];
      const double b = (p_[3] - p_[0]) / p_[1];
      const double z = a > 0 ? standard_normal_cdf(-a) - standard_normal_cdf(-b)
                             : standard_normal_cdf(b) - standard_normal_cdf(a);
      return standard_normal_pdf((x - p_[0]) / p_[1]) / (p_[1] * z);
    }
  }
  return std::numeric_limits<double>::quiet_NaN();
}

double Distribution::quantile(double p) const {
  if (!(p > 0.0)) return support().first;
  if (!(p < 1.0)) return support().second;
  switch (kind_) {
    case DistributionKind::kNormal:
      return bm::quantile(Normal(p_[0], p_[1]), p);
    case DistributionKind::kLognormal:
      return bm::quantile(Lognormal(p_[0], p_[1]), p);
    case DistributionKind::kUniform:
      return bm::quantile(Uniform(p_[0], p_[1]), p);
    case DistributionKind::kGumbel:
      return bm::quantile(Gumbel(p_[0], p_[1]), p);
    case DistributionKind::kFrechet:
      return 1.0 / bm::quantile(bm::complement(Weibull(p_[1], 1.0 / p_[0]), p));
    case DistributionKind::kWeibull:
      return bm::quantile(Weibull(p_[1], p_[0]), p);
    case DistributionKind::kGamma:
      return bm::quantile(Gamma(p_[0], p_[1]), p);
    case DistributionKind::kExponential:
      return p_[1] + bm::quantile(Exponential(p_[0]), p);
    case DistributionKind::kBeta:
      return p_[2] + (p_[3] - p_[2]) * bm::quantile(Beta(p_[0], p_[1]), p);
    case DistributionKind::kTruncatedNormal: {
      const double a = (p_[2] - p_[0]) / p_[1];
      const double b = (p_[3] - p_[0]) / p_[1];
      // Lower-tail form: accurate for small p.
      const double pa = standard_normal_cdf(a);
      const double xi = standard_normal_quantile(pa + p * (standard_normal_cdf(b) - pa));
      return std::clamp(p_[0] + p_[1] * xi, p_[2], p_[3]);
    }
  }
  return std::numeric_limits<double>::quiet_NaN();
}

double Distribution::cquantile(double q) const {
  if (!(q > 0.0)) return support().second;
  if (!(q < 1.0)) return support().first;
  switch (kind_) {
    case DistributionKind::kNormal:
      return bm::quantile(bm::complement(Normal(p_[0], p_[1]), q));
    case DistributionKind::kLognormal:
      return bm::quantile(bm::complement(Lognormal(p_[0], p_[1]), q));
    case DistributionKind::kUniform:
      return bm::quantile(bm::complement(Uniform(p_[0], p_[1]), q));
    case DistributionKind::kGumbel:
      return bm::quantile(bm::complement(Gumbel(p_[0], p_[1]), q));
    case DistributionKind::kFrechet:
      return 1.0 / bm::quantile(Weibull(p_[1], 1.0 / p_[0]), q);
    case DistributionKind::kWeibull:
      return bm::quantile(bm::complement(Weibull(p_[1], p_[0]), q));
    case DistributionKind::kGamma:
      return bm::quantile(bm::complement(Gamma(p_[0], p_[1]), q));
    case DistributionKind::kExponential:
      return p_[1] + bm::quantile(bm::complement(Exponential(p_[0]), q));
    case DistributionKind::kBeta:
      return p_[2] + (p_[3] - p_[2]) * bm::quantile(bm::complement(Beta(p_[0], p_[1]), q));
    case DistributionKind::kTruncatedNormal: {
      const double a = (p_[2] - p_[0]) / p_[1];
      const double b = (p_[3] - p_[0]) / p_[1];
      // Upper-tail form: accurate for small q.
      const double qb = standard_normal_cdf(-b);
      const double xi = -standard_normal_quantile(qb + q * (standard_normal_cdf(-a) - qb));
      return std::clamp(p_[0] + p_[1] * xi, p_[2], p_[3]);
    }
  }
  return std::numeric_limits<double>::quiet_NaN();
}

double Distribution::mean() const {
  switch (kind_) {
    case DistributionKind::kNormal:
      return bm::mean(Normal(p_[0], p_[1]));
    case DistributionKind::kLognormal:
      return bm::mean(Lognormal(p_[0], p_[1]));
    case DistributionKind::kUniform:
      return bm::mean(Uniform(p_[0], p_[1]));
    case DistributionKind::kGumbel:
      return bm::mean(Gumbel(p_[0], p_[1]));
    case DistributionKind::kFrechet:
      return p_[1] > 1 ? p_[0] * bm::tgamma(1.0 - 1.0 / p_[1]) : kInf;
    case DistributionKind::kWeibull:
      return bm::mean(Weibull(p_[1], p_[0]));
    case DistributionKind::kGamma:
      return bm::mean(Gamma(p_[0], p_[1]));
    case DistributionKind::kExponential:
      return p_[1] + bm::mean(Exponential(p_[0]));
    case DistributionKind::kBeta:
      return p_[2] + (p_[3] - p_[2]) * bm::mean(Beta(p_[0], p_[1]));
    case DistributionKind::kTruncatedNormal:
      return truncated_moments(p_[0], p_[1], p_[2], p_[3]).mean;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

double Distribution::stddev() const {
  switch (kind_) {
    case DistributionKind::kNormal:
      return bm::standard_deviation(Normal(p_[0], p_[1]));
    case DistributionKind::kLognormal:
      return bm::standard_deviation(Lognormal(p_[0], p_[1]));
    case DistributionKind::kUniform:
      return bm::standard_deviation(Uniform(p_[0], p_[1]));
    case DistributionKind::kGumbel:
      return bm::standard_deviation(Gumbel(p_[0], p_[1]));
    case DistributionKind::kFrechet: {
      if (p_[1] <= 2) return kInf;
      const double g1 = bm::tgamma(1.0 - 1.0 / p_[1]);
      return p_[0] * std::sqrt(bm::tgamma(1.0 - 2.0 / p_[1]) - g1 * g1);
    }
    case DistributionKind::kWeibull:
      return bm::standard_deviation(Weibull(p_[1], p_[0]));
    case DistributionKind::kGamma:
      return bm::standard_deviation(Gamma(p_[0], p_[1]));
    case DistributionKind::kExponential:
      return bm::standard_deviation(Exponential(p_[0]));
    case DistributionKind::kBeta:
      return (p_[3] - p_[2]) * bm::standard_deviation(Beta(p_[0], p_[1]));
    case DistributionKind::kTruncatedNormal:
      return truncated_moments(p_[0], p_[1], p_[2], p_[3]).stddev;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

double Distribution::to_standard_normal(double x) const {
  const double p = cdf(x);
  double z;
  if (p < 0.5) {
    z = standard_normal_quantile(p);
  } else {
    z = -standard_normal_quantile(ccdf(x));
  }
  return std::clamp(z, -kZMax, kZMax);
}

double Distribution::from_standard_normal(double z) const {
  if (std::isnan(z)) return z;
  z = std::clamp(z, -kZMax, kZMax);
  try {
    if (z < 0) return quantile(standard_normal_cdf(z));
    return cquantile(standard_normal_cdf(-z));
  } catch (const std::exception&) {
    // Some of Boost's inverses give up in the far tails (p < ~1e-250): x is at the bound there.
    return z < 0 ? support().first : support().second;
  }
}

std::vector<std::pair<std::string, double>> Distribution::parameters() const {
  switch (kind_) {
    case DistributionKind::kNormal:
      return {{"mean", p_[0]}, {"stddev", p_[1]}};
    case DistributionKind::kLognormal:
      return {{"lambda", p_[0]}, {"zeta", p_[1]}};
    case DistributionKind::kUniform:
      return {{"lower", p_[0]}, {"upper", p_[1]}};
    case DistributionKind::kGumbel:
      return {{"location", p_[0]}, {"scale", p_[1]}};
    case DistributionKind::kFrechet:
    case DistributionKind::kWeibull:
      return {{"scale", p_[0]}, {"shape", p_[1]}};
    case DistributionKind::kGamma:
      return {{"shape", p_[0]}, {"scale", p_[1]}};
    case DistributionKind::kExponential:
      return {{"rate", p_[0]}, {"lower", p_[1]}};
    case DistributionKind::kBeta:
      return {{"shape_a", p_[0]}, {"shape_b", p_[1]}, {"lower", p_[2]}, {"upper", p_[3]}};
    case DistributionKind::kTruncatedNormal:
      return {{"location", p_[0]}, {"scale", p_[1]}, {"lower", p_[2]}, {"upper", p_[3]}};
  }
  return {};
}

}  // namespace pfem::reliability
