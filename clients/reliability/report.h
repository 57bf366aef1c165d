#pragma once
// The outputs of `pfem-form`: DIR/result.json and the readable summary.
//
// result.json (numbers that are not finite are written as null):
//   problem, description, method, converged, message, beta, pf (= Phi(-beta)), iterations,
//   evaluations, gradient_evaluations, gradient_source, g_at_design_point, wall_seconds,
//   variables:      [{name, distribution, mean, stddev, parameters: {native name: value}}]
//   design_point:   {x: {name: value}, u: {name: value}}   (names in file order)
//   alpha:          {name: value}  -grad G/||grad G|| at u*; u* = beta alpha; > 0 for demands
//   importance_factors: {name: alpha^2}
//   gamma:          {name: value}  importance vector in x accounting for correlation
//   sensitivities:  {name: {dbeta_dmean, dbeta_dstddev, dpf_dmean, dpf_dstddev}}
//   sorm (--sorm):  {valid, message, curvatures: [..], evaluations,
//                    breitung: {pf, beta}, hohenbichler_rackwitz: {pf, beta}, tvedt: {pf, beta}}
//   importance_sampling / monte_carlo (on request): {samples, failures, pf, cov, beta, seed}
//   simulations (model limit states): {evaluations, gradient_evaluations, runs (PFEM runs; FDM:
//                   2P+1 per gradient), cached (answered from the server's cache), seconds}
#include <optional>
#include <string>

#include "clients/reliability/analysis.h"
#include "clients/reliability/problem_io.h"

namespace pfem::reliability {

// ", 2 <= t <= 6", ", 2 <= t", ", t <= 6" or "" for a functional's time window.
std::string time_window_text(std::optional<double> start, std::optional<double> end);

std::string result_json(const Problem& problem, const AnalysisResult& result,
                        const AnalysisOptions& options);
std::string summary_text(const Problem& problem, const AnalysisResult& result,
                         const AnalysisOptions& options);

}  // namespace pfem::reliability
