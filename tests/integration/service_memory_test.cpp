// Memory stays bounded whatever clients do, measured on the pfem-server binary (its VmRSS and
// VmHWM): result streams that are never read hold neither a copy of the result each nor a
// stream slot beyond the caps; unauthenticated requests are refused before their body is read.
// And the stream caps (in total and per client) refuse with RESOURCE_EXHAUSTED naming the cap.
#include "tests/integration/server_process.h"
#include "tests/integration/service_test_support.h"

#include <cstdio>
#include <fstream>

namespace {

using namespace pfem::testing;

// The tiny model with 48 pressure recorders over 20 000 steps: with DDM in two parameters a
// result of 48 x 3 columns x 20 001 rows, 23 MB, in about 5 s.
pfem::v1::SubmitJobRequest big_result_job() {
  pfem::v1::SubmitJobRequest request;
  auto& model = *request.mutable_model();
  model = tiny_model();
  model.clear_recorders();
  for (int i = 1; i <= 48; ++i) {
    auto* r = model.add_recorders();
    r->set_name("p" + std::to_string(i));
    r->set_quantity("p");
    r->mutable_point()->set_x(0.001 * i);
    r->mutable_point()->set_y(0.0);
  }
  request.mutable_options()->set_t_end(40.0);
  request.mutable_options()->set_sensitivity(pfem::v1::SENSITIVITY_METHOD_DDM);
  return request;
}

// A GetResult stream opened and never read.
struct Unread {
  grpc::ClientContext context;
  std::unique_ptr<grpc::ClientReader<pfem::v1::GetResultResponse>> reader;
};

}  // namespace

TEST(ServiceMemory, NeverReadResultStreamsNeitherCopyTheResultNorExceedTheCap) {
  TempDir dir("unread_streams");
  const std::vector<std::string> flags{"--data-dir", (dir.path / "data").string(), "--workers",
                                       "1", "--max-streams-per-client", "32"};
  std::string id;
  std::size_t bytes = 0;
  {
    ServerProcess first(flags);
    auto stub = make_stub(first.address());
    id = submit_job(*stub, big_result_job());
    ASSERT_EQ(wait_for_state(*stub, id, pfem::v1::JOB_STATE_SUCCEEDED, 120).state(),
              pfem::v1::JOB_STATE_SUCCEEDED);
    bytes = result_bytes(*stub, first.address(), id).size();
    ASSERT_GT(bytes, 20u << 20);
  }
  // A fresh server: its peak is the streams' alone.
  ServerProcess server(flags);
  const double result_mb = static_cast<double>(bytes) / (1 << 20);
  const double start_mb = server.rss_mb();
  // A reader that reads nothing takes in no more than its flow-control window (64 KiB; gRPC's
  // bandwidth probe would widen it and take in the whole result).
  grpc::ChannelArguments slow_reader;
  slow_reader.SetInt(GRPC_ARG_HTTP2_BDP_PROBE, 0);
  slow_reader.SetInt(GRPC_ARG_HTTP2_STREAM_LOOKAHEAD_BYTES, 65536);
  auto stub = pfem::v1::GradientService::NewStub(grpc::CreateCustomChannel(
      server.address(), grpc::InsecureChannelCredentials(), slow_reader));
  constexpr int kStreams = 40;  // over the 32 per client
  std::vector<std::unique_ptr<Unread>> streams;
  pfem::v1::JobRequest request;
  request.set_job_id(id);
  for (int i = 0; i < kStreams; ++i) {
    auto s = std::make_unique<Unread>();
    s->reader = stub->GetResult(&s->context, request);
    streams.push_back(std::move(s));
  }
  // A refused stream ends at once; an accepted one sends its header, then what its reader's
  // window takes, and waits.
  int refused = 0;
  for (auto& s : streams) {
    pfem::v1::GetResultResponse header;
    if (s->reader->Read(&header)) continue;
    const auto status = s->reader->Finish();
    s.reset();
    ++refused;
    EXPECT_EQ(status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
    EXPECT_EQ(status.error_message(),
              "max-streams-per-client limit reached: 32 WatchJob and GetResult streams of "
              "ipv4:127.0.0.1 are open, the limit is 32");
  }
  std::this_thread::sleep_for(std::chrono::seconds(2));
  const double peak_mb = server.peak_rss_mb();
  const int threads = server.threads();
  for (auto& s : streams) {
    if (!s) continue;
    s->context.TryCancel();
    EXPECT_EQ(s->reader->Finish().error_code(), grpc::StatusCode::CANCELLED);
  }
  streams.clear();
  std::this_thread::sleep_for(std::chrono::seconds(1));
  const double end_mb = server.rss_mb();
  std::printf("result %.1f MB; %d unread streams (%d refused), %d server threads: RSS %.0f MB "
              "-> peak %.0f MB -> %.0f MB after they closed\n",
              result_mb, kStreams, refused, threads, start_mb, peak_mb, end_mb);
  EXPECT_EQ(refused, kStreams - 32);
  // One shared copy of the result (and its encoding in flight), not one per stream.
  EXPECT_LT(peak_mb - start_mb, 3.0 * result_mb);
  EXPECT_LT(end_mb - start_mb, result_mb);
  // And the server still answers, the result intact.
  EXPECT_EQ(result_bytes(*stub, server.address(), id).size(), bytes);
}

TEST(ServiceMemory, UnauthenticatedRequestsAreRefusedBeforeTheirBodyIsRead) {
  TempDir dir("unauthenticated_bodies");
  std::ofstream(dir.path / "tokens") << "the-token\n";
  ServerProcess server({"--data-dir", (dir.path / "data").string(), "--token-file",
                        (dir.path / "tokens").string(), "--workers", "1"});
  pfem::v1::ValidateModelRequest request;
  *request.mutable_model() = tiny_model();
  request.mutable_model()->set_name(std::string(60 << 20, 'n'));  // a 60 MB request
  const auto send = [&](const std::string& token) {
    auto stub = make_stub(server.address());  // a connection each
    grpc::ClientContext context;
    if (!token.empty()) context.AddMetadata("authorization", "Bearer " + token);
    pfem::v1::ValidateModelResponse response;
    return stub->ValidateModel(&context, request, &response);
  };
  const double start_mb = server.rss_mb();
  constexpr int kClients = 8;
  std::vector<grpc::Status> statuses(kClients);
  std::vector<std::thread> clients;
  for (int i = 0; i < kClients; ++i) clients.emplace_back([&, i] { statuses[i] = send(""); });
  for (auto& t : clients) t.join();
  const double peak_mb = server.peak_rss_mb();
  for (const auto& s : statuses) {
    EXPECT_EQ(s.error_code(), grpc::StatusCode::UNAUTHENTICATED);
    EXPECT_EQ(s.error_message(), "missing or invalid bearer token");
  }
  // The control: one authenticated request of the same size is read.
  const auto accepted = send("the-token");
  const double read_mb = server.peak_rss_mb();
  std::printf("%d unauthenticated 60 MB requests: RSS %.0f -> peak %.0f MB; one authenticated: "
              "peak %.0f MB\n",
              kClients, start_mb, peak_mb, read_mb);
  EXPECT_TRUE(accepted.ok()) << accepted.error_message();
  // Less than one request's body for all eight: none was read. What they raise is what HTTP/2
  // flow control lets each connection buffer before the refusal (measured 9 to 22 MB for the
  // eight, depending on how far the windows had grown); reading them would take 480 MB.
  EXPECT_LT(peak_mb - start_mb, 60.0);
  EXPECT_GT(read_mb - start_mb, 60.0);
}

// Two watches open (from two channels of the one client address), then a third: its status,
// and whether a fourth is taken once the first has closed.
std::pair<grpc::Status, bool> third_watch(long max_streams, long max_per_client) {
  TempDir dir("stream_caps");
  FakeEngine engine;
  engine.steps = 100000;
  engine.step_seconds = 0.001;  // running throughout
  auto options = local_options(dir.path);
  options.limits.max_streams = max_streams;
  options.limits.max_streams_per_client = max_per_client;
  pfem::server::Server server(options, engine.function());
  auto stub = make_stub(server.address());
  auto other = make_stub(server.address());
  pfem::v1::SubmitJobRequest submit_request;
  *submit_request.mutable_model() = tiny_model();
  pfem::v1::JobRequest request;
  request.set_job_id(submit_job(*stub, submit_request));
  struct Watch {
    grpc::ClientContext context;
    std::unique_ptr<grpc::ClientReader<pfem::v1::Job>> reader;
    bool read = false;
  };
  const auto watch = [&](pfem::v1::GradientService::Stub& on) {
    auto w = std::make_unique<Watch>();
    w->reader = on.WatchJob(&w->context, request);
    pfem::v1::Job job;
    w->read = w->reader->Read(&job);
    return w;
  };
  auto first = watch(*stub);
  auto second = watch(*other);
  EXPECT_TRUE(first->read && second->read);
  auto third = watch(*stub);
  EXPECT_FALSE(third->read);
  const grpc::Status refused = third->reader->Finish();
  first->context.TryCancel();
  first->reader->Finish();
  // The slot given back (once the server has seen the cancel) is taken again.
  auto fourth = watch(*stub);
  for (int i = 0; i < 50 && !fourth->read; ++i) {
    fourth->reader->Finish();
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    fourth = watch(*stub);
  }
  for (auto* w : {second.get(), fourth.get()}) {
    w->context.TryCancel();
    w->reader->Finish();
  }
  return {refused, fourth->read};
}

TEST(ServiceMemory, StreamCapsRefuseNamingTheCap) {
  const auto [per_client, retaken_per_client] = third_watch(10, 2);
  EXPECT_EQ(per_client.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_EQ(per_client.error_message(),
            "max-streams-per-client limit reached: 2 WatchJob and GetResult streams of "
            "ipv4:127.0.0.1 are open, the limit is 2");
  EXPECT_TRUE(retaken_per_client);
  const auto [total, retaken_total] = third_watch(2, 10);
  EXPECT_EQ(total.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_EQ(total.error_message(),
            "max-streams limit reached: 2 WatchJob and GetResult streams are open, the limit "
            "is 2");
  EXPECT_TRUE(retaken_total);
}
