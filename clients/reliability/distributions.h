#pragma once
// Marginal distributions of basic random variables: CDF, PDF and quantiles through
// Boost.Math, the moment -> parameter conversions, and the map to and from a standard normal
// variable that the Nataf transformation is built on.
//
// A Distribution is an immutable value: cheap to copy, safe to share between threads.
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace pfem::reliability {

enum class DistributionKind {
  kNormal,
  kLognormal,
  kUniform,
  kGumbel,           // type I largest
  kFrechet,          // type II largest
  kWeibull,          // type III smallest
  kGamma,
  kExponential,      // shifted by `lower`
  kBeta,             // on [lower, upper]
  kTruncatedNormal,  // on [lower, upper], either bound may be infinite
};

// "normal", "lognormal", "uniform", "gumbel", "frechet", "weibull", "gamma", "exponential",
// "beta", "truncated_normal"; nullopt for anything else.
std::optional<DistributionKind> parse_distribution_kind(std::string_view name);
std::string_view to_string(DistributionKind kind);
// The accepted names joined by ", " (for error messages).
std::string distribution_names();

class Distribution {
 public:
  // Native parameters. Each throws std::invalid_argument with a message naming the parameter
  // (e.g. "scale: must be > 0") when a parameter is out of range.
  static Distribution normal(double mean, double stddev);
  static Distribution lognormal(double lambda, double zeta);
  static Distribution uniform(double lower, double upper);
  static Distribution gumbel(double location, double scale);
  static Distribution frechet(double scale, double shape);
  static Distribution weibull(double scale, double shape);
  static Distribution gamma(double shape, double scale);
  static Distribution exponential(double rate, double lower = 0.0);
  static Distribution beta(double shape_a, double shape_b, double lower, double upper);
  static Distribution truncated_normal(double location, double scale, double lower, double upper);

  // From the mean and standard deviation of X. `lower`/`upper` are the bounds of beta and
  // truncated_normal (required for beta; +-infinity allowed for truncated_normal) and are
  // ignored by the other kinds. Fréchet and Weibull solve for the shape from the coefficient
  // of variation (a 1-D root solve), truncated_normal for its parent normal (2-D Newton).
  // Throws std::invalid_argument naming the field ("stddev: must be > 0").
  static Distribution from_moments(DistributionKind kind, double mean, double stddev,
                                   double lower = 0.0, double upper = 0.0);

  // The same family with the mean and standard deviation changed and the bounds kept
  // (uniform: centred on the new mean; exponential: the shift follows). Used for the
  // sensitivities of beta to the moments.
  Distribution with_moments(double mean, double stddev) const;

  DistributionKind kind() const { return kind_; }
  double cdf(double x) const;
  double ccdf(double x) const;  // 1 - cdf, accurate in the upper tail
  double pdf(double x) const;
  double quantile(double p) const;    // x with cdf(x) = p
  double cquantile(double q) const;   // x with ccdf(x) = q
  double mean() const;
  double stddev() const;
  // The support [lower, upper] (may be infinite).
  std::pair<double, double> support() const;

  // z = Phi^-1(F(x)), accurate in both tails.
  double to_standard_normal(double x) const;
  // x = F^-1(Phi(z)), accurate in both tails; z is clamped to +-35 so x stays finite where
  // the support allows it.
  double from_standard_normal(double z) const;

  // Native parameters by name (e.g. {"lambda", 1.6}, {"zeta", 0.1}), for reports.
  std::vector<std::pair<std::string, double>> parameters() const;

 private:
  Distribution(DistributionKind kind, double p0, double p1, double p2 = 0.0, double p3 = 0.0);
  DistributionKind kind_;
  double p_[4];
};

// Standard normal helpers (Boost.Math).
double standard_normal_cdf(double z);
double standard_normal_pdf(double z);
double standard_normal_quantile(double p);

}  // namespace pfem::reliability
