// pfem-server: serves pfem.v1.GradientService (plus grpc.health.v1.Health and reflection).
//   pfem-server --listen 127.0.0.1:50051 --data-dir /var/lib/pfem [--token-file tokens]
// Prints "pfem-server listening on HOST:PORT" on stdout once it accepts calls (with
// --listen HOST:0 the port is chosen by the system; with --umbridge-listen, a line
// "pfem-server UM-Bridge on http://HOST:PORT" comes first), then "pfem-server health on
// HOST:PORT" with --health-listen. SIGTERM or SIGINT drains it.
#include <csignal>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "server/options.h"
#include "server/server.h"

int main(int argc, char** argv) {
  // Block the stop signals in every thread; the main thread waits for them with sigwait.
  sigset_t stop_signals;
  sigemptyset(&stop_signals);
  sigaddset(&stop_signals, SIGTERM);
  sigaddset(&stop_signals, SIGINT);
  pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);
  std::signal(SIGPIPE, SIG_IGN);

  const std::vector<std::string> args(argv + 1, argv + argc);
  if (!args.empty() && (args[0] == "--help" || args[0] == "-h")) {
    std::cout << pfem::server::kServerUsage;
    return 0;
  }
  try {
    const auto options = pfem::server::parse_server_options(args);
    pfem::server::Server server(options);
    if (!server.umbridge_address().empty()) {
      std::cout << "pfem-server UM-Bridge on http://" << server.umbridge_address() << std::endl;
    }
    std::cout << "pfem-server listening on " << server.address() << std::endl;
    if (server.health_port() != 0) {
      const auto& h = options.health_listen;
      std::cout << "pfem-server health on " << h.substr(0, h.rfind(':')) << ":"
                << server.health_port() << std::endl;
    }
    int signal = 0;
    sigwait(&stop_signals, &signal);
    std::cerr << "pfem-server: " << (signal == SIGTERM ? "SIGTERM" : "SIGINT")
              << ": draining (grace " << options.grace_seconds << " s)\n";
    server.shutdown();
    std::cerr << "pfem-server: stopped\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "pfem-server: " << e.what() << '\n' << pfem::server::kServerUsage;
    return 2;
  }
}
