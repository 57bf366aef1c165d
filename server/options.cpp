#include "server/options.h"

#include <cmath>
#include <stdexcept>

#include "engine/cli/arguments.h"

namespace pfem::server {

const char* const kServerUsage =
    "usage: pfem-server --listen HOST:PORT --data-dir DIR [--token-file F] [--workers N]\n"
    "                   [--tls-cert F --tls-key F] [--max-queued N] [--max-particles N]\n"
    "                   [--max-steps N] [--max-message-mb N] [--grace-seconds S]\n"
    "                   [--cache-entries N] [--max-store-mb N] [--max-geometry-points N]\n"
    "                   [--max-fiber-points N] [--max-wall-nodes N] [--reflection]\n"
    "                   [--health-listen HOST:PORT] [--max-connection-age S]\n"
    "                   [--max-streams N] [--max-streams-per-client N]\n"
    "                   [--umbridge-listen HOST:PORT [--umbridge-model NAME=FILE ...]]\n";

std::vector<std::string> ServerOptions::validate() const {
  std::vector<std::string> errors;
  if (listen.empty() || listen.find(':') == std::string::npos) {
    errors.push_back("--listen: must be HOST:PORT");
  }
  if (data_dir.empty()) errors.push_back("--data-dir: required");
  if (workers < 0) errors.push_back("--workers: must be >= 0 (0 = one per core)");
  if (tls_cert.empty() != tls_key.empty()) {
    errors.push_back("--tls-cert/--tls-key: give both or neither");
  }
  if (limits.max_queued < 1) errors.push_back("--max-queued: must be >= 1");
  if (limits.max_particles < 1) errors.push_back("--max-particles: must be >= 1");
  if (limits.max_steps < 1) errors.push_back("--max-steps: must be >= 1");
  if (limits.max_geometry_points < 1) errors.push_back("--max-geometry-points: must be >= 1");
  if (limits.max_fiber_points < 1) errors.push_back("--max-fiber-points: must be >= 1");
  if (limits.max_wall_nodes < 1) errors.push_back("--max-wall-nodes: must be >= 1");
  if (limits.max_streams < 1) errors.push_back("--max-streams: must be >= 1");
  if (limits.max_streams_per_client < 1) {
    errors.push_back("--max-streams-per-client: must be >= 1");
  }
  if (limits.max_message_mb < 1 || limits.max_message_mb > 2047) {
    errors.push_back("--max-message-mb: must be in [1, 2047]");
  }
  if (!(grace_seconds >= 0.0) || !std::isfinite(grace_seconds)) {
    errors.push_back("--grace-seconds: must be >= 0");
  }
  if (!health_listen.empty() && health_listen.find(':') == std::string::npos) {
    errors.push_back("--health-listen: must be HOST:PORT");
  }
  const bool any_port = listen.size() > 2 && listen.compare(listen.size() - 2, 2, ":0") == 0;
  if (!health_listen.empty() && health_listen == listen && !any_port) {
    errors.push_back("--health-listen: must differ from --listen");
  }
  if (!(max_connection_age_seconds >= 0.0) || !std::isfinite(max_connection_age_seconds) ||
      max_connection_age_seconds > 2147483.0) {
    errors.push_back("--max-connection-age: must be in [0, 2147483] seconds (0 = never)");
  }
  if (!umbridge_listen.empty() && umbridge_listen.find(':') == std::string::npos) {
    errors.push_back("--umbridge-listen: must be HOST:PORT");
  }
  if (umbridge_listen.empty() && !umbridge_models.empty()) {
    errors.push_back("--umbridge-model: needs --umbridge-listen");
  }
  for (std::size_t i = 0; i < umbridge_models.size(); ++i) {
    const auto& [name, file] = umbridge_models[i];
    if (name.empty() || file.empty()) errors.push_back("--umbridge-model: must be NAME=FILE");
    for (std::size_t j = 0; j < i; ++j) {
      if (umbridge_models[j].first == name) {
        errors.push_back("--umbridge-model: the name '" + name + "' is given twice");
      }
    }
  }
  return errors;
}

ServerOptions parse_server_options(const std::vector<std::string>& args) {
  cli::Arguments a(args);
  ServerOptions o;
  if (auto v = a.take_string("--listen")) o.listen = *v;
  if (auto v = a.take_string("--data-dir")) o.data_dir = *v;
  if (auto v = a.take_string("--token-file")) o.token_file = *v;
  if (auto v = a.take_int("--workers")) o.workers = *v;
  if (auto v = a.take_string("--tls-cert")) o.tls_cert = *v;
  if (auto v = a.take_string("--tls-key")) o.tls_key = *v;
  if (auto v = a.take_double("--max-queued")) o.limits.max_queued = static_cast<long>(*v);
  if (auto v = a.take_double("--max-particles")) o.limits.max_particles = static_cast<long>(*v);
  if (auto v = a.take_double("--max-steps")) o.limits.max_steps = static_cast<long>(*v);
  if (auto v = a.take_int("--max-message-mb")) o.limits.max_message_mb = *v;
  if (auto v = a.take_double("--max-geometry-points")) o.limits.max_geometry_points = static_cast<long>(*v);
  if (auto v = a.take_double("--max-fiber-points")) o.limits.max_fiber_points = static_cast<long>(*v);
  if (auto v = a.take_double("--max-wall-nodes")) o.limits.max_wall_nodes = static_cast<long>(*v);
  if (auto v = a.take_double("--max-streams")) o.limits.max_streams = static_cast<long>(*v);
  if (auto v = a.take_double("--max-streams-per-client")) {
    o.limits.max_streams_per_client = static_cast<long>(*v);
  }
  if (auto v = a.take_double("--grace-seconds")) o.grace_seconds = *v;
  if (auto v = a.take_string("--health-listen")) o.health_listen = *v;
  if (auto v = a.take_double("--max-connection-age")) o.max_connection_age_seconds = *v;
  if (auto v = a.take_int("--cache-entries")) {
    if (*v < 0) throw std::invalid_argument("--cache-entries: must be >= 0");
    o.cache_entries = static_cast<std::size_t>(*v);
  }
  if (auto v = a.take_int("--max-store-mb")) {
    if (*v < 0) throw std::invalid_argument("--max-store-mb: must be >= 0 (0 = no cap)");
    o.max_store_mb = *v;
  }
  o.reflection = a.take_flag("--reflection");
  if (auto v = a.take_string("--umbridge-listen")) o.umbridge_listen = *v;
  while (auto v = a.take_string("--umbridge-model")) {
    const auto eq = v->find('=');
    if (eq == std::string::npos) throw std::invalid_argument("--umbridge-model: must be NAME=FILE");
    o.umbridge_models.emplace_back(v->substr(0, eq), v->substr(eq + 1));
  }
  a.expect_done(0);
  return o;
}

}  // namespace pfem::server
