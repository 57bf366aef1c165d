#include "server/job_manager.h"

#include <algorithm>
#include <cstdio>
#include <random>

#include "server/convert.h"
#include "server/status.h"
#include "wire/convert.h"

namespace pfem::server {
namespace {

double now_unix() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

std::string new_job_id() {
  static std::mutex mutex;
  static std::mt19937_64 rng{std::random_device{}()};
  std::lock_guard lock(mutex);
  static constexpr char kHex[] = "0123456789abcdef";
  std::uint64_t v = rng();
  std::string id(16, '0');
  for (int i = 15; i >= 0; --i, v >>= 4) id[static_cast<std::size_t>(i)] = kHex[v & 15];
  return id;
}

bool finished(pfem::v1::JobState s) {
  return s == pfem::v1::JOB_STATE_SUCCEEDED || s == pfem::v1::JOB_STATE_FAILED ||
         s == pfem::v1::JOB_STATE_CANCELLED;
}

}  // namespace

struct JobManager::ActiveJob {
  std::string id;
  const ChangeListener* listener = nullptr;  // the manager's (may be empty)
  std::mutex m;
  pfem::v1::Job job;          // snapshot shown to GetJob / WatchJob
  std::uint64_t version = 0;  // bumped on every change of `job`
  std::atomic<bool> cancel{false};
  std::atomic<bool> user_cancelled{false};  // set under m, and only while !ending
  bool ending = false;  // under m: the run is over and its end being decided (too late to cancel)
  std::atomic<bool> timed_out{false};
  std::atomic<bool> interrupted{false};  // stopped by a shutdown: back to QUEUED

  // A change of state (or of more than the progress): the listener is told at once.
  void update(const std::function<void(pfem::v1::Job&)>& change) { apply(change, true); }
  // Progress, at every step: the listener is told too, but as progress, which watchers take
  // at their own pace (waking 300 watchers at every step had cut a job from 481 to 171
  // steps/s).
  void update_progress(const std::function<void(pfem::v1::Job&)>& change) { apply(change, false); }
  pfem::v1::Job snapshot() {
    std::lock_guard lock(m);
    return job;
  }

 private:
  void apply(const std::function<void(pfem::v1::Job&)>& change, bool state_changed) {
    {
      std::lock_guard lock(m);
      change(job);
      ++version;
    }
    if (listener && *listener) (*listener)(id, state_changed);
  }
};

struct JobManager::EvalTask {
  pfem::v1::Model model;
  RunOptions options;
  std::atomic<bool> cancel{false};
  std::mutex m;
  std::condition_variable cv;
  bool started = false;
  bool done = false;
  RunResult result;
  std::exception_ptr error;
};

JobManager::JobManager(Store& store, JobManagerOptions options, RunFunction run)
    : store_(store), options_(options), run_(std::move(run)) {
  if (!run_) run_ = [](const pfem::v1::Model& m, const RunOptions& o) { return pfem::run(m, o); };
}

JobManager::~JobManager() {
  if (started_ && !stopped_) stop(std::chrono::steady_clock::now());
}

void JobManager::set_listener(ChangeListener listener) { listener_ = std::move(listener); }

std::shared_ptr<JobManager::ActiveJob> JobManager::new_entry(const pfem::v1::Job& job) {
  auto entry = std::make_shared<ActiveJob>();
  entry->id = job.id();
  entry->listener = &listener_;
  entry->job = job;
  return entry;
}

void JobManager::start() {
  const auto ids = store_.recover_queued();
  {
    std::lock_guard lock(mutex_);
    for (const auto& id : ids) {
      auto job = store_.get_job(id);
      if (!job) continue;
      active_[id] = new_entry(*job);
      queue_.push_back(id);
    }
    started_ = true;
  }
  const int n = std::max(1, options_.workers);
  for (int i = 0; i < n; ++i) workers_.emplace_back([this] { worker_loop(); });
}

std::string JobManager::submit(const pfem::v1::SubmitJobRequest& request) {
  std::lock_guard lock(mutex_);
  if (draining_) throw ServiceError(grpc::StatusCode::UNAVAILABLE, "server is shutting down");
  if (static_cast<long>(queue_.size()) >= options_.max_queued) {
    throw ServiceError(grpc::StatusCode::RESOURCE_EXHAUSTED,
                       "max-queued limit reached: " + std::to_string(queue_.size()) +
                           " jobs are queued, the limit is " +
                           std::to_string(options_.max_queued));
  }
  pfem::v1::Job job;
  job.set_id(new_job_id());
  job.set_state(pfem::v1::JOB_STATE_QUEUED);
  job.set_model_name(request.model().name());
  job.set_created_unix(now_unix());
  job.set_sensitivity(request.options().sensitivity() == pfem::v1::SENSITIVITY_METHOD_UNSPECIFIED
                          ? pfem::v1::SENSITIVITY_METHOD_NONE
                          : request.options().sensitivity());
  store_.insert_job(job, request);
  active_[job.id()] = new_entry(job);
  queue_.push_back(job.id());
  work_cv_.notify_one();
  return job.id();
}

std::shared_ptr<JobManager::ActiveJob> JobManager::find_active(const std::string& id) {
  std::lock_guard lock(mutex_);
  const auto it = active_.find(id);
  return it == active_.end() ? nullptr : it->second;
}

std::optional<pfem::v1::Job> JobManager::unstored_job(const std::string& id) {
  std::lock_guard lock(mutex_);
  const auto it = unstored_.find(id);
  if (it == unstored_.end()) return std::nullopt;
  return it->second;
}

pfem::v1::Job JobManager::get(const std::string& id) {
  if (auto entry = find_active(id)) return entry->snapshot();
  if (auto job = unstored_job(id)) return *job;
  if (auto job = store_.get_job(id)) return *job;
  throw ServiceError(grpc::StatusCode::NOT_FOUND, "no job '" + id + "'");
}

pfem::v1::Job JobManager::cancel(const std::string& id) {
  std::shared_ptr<ActiveJob> entry;
  {
    std::lock_guard lock(mutex_);
    const auto it = active_.find(id);
    if (it != active_.end()) {
      entry = it->second;
      const auto q = std::find(queue_.begin(), queue_.end(), id);
      if (q != queue_.end()) {  // still queued: cancelled here and now
        pfem::v1::Job job = entry->snapshot();
        job.set_state(pfem::v1::JOB_STATE_CANCELLED);
        job.set_finished_unix(now_unix());
        job.mutable_error()->set_message("cancelled before it started");
        job.mutable_error()->set_step(-1);
        store_.finish_job(job, nullptr, "cancelled while queued");
        queue_.erase(q);
        entry->update([&](pfem::v1::Job& j) { j = job; });
        active_.erase(it);
        return job;
      }
    }
  }
  if (entry) {
    // Under the job's lock, so that an acknowledged cancel is one the end sees: a run that
    // has ended (the end being decided, or decided) is too late to cancel.
    std::lock_guard lock(entry->m);
    if (finished(entry->job.state())) {  // ended, not yet out of the active list
      throw ServiceError(grpc::StatusCode::FAILED_PRECONDITION,
                         "job '" + id + "' has already finished (" +
                             pfem::v1::JobState_Name(entry->job.state()) + ")");
    }
    if (entry->ending) {
      throw ServiceError(grpc::StatusCode::FAILED_PRECONDITION,
                         "job '" + id + "' has already finished its run (its end is being stored)");
    }
    store_.request_cancel(id);  // durable before it is acknowledged (kept over a crash)
    entry->user_cancelled = true;
    entry->cancel = true;
    return entry->job;
  }
  if (auto job = unstored_job(id)) {
    throw ServiceError(grpc::StatusCode::FAILED_PRECONDITION,
                       "job '" + id + "' has already finished (" +
                           pfem::v1::JobState_Name(job->state()) + ")");
  }
  auto job = store_.get_job(id);
  if (!job) throw ServiceError(grpc::StatusCode::NOT_FOUND, "no job '" + id + "'");
  throw ServiceError(grpc::StatusCode::FAILED_PRECONDITION,
                     "job '" + id + "' has already finished (" +
                         pfem::v1::JobState_Name(job->state()) + ")");
}

pfem::v1::Job JobManager::observe(const std::string& id, std::uint64_t* version) {
  if (auto entry = find_active(id)) {
    std::lock_guard lock(entry->m);
    *version = entry->version;
    return entry->job;
  }
  *version = kSettled;
  return get(id);
}

RunResult JobManager::run_now(const pfem::v1::Model& model, RunOptions options,
                              const std::function<grpc::StatusCode()>& should_stop) {
  auto task = std::make_shared<EvalTask>();
  task->model = model;
  task->options = std::move(options);
  {
    std::lock_guard lock(mutex_);
    if (stopping_) throw ServiceError(grpc::StatusCode::UNAVAILABLE, "server is shutting down");
    eval_queue_.push_back(task);
  }
  work_cv_.notify_one();
  grpc::StatusCode stop_code = grpc::StatusCode::OK;
  std::unique_lock lock(task->m);
  while (!task->done) {
    task->cv.wait_for(lock, std::chrono::milliseconds(20));
    if (task->done || stop_code != grpc::StatusCode::OK) continue;
    lock.unlock();
    stop_code = should_stop ? should_stop() : grpc::StatusCode::OK;
    lock.lock();
    if (stop_code == grpc::StatusCode::OK) continue;
    task->cancel = true;
    if (!task->started) {  // never reached a worker: take it out of the lane
      task->done = true;
      lock.unlock();
      std::lock_guard qlock(mutex_);
      const auto it = std::find(eval_queue_.begin(), eval_queue_.end(), task);
      if (it != eval_queue_.end()) eval_queue_.erase(it);
      lock.lock();
    }
  }
  if (stop_code != grpc::StatusCode::OK) {
    throw ServiceError(stop_code, stop_code == grpc::StatusCode::DEADLINE_EXCEEDED
                                      ? "deadline exceeded: the run was cancelled"
                                      : "the call was cancelled: the run was stopped");
  }
  if (task->error) std::rethrow_exception(task->error);
  return std::move(task->result);
}

void JobManager::worker_loop() {
  for (;;) {
    std::shared_ptr<EvalTask> task;
    std::shared_ptr<ActiveJob> entry;
    {
      std::unique_lock lock(mutex_);
      work_cv_.wait(lock, [&] {
        return stopping_ || !eval_queue_.empty() || (!draining_ && !queue_.empty());
      });
      if (!eval_queue_.empty()) {
        task = eval_queue_.front();
        eval_queue_.pop_front();
      } else if (stopping_) {
        return;
      } else {
        const std::string id = queue_.front();
        queue_.pop_front();
        entry = active_.at(id);
        ++running_jobs_;
      }
    }
    if (task) {
      run_eval(task);
      continue;
    }
    run_job(entry);
    {
      std::lock_guard lock(mutex_);
      --running_jobs_;
      active_.erase(entry->job.id());
    }
    idle_cv_.notify_all();
  }
}

void JobManager::run_eval(const std::shared_ptr<EvalTask>& task) {
  {
    std::lock_guard lock(task->m);
    if (task->done) return;  // abandoned by its caller before it started
    task->started = true;
  }
  try {
    task->options.cancel = &task->cancel;
    task->result = run_(task->model, task->options);
  } catch (...) {
    task->error = std::current_exception();
  }
  {
    std::lock_guard lock(task->m);
    task->done = true;
  }
  task->cv.notify_all();
}

void JobManager::run_job(const std::shared_ptr<ActiveJob>& entry) {
  const std::string id = entry->snapshot().id();
  entry->update([](pfem::v1::Job& job) {
    job.set_state(pfem::v1::JOB_STATE_RUNNING);
    job.set_started_unix(now_unix());
    job.set_attempts(job.attempts() + 1);
    job.clear_error();
  });
  std::optional<pfem::v1::Result> result;
  std::string failure;  // an exception before or instead of a result
  try {
    store_.update_job(entry->snapshot(), "started");
    const auto request = store_.get_request(id);
    if (!request) throw StoreError("no request stored for job " + id);
    pfem::v1::Model model = request->model();
    const auto errors = apply_parameter_values(model, request->parameter_values());
    if (!errors.empty()) throw ModelError(errors);
    RunOptions options = to_run_options(request->options(), SensitivityMethod::kNone);
    options.cancel = &entry->cancel;
    // Compared in seconds as doubles: a time point now + 1e10 s overflows the clock's
    // nanoseconds (the job would be cancelled at its first step).
    const auto started = std::chrono::steady_clock::now();
    const std::optional<double> timeout =
        request->has_timeout_seconds() ? std::optional<double>(request->timeout_seconds())
                                       : std::nullopt;
    options.progress = [entry, started, timeout](const Progress& p) {
      entry->update_progress([&](pfem::v1::Job& job) { *job.mutable_progress() = wire::to_proto(p); });
      if (timeout && std::chrono::duration<double>(std::chrono::steady_clock::now() - started)
                             .count() > *timeout) {
        entry->timed_out = true;
        entry->cancel = true;
      }
    };
    result = wire::to_proto(run_(model, options));
  } catch (const ModelError& e) {
    failure = std::string("invalid model: ") + e.what();
  } catch (const std::exception& e) {
    failure = e.what();
  } catch (...) {
    failure = "unknown error";
  }

  // The store is written first and the snapshot after, so that whoever sees the final
  // state (GetJob, WatchJob) also finds the stored result.
  try {
    pfem::v1::Job job;
    {
      std::lock_guard lock(entry->m);
      entry->ending = true;  // no cancel is acknowledged from here on
      job = entry->job;
    }
    if (entry->interrupted && !entry->user_cancelled) {
      job.set_state(pfem::v1::JOB_STATE_QUEUED);
      job.clear_progress();
      store_.update_job(job, "re-queued: interrupted by a server shutdown");
      entry->update([&](pfem::v1::Job& j) { j = job; });
      return;
    }
    std::string note;
    job.set_finished_unix(now_unix());
    auto* error = job.mutable_error();
    if (!result) {
      job.set_state(pfem::v1::JOB_STATE_FAILED);
      error->set_message(failure);
      error->set_step(job.progress().step());
      error->set_time(job.progress().time());
      note = "failed: " + failure;
    } else {
      const auto& s = result->summary();
      switch (s.status()) {
        case pfem::v1::RUN_STATUS_FAILED:
          job.set_state(pfem::v1::JOB_STATE_FAILED);
          error->set_message(s.message());
          error->set_step(s.failed_step());
          error->set_time(s.failed_time());
          note = "failed: " + s.message();
          break;
        case pfem::v1::RUN_STATUS_CANCELLED:
          job.set_state(pfem::v1::JOB_STATE_CANCELLED);
          error->set_message(entry->timed_out && !entry->user_cancelled
                                 ? "timeout_seconds exceeded"
                                 : (entry->user_cancelled ? "cancelled by a client"
                                                          : s.message()));
          error->set_step(s.steps());
          error->set_time(job.progress().time());
          note = "cancelled: " + error->message();
          break;
        default:
          if (entry->user_cancelled) {  // acknowledged during the run's last step: kept
            job.set_state(pfem::v1::JOB_STATE_CANCELLED);
            error->set_message("cancelled by a client (the run had reached its end)");
            error->set_step(s.steps());
            error->set_time(job.progress().time());
            note = "cancelled: " + error->message();
            break;
          }
          job.set_state(pfem::v1::JOB_STATE_SUCCEEDED);
          job.clear_error();
          note = "succeeded";
          break;
      }
    }
    try {
      store_.finish_job(job, result ? &*result : nullptr, note);
    } catch (const std::exception& e) {
      store_failed(entry, job, e.what());
      return;
    }
    entry->update([&](pfem::v1::Job& j) { j = job; });
  } catch (const std::exception& e) {
    store_failed(entry, entry->snapshot(), e.what());
  }
}

void JobManager::store_failed(const std::shared_ptr<ActiveJob>& entry, pfem::v1::Job job,
                              const std::string& why) {
  // The job ends FAILED naming why, for its watchers and GetJob. Without its result the row
  // is smaller: storing that may still succeed (a full disk); if it does not, the stored job
  // stays RUNNING and the next start runs it again, while this server answers FAILED.
  std::fprintf(stderr, "pfem-server: cannot store the end of job %s: %s\n", job.id().c_str(),
               why.c_str());
  job.set_state(pfem::v1::JOB_STATE_FAILED);
  job.set_finished_unix(now_unix());
  job.mutable_error()->set_message("the job's end could not be stored: " + why);
  job.mutable_error()->set_step(job.progress().step());
  job.mutable_error()->set_time(job.progress().time());
  try {
    store_.finish_job(job, nullptr, "failed: " + job.error().message());
  } catch (const std::exception&) {
    std::lock_guard lock(mutex_);
    unstored_[job.id()] = job;
  }
  entry->update([&](pfem::v1::Job& j) { j = job; });
}

void JobManager::begin_drain() {
  std::lock_guard lock(mutex_);
  draining_ = true;
}

bool JobManager::draining() const {
  std::lock_guard lock(mutex_);
  return draining_;
}

void JobManager::stop(std::chrono::steady_clock::time_point deadline) {
  std::unique_lock lock(mutex_);
  if (stopped_) return;
  draining_ = true;
  work_cv_.notify_all();
  idle_cv_.wait_until(lock, deadline, [&] { return running_jobs_ == 0; });
  for (auto& [id, entry] : active_) {
    if (entry->snapshot().state() == pfem::v1::JOB_STATE_RUNNING) {
      entry->interrupted = true;
      entry->cancel = true;
    }
  }
  stopping_ = true;
  for (auto& task : eval_queue_) {
    std::lock_guard tlock(task->m);
    task->error = std::make_exception_ptr(
        ServiceError(grpc::StatusCode::UNAVAILABLE, "server is shutting down"));
    task->done = true;
    task->cv.notify_all();
  }
  eval_queue_.clear();
  work_cv_.notify_all();
  lock.unlock();
  for (auto& t : workers_) t.join();
  workers_.clear();
  lock.lock();
  stopped_ = true;
}

long JobManager::queued() const {
  std::lock_guard lock(mutex_);
  return static_cast<long>(queue_.size());
}

long JobManager::running() const {
  std::lock_guard lock(mutex_);
  return running_jobs_;
}

}  // namespace pfem::server
