#pragma once
// Jobs on a bounded worker pool: a bounded FIFO queue of persisted jobs, plus a priority lane
// for the synchronous Evaluate runs (not persisted). Cancellation, job timeouts and call
// deadlines reach the engine through its cancel flag; progress reaches watchers through a
// per-job snapshot that the engine's progress callback overwrites under a mutex, and a
// listener told of every change (it never waits for a watcher: server/job_watchers.h).
//
// Lifecycle: start() re-queues what a previous server left QUEUED or RUNNING and starts the
// workers; begin_drain() stops starting queued jobs and refuses new ones; stop(deadline) lets
// running jobs finish until the deadline, then interrupts them and stores them as QUEUED (so
// the next start runs them again), and joins the workers.
//
// Thread-safety: every public method may be called from any thread.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <grpcpp/support/status.h>

#include "engine/analysis/run.h"
#include "pfem/v1/service.pb.h"
#include "server/store.h"

namespace pfem::server {

struct JobManagerOptions {
  int workers = 1;          // worker threads, >= 1
  long max_queued = 1000;   // jobs waiting for a worker, >= 1
};

class JobManager {
 public:
  // The engine entry point; tests may substitute a fake. Default: pfem::run.
  using RunFunction = std::function<RunResult(const pfem::v1::Model&, const RunOptions&)>;

  // Told the id of a job after each change of what get() shows for it: `state_changed` is
  // false for progress (at every step of a run, on the worker: it must be quick) and true for
  // every other change. It may be called with the manager's locks held: it must not call the
  // manager.
  using ChangeListener = std::function<void(const std::string& id, bool state_changed)>;

  JobManager(Store& store, JobManagerOptions options, RunFunction run = {});
  ~JobManager();  // stop(now) when still running
  JobManager(const JobManager&) = delete;
  JobManager& operator=(const JobManager&) = delete;

  // Before start().
  void set_listener(ChangeListener listener);
  void start();

  // Queues an already validated request. Throws ServiceError: RESOURCE_EXHAUSTED when
  // max_queued jobs wait, UNAVAILABLE when draining.
  std::string submit(const pfem::v1::SubmitJobRequest& request);

  // The job as it is now. Throws ServiceError NOT_FOUND.
  pfem::v1::Job get(const std::string& id);

  // Cancels a queued job at once, or sets a running job's cancel flag (it ends CANCELLED with
  // its partial result) once the store has recorded the cancel. Throws NOT_FOUND, or
  // FAILED_PRECONDITION when it has finished.
  pfem::v1::Job cancel(const std::string& id);

  // The job as get() shows it, and in *version a number that changes with it: bumped at
  // every change while the job is queued or running here, kSettled once it has left the
  // running jobs (finished, or stored by a server that could not store its end). Throws
  // NOT_FOUND.
  static constexpr std::uint64_t kSettled = ~std::uint64_t{0} - 1;
  pfem::v1::Job observe(const std::string& id, std::uint64_t* version);

  // Runs a model on a worker ahead of the queued jobs and waits for the result. `should_stop`
  // is polled about every 20 ms while waiting; when it returns a code other than OK the run
  // is cancelled and ServiceError(code) is thrown. UNAVAILABLE when stopping.
  RunResult run_now(const pfem::v1::Model& model, RunOptions options,
                    const std::function<grpc::StatusCode()>& should_stop);

  void begin_drain();
  bool draining() const;
  void stop(std::chrono::steady_clock::time_point deadline);

  long queued() const;
  long running() const;

 private:
  struct ActiveJob;
  struct EvalTask;

  void worker_loop();
  void run_job(const std::shared_ptr<ActiveJob>& entry);
  void run_eval(const std::shared_ptr<EvalTask>& task);
  std::shared_ptr<ActiveJob> find_active(const std::string& id);
  std::shared_ptr<ActiveJob> new_entry(const pfem::v1::Job& job);
  // Ends a job FAILED when its end could not be stored (store_failed) ...
  void store_failed(const std::shared_ptr<ActiveJob>& entry, pfem::v1::Job job,
                    const std::string& why);
  // ... and, when not even that could be stored, the job as this server answers it.
  std::optional<pfem::v1::Job> unstored_job(const std::string& id);

  Store& store_;
  const JobManagerOptions options_;
  RunFunction run_;
  ChangeListener listener_;  // set before start(), then only read

  mutable std::mutex mutex_;
  std::condition_variable work_cv_;  // work queued, or stopping
  std::condition_variable idle_cv_;  // a job finished
  std::map<std::string, std::shared_ptr<ActiveJob>> active_;  // queued and running jobs
  std::deque<std::string> queue_;
  std::map<std::string, pfem::v1::Job> unstored_;  // finished, but the store refused the end
  std::deque<std::shared_ptr<EvalTask>> eval_queue_;
  long running_jobs_ = 0;
  bool draining_ = false;
  bool stopping_ = false;
  bool started_ = false;
  bool stopped_ = false;
  std::vector<std::thread> workers_;
};

}  // namespace pfem::server
