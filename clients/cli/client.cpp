#include "clients/cli/client.h"

#include <algorithm>
#include <chrono>
#include <fstream>
#include <stdexcept>
#include <thread>

namespace pfem::client {

std::string read_token_file(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error("--token-file: cannot read " + file.string());
  std::string line;
  while (std::getline(in, line)) {
    const auto first = line.find_first_not_of(" \t\r\n");
    if (first == std::string::npos || line[first] == '#') continue;
    const auto last = line.find_last_not_of(" \t\r\n");
    return line.substr(first, last - first + 1);
  }
  throw std::runtime_error("--token-file: no token in " + file.string());
}

std::shared_ptr<grpc::Channel> make_channel(const ConnectionOptions& options) {
  std::shared_ptr<grpc::ChannelCredentials> credentials = grpc::InsecureChannelCredentials();
  if (!options.tls_ca_pem.empty()) {
    grpc::SslCredentialsOptions ssl;
    ssl.pem_root_certs = options.tls_ca_pem;
    credentials = grpc::SslCredentials(ssl);
  }
  grpc::ChannelArguments args;
  args.SetMaxReceiveMessageSize(options.max_message_mb * 1024 * 1024);
  args.SetLoadBalancingPolicyName("round_robin");
  return grpc::CreateCustomChannel(options.server, credentials, args);
}

grpc::Status call_with_retries(const std::function<grpc::Status()>& attempt, int max_attempts,
                               int* retries) {
  double wait = 0.1;
  for (int k = 1;; ++k) {
    const grpc::Status status = attempt();
    if (status.error_code() != grpc::StatusCode::UNAVAILABLE || k >= max_attempts) return status;
    if (retries) ++*retries;
    std::this_thread::sleep_for(std::chrono::duration<double>(wait));
    wait = std::min(2.0 * wait, 2.0);
  }
}

void authorize(grpc::ClientContext& context, const ConnectionOptions& options) {
  if (!options.token.empty()) context.AddMetadata("authorization", "Bearer " + options.token);
}

namespace {

// Appends a chunk's values at their offset into the right column of h.
bool apply_chunk(pfem::v1::Histories& h, const pfem::v1::HistoriesChunk& chunk) {
  google::protobuf::RepeatedField<double>* values = nullptr;
  if (chunk.column() == -1) {
    values = h.mutable_time();
  } else if (chunk.column() >= 0 && chunk.column() < h.columns_size()) {
    values = h.mutable_columns(chunk.column())->mutable_values();
  } else {
    return false;
  }
  if (chunk.offset() != values->size()) return false;  // slices arrive in order
  values->Add(chunk.values().begin(), chunk.values().end());
  return true;
}

}  // namespace

grpc::Status fetch_result(pfem::v1::GradientService::Stub& stub, const ConnectionOptions& options,
                          const std::string& job_id, pfem::v1::Result* result,
                          pfem::v1::Job* job) {
  grpc::ClientContext context;
  authorize(context, options);
  pfem::v1::JobRequest request;
  request.set_job_id(job_id);
  auto reader = stub.GetResult(&context, request);
  pfem::v1::GetResultResponse message;
  pfem::v1::Result out;
  bool have_header = false;
  bool malformed = false;
  while (reader->Read(&message)) {
    if (message.has_header()) {
      if (have_header) malformed = true;
      have_header = true;
      const auto& header = message.header();
      *out.mutable_summary() = header.summary();
      if (job) *job = header.job();
      for (const auto& name : header.response_columns()) {
        out.mutable_responses()->add_columns()->set_name(name);
      }
      for (const auto& name : header.sensitivity_columns()) {
        out.mutable_sensitivities()->add_columns()->set_name(name);
      }
    } else if (message.has_chunk() && have_header) {
      const auto& chunk = message.chunk();
      auto& h = chunk.kind() == pfem::v1::HISTORIES_KIND_SENSITIVITIES
                    ? *out.mutable_sensitivities()
                    : *out.mutable_responses();
      if (!apply_chunk(h, chunk)) malformed = true;
    } else {
      malformed = true;
    }
  }
  const grpc::Status status = reader->Finish();
  if (!status.ok()) return status;
  if (malformed || !have_header) {
    return {grpc::StatusCode::DATA_LOSS, "malformed GetResult stream"};
  }
  if (out.sensitivities().columns_size() > 0 && out.sensitivities().time_size() == 0) {
    // Sensitivities share the responses' sample times when the server sends none of their own.
    *out.mutable_sensitivities()->mutable_time() = out.responses().time();
  }
  *result = std::move(out);
  return grpc::Status::OK;
}

}  // namespace pfem::client
