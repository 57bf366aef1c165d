#pragma once
// pfem.v1.GradientService handlers (the port has authenticated the call before its request
// was read: server/port_credentials.h). Each one is thin: check the request, call
// the job manager / store / cache, convert the answer; errors are converted once by
// guarded() (server/status.h), so no exception crosses into gRPC. WatchJob is gRPC's callback
// API (a reactor, no thread held while it waits: server/job_watchers.h); the others are
// synchronous handlers.
#include <grpcpp/grpcpp.h>

#include <atomic>
#include <chrono>
#include <functional>

#include "pfem/v1/service.grpc.pb.h"
#include "server/evaluator.h"
#include "server/job_watchers.h"
#include "server/job_manager.h"
#include "server/limits.h"
#include "server/open_results.h"
#include "server/result_cache.h"
#include "server/store.h"
#include "server/stream_slots.h"

namespace pfem::server {

class GradientService final : public pfem::v1::GradientService::WithCallbackMethod_WatchJob<
                                  pfem::v1::GradientService::Service> {
 public:
  // All references must outlive the service; construct it before jobs.start() (it listens to
  // the job manager's changes) and destroy it after jobs.stop().
  GradientService(Store& store, JobManager& jobs, ResultCache& cache, const Limits& limits)
      : store_(store),
        jobs_(jobs),
        limits_(limits),
        evaluator_(store, jobs, cache, limits),
        streams_(limits.max_streams, limits.max_streams_per_client),
        results_(store),
        watchers_(jobs, kWatchInterval) {}

  grpc::Status ValidateModel(grpc::ServerContext* context,
                             const pfem::v1::ValidateModelRequest* request,
                             pfem::v1::ValidateModelResponse* response) override;
  grpc::Status SubmitJob(grpc::ServerContext* context, const pfem::v1::SubmitJobRequest* request,
                         pfem::v1::SubmitJobResponse* response) override;
  grpc::ServerWriteReactor<pfem::v1::Job>* WatchJob(grpc::CallbackServerContext* context,
                                                    const pfem::v1::JobRequest* request) override;
  grpc::Status GetJob(grpc::ServerContext* context, const pfem::v1::JobRequest* request,
                      pfem::v1::Job* response) override;
  grpc::Status GetResult(grpc::ServerContext* context, const pfem::v1::JobRequest* request,
                         grpc::ServerWriter<pfem::v1::GetResultResponse>* writer) override;
  grpc::Status CancelJob(grpc::ServerContext* context, const pfem::v1::JobRequest* request,
                         pfem::v1::Job* response) override;
  grpc::Status ListJobs(grpc::ServerContext* context, const pfem::v1::ListJobsRequest* request,
                        pfem::v1::ListJobsResponse* response) override;
  grpc::Status PutModel(grpc::ServerContext* context, const pfem::v1::PutModelRequest* request,
                        pfem::v1::PutModelResponse* response) override;
  grpc::Status Evaluate(grpc::ServerContext* context, const pfem::v1::EvaluateRequest* request,
                        pfem::v1::EvaluateResponse* response) override;

  // Values per GetResult chunk message (8 bytes each).
  static constexpr int kChunkValues = 65536;
  // A WatchJob stream is sent at most one message an interval (the final state at once).
  static constexpr std::chrono::milliseconds kWatchInterval{100};

  // From now on every new call gets UNAVAILABLE; calls already running go on, but WatchJob
  // streams of unfinished jobs end UNAVAILABLE.
  void begin_drain() {
    draining_ = true;
    watchers_.begin_drain();
  }
  // Calls inside a handler right now, and WatchJob streams open.
  int in_flight() const { return in_flight_.load() + static_cast<int>(watchers_.open()); }

 private:
  // Runs one handler body: refuses it while draining, counts it, converts errors (guarded).
  grpc::Status handle(const std::function<grpc::Status()>& body);

  Store& store_;
  JobManager& jobs_;
  const Limits& limits_;
  const Evaluator evaluator_;  // Evaluate (shared with the UM-Bridge endpoint)
  StreamSlots streams_;        // WatchJob and GetResult streams open
  OpenResults results_;        // the results GetResult streams are sending
  JobWatchers watchers_;       // the WatchJob streams
  std::atomic<bool> draining_{false};
  std::atomic<int> in_flight_{0};
};

}  // namespace pfem::server
