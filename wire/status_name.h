#pragma once
// The names of gRPC status codes, for the server's logs and the clients' messages.
#include <grpcpp/support/status.h>

#include <string>

namespace pfem::wire {

// "INVALID_ARGUMENT", "NOT_FOUND", ... (for logs and the CLI).
std::string status_code_name(grpc::StatusCode code);

}  // namespace pfem::wire
