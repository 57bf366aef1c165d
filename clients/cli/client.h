#pragma once
// A small C++ client layer over pfem.v1.GradientService for pfemctl, the tests and the
// reliability drivers: channels with TLS and bearer tokens, and the reassembly of a GetResult
// stream into one pfem.v1.Result.
#include <grpcpp/grpcpp.h>

#include <filesystem>
#include <memory>
#include <string>

#include "pfem/v1/service.grpc.pb.h"

namespace pfem::client {

struct ConnectionOptions {
  std::string server;      // HOST:PORT
  std::string token;       // bearer token; empty = none
  std::string tls_ca_pem;  // PEM of the CA that signed the server's certificate; empty = plaintext
  int max_message_mb = 256;  // largest message accepted from the server
};

// The first token of a token file (one per line; blank lines and '#' comments skipped).
// Throws std::runtime_error when unreadable or empty.
std::string read_token_file(const std::filesystem::path& file);

std::shared_ptr<grpc::Channel> make_channel(const ConnectionOptions& options);

// Adds the bearer token (when there is one) to a call's metadata.
void authorize(grpc::ClientContext& context, const ConnectionOptions& options);

// Reads job_id's result stream and reassembles it. On OK, *result (and *job when not null)
// hold the result; a malformed stream gives DATA_LOSS.
grpc::Status fetch_result(pfem::v1::GradientService::Stub& stub, const ConnectionOptions& options,
                          const std::string& job_id, pfem::v1::Result* result,
                          pfem::v1::Job* job = nullptr);

}  // namespace pfem::client
