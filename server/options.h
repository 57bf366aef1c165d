#pragma once
// pfem-server settings (style practice 1: defaults in the declaration, a check naming the
// flag and the rule it broke).
#include <cstddef>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "server/limits.h"

namespace pfem::server {

struct ServerOptions {
  std::string listen = "127.0.0.1:50051";  // --listen HOST:PORT (port 0 = any free port)
  std::filesystem::path data_dir;          // --data-dir DIR (required): the SQLite store
  std::filesystem::path token_file;        // --token-file F: bearer tokens; empty = no auth
  int workers = 0;                         // --workers N; 0 = one per core
  std::filesystem::path tls_cert;          // --tls-cert F (PEM), with --tls-key
  std::filesystem::path tls_key;           // --tls-key F (PEM), with --tls-cert
  Limits limits;                           // --max-queued, --max-particles, --max-steps, --max-message-mb
  double grace_seconds = 30.0;             // --grace-seconds S: drain time on SIGTERM/SIGINT
  std::size_t cache_entries = 256;         // --cache-entries N: Evaluate runs kept in memory
  long long max_store_mb = 0;              // --max-store-mb N: cap on the database; 0 = none
  bool reflection = false;                 // --reflection: serve gRPC reflection (the schema)
  // --health-listen HOST:PORT: a second, plaintext port serving only grpc.health.v1.Health
  // (no token), for Kubernetes' native gRPC probes; empty = none.
  std::string health_listen;
  // --max-connection-age S: connections are asked to go away (GOAWAY) after S seconds, so that
  // clients balancing over a DNS name re-resolve and find replicas added by scaling; calls in
  // progress finish first. 0 = never.
  double max_connection_age_seconds = 0.0;
  std::string umbridge_listen;             // --umbridge-listen HOST:PORT: UM-Bridge 1.0 HTTP; empty = off
  // --umbridge-model NAME=FILE (repeatable): models served under NAME over UM-Bridge
  std::vector<std::pair<std::string, std::filesystem::path>> umbridge_models;

  // "--flag: rule" for every invalid setting; empty when valid.
  std::vector<std::string> validate() const;
};

// Parses argv (without argv[0]); throws std::invalid_argument naming the flag.
ServerOptions parse_server_options(const std::vector<std::string>& args);

extern const char* const kServerUsage;

}  // namespace pfem::server
