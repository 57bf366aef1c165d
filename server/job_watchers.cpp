#include "server/job_watchers.h"

#include <vector>

#include "server/status.h"

namespace pfem::server {
namespace {

using Clock = std::chrono::steady_clock;

bool finished(pfem::v1::JobState s) {
  return s == pfem::v1::JOB_STATE_SUCCEEDED || s == pfem::v1::JOB_STATE_FAILED ||
         s == pfem::v1::JOB_STATE_CANCELLED;
}

// Nothing sent yet (no version of JobManager::observe is this).
constexpr std::uint64_t kNothingSent = ~std::uint64_t{0};
static_assert(kNothingSent != JobManager::kSettled);

class Refused final : public grpc::ServerWriteReactor<pfem::v1::Job> {
 public:
  explicit Refused(const grpc::Status& status) { Finish(status); }
  void OnDone() override { delete this; }
};

}  // namespace

class JobWatchers::Stream final : public grpc::ServerWriteReactor<pfem::v1::Job> {
 public:
  Stream(JobWatchers& hub, std::string job_id, StreamSlots::Slot slot)
      : id(std::move(job_id)), hub_(hub), slot_(std::move(slot)) {}

  void OnWriteDone(bool ok) override { hub_.write_done(this, ok); }
  void OnCancel() override { hub_.cancelled(this); }
  void OnDone() override { hub_.done(this); }  // deletes this

  const std::string id;  // the job followed
  // Under the hub's mutex:
  pfem::v1::Job message;  // the message being written (untouched until its write is done)
  std::uint64_t sent_version = kNothingSent;
  Clock::time_point last_sent{};
  bool writing = false;    // a write in flight
  bool ended = false;      // Finish or StartWriteAndFinish called (or about to be)
  bool cancelled = false;  // the call was cancelled (the reader left, or a shutdown)

 private:
  JobWatchers& hub_;
  StreamSlots::Slot slot_;  // given back when the stream is deleted
};

JobWatchers::JobWatchers(JobManager& jobs, std::chrono::milliseconds interval)
    : jobs_(jobs), interval_(interval) {
  jobs_.set_listener(
      [this](const std::string& id, bool state_changed) { job_changed(id, state_changed); });
  dispatcher_ = std::thread([this] { dispatch_loop(); });
}

JobWatchers::~JobWatchers() {
  {
    std::lock_guard lock(changes_mutex_);
    stopping_ = true;
  }
  changes_cv_.notify_all();
  dispatcher_.join();
}

grpc::ServerWriteReactor<pfem::v1::Job>* JobWatchers::refuse(const grpc::Status& status) {
  return new Refused(status);
}

grpc::ServerWriteReactor<pfem::v1::Job>* JobWatchers::watch(const std::string& id,
                                                             StreamSlots::Slot slot) {
  auto* stream = new Stream(*this, id, std::move(slot));
  ++open_;
  {
    std::lock_guard lock(mutex_);
    by_job_[id].insert(stream);
    pending_.insert(stream);
  }
  {
    std::lock_guard lock(changes_mutex_);
    wake_ = true;  // its first message at once
  }
  changes_cv_.notify_one();
  return stream;
}

void JobWatchers::begin_drain() {
  draining_ = true;
  {
    std::lock_guard lock(changes_mutex_);
    wake_ = true;
  }
  changes_cv_.notify_one();
}

void JobWatchers::job_changed(const std::string& id, bool state_changed) {
  bool wake = false;
  {
    std::lock_guard lock(changes_mutex_);
    changed_.insert(id);
    if (state_changed && !wake_) wake = wake_ = true;
  }
  if (wake) changes_cv_.notify_one();
}

void JobWatchers::dispatch_loop() {
  for (;;) {
    std::unordered_set<std::string> changed;
    {
      std::unique_lock lock(changes_mutex_);
      changes_cv_.wait_for(lock, interval_, [&] { return wake_ || stopping_; });
      if (stopping_) return;
      wake_ = false;
      changed.swap(changed_);
    }
    dispatch(std::move(changed));
  }
}

void JobWatchers::dispatch(std::unordered_set<std::string> changed) {
  enum class What { kWrite, kWriteAndFinish, kFinish };
  struct Action {
    Stream* stream;
    What what;
    grpc::Status status;
  };
  struct Snapshot {
    grpc::Status status;
    pfem::v1::Job job;
    std::uint64_t version = 0;
  };
  std::vector<Action> actions;
  {
    std::lock_guard lock(mutex_);
    const bool draining = draining_;
    const auto mark = [&](const std::set<Stream*>& streams) {
      pending_.insert(streams.begin(), streams.end());
    };
    if (draining) {
      for (const auto& entry : by_job_) mark(entry.second);
    } else {
      for (const auto& id : changed) {
        if (const auto it = by_job_.find(id); it != by_job_.end()) mark(it->second);
      }
    }
    const auto now = Clock::now();
    std::map<std::string, Snapshot> snapshots;  // one per job and pass
    for (auto it = pending_.begin(); it != pending_.end();) {
      Stream* s = *it;
      if (s->ended) {
        it = pending_.erase(it);
        continue;
      }
      if (s->writing) {  // looked at again in a pass after its write is done
        ++it;
        continue;
      }
      auto [found, fresh] = snapshots.try_emplace(s->id);
      Snapshot& snapshot = found->second;
      if (fresh) {
        snapshot.status = guarded([&] {
          snapshot.job = jobs_.observe(s->id, &snapshot.version);
          return grpc::Status::OK;
        });
      }
      if (!snapshot.status.ok()) {
        s->ended = true;
        actions.push_back({s, What::kFinish, snapshot.status});
      } else if (finished(snapshot.job.state())) {  // the final state always goes out
        s->message = snapshot.job;
        s->ended = true;
        actions.push_back({s, What::kWriteAndFinish, grpc::Status::OK});
      } else if (draining) {
        s->ended = true;
        actions.push_back({s, What::kFinish,
                           grpc::Status(grpc::StatusCode::UNAVAILABLE,
                                        "server is shutting down; the job is kept and resumes "
                                        "on restart")});
      } else if (snapshot.version == s->sent_version) {  // nothing new
      } else if (now - s->last_sent < interval_) {       // not yet: the next pass
        ++it;
        continue;
      } else {
        s->message = snapshot.job;
        s->sent_version = snapshot.version;
        s->last_sent = now;
        s->writing = true;
        actions.push_back({s, What::kWrite, grpc::Status::OK});
      }
      it = pending_.erase(it);
    }
  }
  // Outside the lock (a stream's reactions take it). A stream is not deleted before the
  // Finish it is due, and `message` is not touched while its write is in flight.
  for (auto& a : actions) {
    switch (a.what) {
      case What::kWrite:
        a.stream->StartWrite(&a.stream->message);
        break;
      case What::kWriteAndFinish:
        a.stream->StartWriteAndFinish(&a.stream->message, grpc::WriteOptions(),
                                      grpc::Status::OK);
        break;
      case What::kFinish:
        a.stream->Finish(a.status);
        break;
    }
  }
}

void JobWatchers::write_done(Stream* stream, bool ok) {
  bool finish = false;
  {
    std::lock_guard lock(mutex_);
    stream->writing = false;
    if (!ok || stream->cancelled) {
      finish = !stream->ended;
      stream->ended = true;
    } else {
      pending_.insert(stream);  // what changed during the write goes out at the next pass
    }
  }
  if (finish) stream->Finish(grpc::Status(grpc::StatusCode::CANCELLED, "watcher left"));
}

void JobWatchers::cancelled(Stream* stream) {
  bool finish = false;
  {
    std::lock_guard lock(mutex_);
    stream->cancelled = true;
    if (!stream->writing && !stream->ended) finish = stream->ended = true;
  }
  if (finish) stream->Finish(grpc::Status(grpc::StatusCode::CANCELLED, "watch cancelled"));
}

void JobWatchers::done(Stream* stream) {
  {
    std::lock_guard lock(mutex_);
    const auto it = by_job_.find(stream->id);
    if (it != by_job_.end()) {
      it->second.erase(stream);
      if (it->second.empty()) by_job_.erase(it);
    }
    pending_.erase(stream);
  }
  delete stream;
  --open_;
}

}  // namespace pfem::server
