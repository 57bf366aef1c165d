#pragma once
// What a limit state (or an optimisation) backed by PFEM simulations did, for reports.
namespace pfem::reliability {

struct SimulationStats {
  long long evaluations = 0;           // evaluations of the model's functionals
  long long gradient_evaluations = 0;  // of which with gradients
  long long simulations = 0;           // PFEM runs done for them (FDM: 2P + 1 per gradient)
  long long cached = 0;                // --server: answers from the server's cache (no run)
  long long retries = 0;               // --server: Evaluate calls repeated after UNAVAILABLE
  double seconds = 0.0;                // wall time spent in the evaluations
};

}  // namespace pfem::reliability
