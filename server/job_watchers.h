#pragma once
// WatchJob streams without a thread each. Every stream is a gRPC callback reactor: while it
// waits for its job to change it holds no thread, only its call's state (a few KB). One
// dispatcher thread feeds them all from the job manager's change listener:
// - a job's progress (at every step of its run) only marks the job changed; a change of
//   state also wakes the dispatcher at once;
// - every `interval`, or when woken, the dispatcher takes one snapshot of each changed job and
//   starts a write of it on each of its streams that has no write in flight and has not been
//   sent one within `interval` (a reader that does not keep up holds one message in flight and
//   is sent the latest state once it takes it: nothing queues up behind it);
// - the final state always goes out, as the stream's last message, and the stream ends OK.
// While draining, a stream whose job has not finished ends UNAVAILABLE ("the job is kept and
// resumes on restart"); a stream whose reader leaves ends CANCELLED.
//
// Thread-safety: every public method may be called from any thread. The gRPC server must
// have shut down (every stream ended) before the JobWatchers is destroyed.
#include <grpcpp/grpcpp.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <thread>
#include <unordered_set>

#include "pfem/v1/service.pb.h"
#include "server/job_manager.h"
#include "server/stream_slots.h"

namespace pfem::server {

class JobWatchers {
 public:
  // Registers itself as `jobs`' change listener: construct before jobs.start().
  JobWatchers(JobManager& jobs, std::chrono::milliseconds interval);
  ~JobWatchers();  // stops the dispatcher
  JobWatchers(const JobWatchers&) = delete;
  JobWatchers& operator=(const JobWatchers&) = delete;

  // A stream following job `id` (which exists), holding `slot` until it ends.
  grpc::ServerWriteReactor<pfem::v1::Job>* watch(const std::string& id, StreamSlots::Slot slot);
  // A stream that ends at once with `status` (a refused WatchJob).
  static grpc::ServerWriteReactor<pfem::v1::Job>* refuse(const grpc::Status& status);

  // From now on every stream of an unfinished job ends UNAVAILABLE.
  void begin_drain();
  // Streams not yet ended.
  long open() const { return open_.load(); }

 private:
  class Stream;

  void job_changed(const std::string& id, bool state_changed);  // the listener
  void dispatch_loop();
  void dispatch(std::unordered_set<std::string> changed);
  // The reactions of a stream (on gRPC's callback threads).
  void write_done(Stream* stream, bool ok);
  void cancelled(Stream* stream);
  void done(Stream* stream);

  JobManager& jobs_;
  const std::chrono::milliseconds interval_;

  // What the listener and drain touch (never held while taking another lock).
  std::mutex changes_mutex_;
  std::condition_variable changes_cv_;
  std::unordered_set<std::string> changed_;  // jobs changed since the last pass
  bool wake_ = false;                        // pass at once
  bool stopping_ = false;

  // The streams (a stream's own fields too: Stream is only touched under this lock).
  mutable std::mutex mutex_;
  std::map<std::string, std::set<Stream*>> by_job_;
  std::set<Stream*> pending_;  // may have something to send or to end
  std::atomic<bool> draining_{false};
  std::atomic<long> open_{0};

  std::thread dispatcher_;
};

}  // namespace pfem::server
