// WatchJob streams hold no server thread each (gRPC's callback API, fed by the job manager's
// change listener: server/job_watchers.h). Many more watchers than the process has threads
// each get every update of a job and its final state; a server that drains ends the streams
// of unfinished jobs UNAVAILABLE at once. In-process server on 127.0.0.1 with a fake engine
// whose steps the test paces.
#include "tests/integration/service_test_support.h"

#include <condition_variable>
#include <cstdio>
#include <fstream>
#include <mutex>

namespace {

using namespace pfem::testing;

// Threads of this process (/proc/self/status).
int process_threads() {
  std::ifstream in("/proc/self/status");
  std::string key;
  while (in >> key) {
    if (key == "Threads:") {
      int n = 0;
      in >> n;
      return n;
    }
    in.ignore(1 << 20, '\n');
  }
  return -1;
}

// A fake engine that waits for `go`, then reports `steps` steps `step_seconds` apart (each
// one an update that watchers must all see) and succeeds.
struct PacedEngine {
  int steps = 4;
  double step_seconds = 0.5;
  std::shared_ptr<std::atomic<bool>> go = std::make_shared<std::atomic<bool>>(false);

  pfem::server::JobManager::RunFunction function() const {
    PacedEngine self = *this;
    return [self](const pfem::v1::Model&, const pfem::RunOptions& options) {
      pfem::RunResult r;
      r.responses.columns = {"x"};
      r.responses.time.push_back(0.0);
      r.responses.rows.push_back({0.0});
      r.summary.dt = 0.001;
      r.summary.t_end = self.steps * 0.001;
      const auto cancelled = [&] { return options.cancel && options.cancel->load(); };
      while (!self.go->load() && !cancelled()) {
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
      }
      for (int step = 1; step <= self.steps; ++step) {
        std::this_thread::sleep_for(std::chrono::duration<double>(self.step_seconds));
        if (cancelled()) {
          r.summary.status = pfem::RunStatus::kCancelled;
          r.summary.message = "cancelled";
          return r;
        }
        r.responses.time.push_back(step * 0.001);
        r.responses.rows.push_back({step * 0.001});
        r.summary.steps = step;
        pfem::Progress p;
        p.step = step;
        p.total_steps = self.steps;
        p.time = step * 0.001;
        p.t_end = self.steps * 0.001;
        options.progress(p);
      }
      return r;
    };
  }
};

// Many WatchJob streams on one completion queue, driven by one thread: (state, step) of
// every message each stream receives, and its status.
class Watchers {
 public:
  Watchers(pfem::v1::GradientService::Stub& stub, const std::string& id, int n) : streams_(n) {
    pfem::v1::JobRequest request;
    request.set_job_id(id);
    for (auto& s : streams_) {
      s.reader = stub.PrepareAsyncWatchJob(&s.context, request, &cq_);
      s.reader->StartCall(&s);
    }
    thread_ = std::thread([this] { drive(); });
  }
  ~Watchers() {
    for (auto& s : streams_) s.context.TryCancel();
    wait_ended(30.0);
    cq_.Shutdown();
    thread_.join();
  }

  struct Stream {
    grpc::ClientContext context;
    std::unique_ptr<grpc::ClientAsyncReader<pfem::v1::Job>> reader;
    pfem::v1::Job message;
    std::vector<std::pair<pfem::v1::JobState, long>> received;  // under the mutex
    grpc::Status status;
    bool finishing = false;
    bool ended = false;
  };

  // Waits (at most `seconds`) until every stream has received a message / has ended.
  bool wait_first_message(double seconds) {
    return wait(seconds, [&] { return all([](const Stream& s) { return !s.received.empty() || s.ended; }); });
  }
  bool wait_ended(double seconds) {
    return wait(seconds, [&] { return all([](const Stream& s) { return s.ended; }); });
  }
  // The streams' records (call once they have ended).
  const std::vector<Stream>& streams() const { return streams_; }

 private:
  void drive() {
    void* tag = nullptr;
    bool ok = false;
    while (cq_.Next(&tag, &ok)) {
      auto& s = *static_cast<Stream*>(tag);
      std::lock_guard lock(mutex_);
      if (s.finishing) {  // Finish completed
        s.ended = true;
        cv_.notify_all();
        continue;
      }
      if (ok && s.message.ByteSizeLong() > 0) {  // a message (not the call's start)
        s.received.emplace_back(s.message.state(), s.message.progress().step());
        s.message.Clear();
        cv_.notify_all();
      }
      if (ok) {  // the call started, or a message was read: read the next one
        s.reader->Read(&s.message, &s);
      } else {  // no more messages
        s.finishing = true;
        s.reader->Finish(&s.status, &s);
      }
    }
  }
  template <typename Predicate>
  bool all(Predicate p) const {
    for (const auto& s : streams_) {
      if (!p(s)) return false;
    }
    return true;
  }
  template <typename Condition>
  bool wait(double seconds, Condition done) {
    std::unique_lock lock(mutex_);
    return cv_.wait_for(lock, std::chrono::duration<double>(seconds), done);
  }

  std::vector<Stream> streams_;
  grpc::CompletionQueue cq_;
  std::mutex mutex_;
  std::condition_variable cv_;
  std::thread thread_;
};

pfem::v1::SubmitJobRequest tiny_job() {
  pfem::v1::SubmitJobRequest request;
  *request.mutable_model() = tiny_model();
  return request;
}

}  // namespace

// 400 watchers of one job: the server takes a few threads for them all (a synchronous
// WatchJob held one each: issue 20 measured 300 streams using 300 threads), and each stream
// gets the running state, every one of the job's four steps (0.5 s apart, five times the
// watch interval) and the final state, last, once; then the stream ends OK.
TEST(ServiceWatchers, ManyMoreWatchersThanThreadsEachGetEveryUpdateAndTheFinalState) {
  TempDir dir("watchers");
  constexpr int kWatchers = 400;
  auto options = local_options(dir.path);
  options.workers = 1;
  options.limits.max_streams = kWatchers;
  options.limits.max_streams_per_client = kWatchers;
  PacedEngine engine;
  pfem::server::Server server(options, engine.function());
  auto stub = make_stub(server.address());
  const std::string id = submit_job(*stub, tiny_job());
  ASSERT_EQ(wait_for_state(*stub, id, pfem::v1::JOB_STATE_RUNNING).state(),
            pfem::v1::JOB_STATE_RUNNING);

  const int threads_before = process_threads();
  Watchers watchers(*stub, id, kWatchers);
  ASSERT_TRUE(watchers.wait_first_message(60.0)) << "not every watcher got its first message";
  const int threads_open = process_threads();
  engine.go->store(true);
  ASSERT_TRUE(watchers.wait_ended(60.0)) << "not every watch ended";
  std::printf("%d watchers open: %d -> %d threads in the process (server and client)\n",
              kWatchers, threads_before, threads_open);
  EXPECT_LT(threads_open - threads_before, kWatchers / 8);

  int complete = 0;
  for (const auto& s : watchers.streams()) {
    ASSERT_TRUE(s.status.ok()) << s.status.error_message();
    ASSERT_GE(s.received.size(), 2u);
    EXPECT_EQ(s.received.front(), std::make_pair(pfem::v1::JOB_STATE_RUNNING, 0L));
    EXPECT_EQ(s.received.back(), std::make_pair(pfem::v1::JOB_STATE_SUCCEEDED, long{engine.steps}));
    std::vector<long> steps;  // the distinct steps seen while RUNNING, in order
    for (std::size_t i = 0; i + 1 < s.received.size(); ++i) {
      EXPECT_EQ(s.received[i].first, pfem::v1::JOB_STATE_RUNNING);
      if (steps.empty() || steps.back() != s.received[i].second) {
        steps.push_back(s.received[i].second);
      }
    }
    const std::vector<long> every{0, 1, 2, 3, 4};
    // The last step may come with the final state alone (the job ends right after it).
    const std::vector<long> all_but_last{0, 1, 2, 3};
    EXPECT_TRUE(steps == every || steps == all_but_last) << ::testing::PrintToString(steps);
    complete += steps == every || steps == all_but_last;
  }
  EXPECT_EQ(complete, kWatchers);
}

// Draining ends the stream of a running job UNAVAILABLE at once (the job is kept), and the
// server does not wait its grace period for the watchers.
TEST(ServiceWatchers, ADrainEndsTheStreamsOfUnfinishedJobsUnavailable) {
  TempDir dir("watchers_drain");
  auto options = local_options(dir.path);
  options.workers = 1;
  options.grace_seconds = 30;
  PacedEngine engine;  // never told to go: the job runs until the drain interrupts it
  auto server = std::make_unique<pfem::server::Server>(options, engine.function());
  auto stub = make_stub(server->address());
  const std::string id = submit_job(*stub, tiny_job());
  ASSERT_EQ(wait_for_state(*stub, id, pfem::v1::JOB_STATE_RUNNING).state(),
            pfem::v1::JOB_STATE_RUNNING);
  {
    Watchers watchers(*stub, id, 8);
    ASSERT_TRUE(watchers.wait_first_message(30.0));
    std::thread stopper([&] {
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
      engine.go->store(true);  // the job ends within its steps (2 s), before the grace ends
    });
    const auto start = std::chrono::steady_clock::now();
    std::thread drain([&] { server->shutdown(); });
    ASSERT_TRUE(watchers.wait_ended(10.0));
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_LT(seconds, 1.5);
    for (const auto& s : watchers.streams()) {
      EXPECT_EQ(s.status.error_code(), grpc::StatusCode::UNAVAILABLE);
      EXPECT_TRUE(mentions(s.status, "the job is kept and resumes on restart"));
    }
    drain.join();
    stopper.join();
  }
}
