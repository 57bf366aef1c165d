#pragma once
// The Evaluate computation: one (cached) run of a model at given parameter values, reduced to
// functionals and their gradients. Shared by the gRPC handler (GradientService::Evaluate) and
// the UM-Bridge endpoint (server/umbridge_server.h), so both answer with the same numbers
// from the same cache.
//
// Thread-safety: evaluate() may be called from any thread (the references are thread-safe).
#include <grpcpp/support/status.h>

#include <functional>

#include "pfem/v1/service.pb.h"
#include "server/job_manager.h"
#include "server/limits.h"
#include "server/result_cache.h"
#include "server/store.h"

namespace pfem::server {

class Evaluator {
 public:
  // Polled while a run goes on; a code other than OK cancels it (client gone, deadline).
  using StopFunction = std::function<grpc::StatusCode()>;

  // All references must outlive the evaluator.
  Evaluator(Store& store, JobManager& jobs, ResultCache& cache, const Limits& limits)
      : store_(store), jobs_(jobs), cache_(cache), limits_(limits) {}

  // Checks the request (every field error at once), runs it or takes it from the cache, and
  // fills *response (wall_seconds included). Throws ServiceError: INVALID_ARGUMENT,
  // NOT_FOUND (model_id), RESOURCE_EXHAUSTED (limits), CANCELLED / DEADLINE_EXCEEDED (from
  // should_stop), FAILED_PRECONDITION (the simulation failed).
  void evaluate(const pfem::v1::EvaluateRequest& request, const StopFunction& should_stop,
                pfem::v1::EvaluateResponse* response) const;

 private:
  Store& store_;
  JobManager& jobs_;
  ResultCache& cache_;
  const Limits& limits_;
};

}  // namespace pfem::server
