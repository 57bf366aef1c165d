#pragma once
// A small C++ client layer over pfem.v1.GradientService for pfemctl, the tests and the
// reliability drivers: channels with TLS and bearer tokens, round_robin load balancing over
// every address a target resolves to, retries of idempotent calls, and the reassembly of a
// GetResult stream into one pfem.v1.Result.
#include <grpcpp/grpcpp.h>

#include <filesystem>
#include <functional>
#include <memory>
#include <string>

#include "pfem/v1/service.grpc.pb.h"

namespace pfem::client {

struct ConnectionOptions {
  // Any gRPC target: HOST:PORT, dns:///NAME:PORT (every address of the name, e.g. a
  // Kubernetes headless Service), ipv4:A:P,B:P (a fixed list of replicas).
  std::string server;
  std::string token;       // bearer token; empty = none
  std::string tls_ca_pem;  // PEM of the CA that signed the server's certificate; empty = plaintext
  int max_message_mb = 256;  // largest message accepted from the server
};

// The first token of a token file (one per line; blank lines and '#' comments skipped).
// Throws std::runtime_error when unreadable or empty.
std::string read_token_file(const std::filesystem::path& file);

// A channel with the round_robin policy: calls are spread over every READY address of the
// target, and an address that stops answering is skipped until it reconnects.
std::shared_ptr<grpc::Channel> make_channel(const ConnectionOptions& options);

// Retries of idempotent calls (an Evaluate of a stored model gives the same answer on every
// replica): `attempt` makes one call with a fresh ClientContext; it is repeated while it
// returns UNAVAILABLE (a replica died or is draining), at most `max_attempts` times in all,
// after 0.1, 0.2, 0.4 ... s (at most 2 s). `retries`, when given, is increased per retry.
grpc::Status call_with_retries(const std::function<grpc::Status()>& attempt, int max_attempts,
                               int* retries = nullptr);

// Adds the bearer token (when there is one) to a call's metadata.
void authorize(grpc::ClientContext& context, const ConnectionOptions& options);

// Reads job_id's result stream and reassembles it. On OK, *result (and *job when not null)
// hold the result; a malformed stream gives DATA_LOSS.
grpc::Status fetch_result(pfem::v1::GradientService::Stub& stub, const ConnectionOptions& options,
                          const std::string& job_id, pfem::v1::Result* result,
                          pfem::v1::Job* job = nullptr);

}  // namespace pfem::client
