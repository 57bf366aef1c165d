// WatchJob benchmark: a running job's steps/s with 1, 300 and 1000 WatchJob streams open on
// it, and the server threads they take (one stream at least: it samples the progress).
//   pfem-bench-watchers [--server HOST:PORT [--server-pid PID]] [--model FILE] [--t-end T]
//                       [--watchers 1,300,1000] [--repeat N]
// Without --server it starts an in-process server (one worker, the stream caps raised) on
// 127.0.0.1; an external server needs --max-streams and --max-streams-per-client above the
// largest count. For each count (the counts alternated, --repeat times) it submits the model,
// opens the streams at once (one completion queue, one client thread reading every message),
// and takes the job's speed from its progress: steps and elapsed time between the first
// message a stream got after all were open and the last before the final state. It prints
// a table; it never asserts times.
#include <grpcpp/grpcpp.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "clients/cli/client.h"
#include "engine/cli/arguments.h"
#include "engine/io/model_io.h"
#include "bench/service/bench_server.h"

namespace {

// Threads of process `pid` (/proc/PID/status), -1 when unknown.
int threads_of(const std::string& pid) {
  std::ifstream in("/proc/" + pid + "/status");
  std::string key;
  while (in >> key) {
    if (key == "Threads:") {
      int n = -1;
      in >> n;
      return n;
    }
    in.ignore(1 << 20, '\n');
  }
  return -1;
}

struct Sample {
  long step;
  double elapsed;  // the job's own clock (Progress.elapsed_seconds)
};

// One job watched by `n` streams until it ends; the progress samples of stream 0 taken after
// every stream had its first message, and the process's threads then.
struct Case {
  std::vector<Sample> samples;
  int threads = -1;
  int failed_streams = 0;
  std::string first_error;
  std::string final_state;
};

Case run_case(pfem::v1::GradientService::Stub& stub, const pfem::v1::SubmitJobRequest& submit,
              int n, const std::string& pid) {
  Case result;
  std::string id;
  {
    grpc::ClientContext context;
    pfem::v1::SubmitJobResponse response;
    const auto status = stub.SubmitJob(&context, submit, &response);
    if (!status.ok()) throw std::runtime_error("SubmitJob: " + status.error_message());
    id = response.job_id();
  }
  pfem::v1::JobRequest request;
  request.set_job_id(id);
  struct Stream {
    grpc::ClientContext context;
    std::unique_ptr<grpc::ClientAsyncReader<pfem::v1::Job>> reader;
    pfem::v1::Job message;
    grpc::Status status;
    bool got_first = false;
    bool finishing = false;
  };
  const int streams_n = std::max(1, n);  // stream 0 samples the progress
  std::vector<Stream> streams(static_cast<std::size_t>(streams_n));
  grpc::CompletionQueue cq;
  std::mutex mutex;
  std::condition_variable cv;
  int first = 0;
  int ended = 0;
  bool all_open = false;
  for (auto& s : streams) {
    s.reader = stub.PrepareAsyncWatchJob(&s.context, request, &cq);
    s.reader->StartCall(&s);
  }
  std::thread reader([&] {
    void* tag = nullptr;
    bool ok = false;
    while (cq.Next(&tag, &ok)) {
      auto& s = *static_cast<Stream*>(tag);
      std::lock_guard lock(mutex);
      if (s.finishing) {
        if (!s.status.ok() && result.failed_streams++ == 0) {
          result.first_error = s.status.error_message();
        }
        if (++ended == streams_n) cv.notify_all();
        continue;
      }
      if (ok && s.message.ByteSizeLong() > 0) {
        if (!s.got_first) {
          s.got_first = true;
          if (++first == streams_n) cv.notify_all();
        }
        if (&s == &streams[0]) {
          if (s.message.state() == pfem::v1::JOB_STATE_RUNNING && all_open) {
            result.samples.push_back({s.message.progress().step(),
                                      s.message.progress().elapsed_seconds()});
          } else if (s.message.state() >= pfem::v1::JOB_STATE_SUCCEEDED) {
            result.final_state = pfem::v1::JobState_Name(s.message.state());
            if (s.message.has_error()) result.final_state += " (" + s.message.error().message() + ")";
          }
        }
        s.message.Clear();
      }
      if (ok) {
        s.reader->Read(&s.message, &s);
      } else {
        s.finishing = true;
        s.reader->Finish(&s.status, &s);
      }
    }
  });
  {
    std::unique_lock lock(mutex);
    cv.wait(lock, [&] { return first == streams_n || ended == streams_n; });
    all_open = true;
    result.threads = pid.empty() ? -1 : threads_of(pid);
    cv.wait(lock, [&] { return ended == streams_n; });
  }
  cq.Shutdown();
  reader.join();
  return result;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  try {
    pfem::cli::Arguments a(std::vector<std::string>(argv + 1, argv + argc));
    const auto server_address = a.take_string("--server");
    std::string pid = a.take_string("--server-pid").value_or("");
    const std::string model_file = a.take_string("--model").value_or(
        std::string(PFEM_SOURCE_DIR) + "/examples/hydrostatic.json");
    const double t_end = a.take_double("--t-end").value_or(2.0);
    std::vector<int> counts;
    for (const auto& c : pfem::cli::split(a.take_string("--watchers").value_or("1,300,1000"), ',')) {
      counts.push_back(std::stoi(c));
    }
    const int repeat = a.take_int("--repeat").value_or(3);
    a.expect_done(0);

    pfem::server::ServerOptions options;
    options.workers = 1;
    const int most = *std::max_element(counts.begin(), counts.end());
    options.limits.max_streams = std::max(1, most);
    options.limits.max_streams_per_client = std::max(1, most);
    const pfem::bench::BenchServer server(server_address, "pfem_bench_watchers", options);
    if (server.in_process()) pid = "self";
    const std::string& address = server.address();
    pfem::client::ConnectionOptions connection;
    connection.server = address;
    auto stub = pfem::v1::GradientService::NewStub(pfem::client::make_channel(connection));
    pfem::v1::SubmitJobRequest submit;
    *submit.mutable_model() = pfem::read_model_file(model_file);
    submit.mutable_options()->set_t_end(t_end);

    std::printf("watchers: %s, model %s to t = %g s, %s\n", address.c_str(),
                std::filesystem::path(model_file).filename().c_str(), t_end,
                server.in_process() ? "in-process server (1 worker; threads: the whole process)"
                       : "external server");
    std::map<int, std::vector<double>> rates;
    std::map<int, int> threads;
    int errors = 0;
    for (int r = 0; r < repeat; ++r) {
      for (const int n : counts) {
        const Case c = run_case(*stub, submit, n, pid);
        if (c.failed_streams) {
          std::printf("  %d watchers: %d streams failed: %s\n", n, c.failed_streams,
                      c.first_error.c_str());
          ++errors;
        }
        if (c.samples.size() >= 2) {
          const auto& s0 = c.samples.front();
          const auto& s1 = c.samples.back();
          const double rate = static_cast<double>(s1.step - s0.step) / (s1.elapsed - s0.elapsed);
          rates[n].push_back(rate);
          std::printf("  run %d, %4d watchers: %.0f steps/s (steps %ld..%ld), %s, %d threads\n",
                      r + 1, n, rate, s0.step, s1.step, c.final_state.c_str(), c.threads);
        } else {
          std::printf("  run %d, %4d watchers: too few progress messages (%zu), %s\n", r + 1, n,
                      c.samples.size(), c.final_state.c_str());
          ++errors;
        }
        threads[n] = std::max(threads[n], c.threads);
      }
    }
    std::printf("%9s %14s %9s %9s\n", "watchers", "steps/s (med)", "min", "threads");
    for (const int n : counts) {
      const auto& v = rates[n];
      std::printf("%9d %14.0f %9.0f %9d\n", n, median(v),
                  v.empty() ? 0.0 : *std::min_element(v.begin(), v.end()), threads[n]);
    }
    std::fflush(stdout);
    return errors ? 1 : 0;
  } catch (const std::exception& e) {
    std::cerr << "pfem-bench-watchers: " << e.what() << '\n';
    return 2;
  }
}
