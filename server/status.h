#pragma once
// The service's one place where errors become gRPC statuses (style practice 8).
//
// Handlers throw ServiceError (or let pfem::ModelError, StoreError and std::exception escape);
// guarded() runs a handler body, catches everything and converts it once, so no exception
// ever crosses into gRPC. Mapping:
//   ServiceError(code, msg)  -> code, msg
//   pfem::ModelError         -> INVALID_ARGUMENT, every "path: message", one per line
//   StoreError               -> INTERNAL "store: ...", RESOURCE_EXHAUSTED when full
//                               (the database or the disk)
//   std::bad_alloc           -> RESOURCE_EXHAUSTED "out of memory"
//   anything else            -> INTERNAL (the detail goes to the server log only)
// The codes' names (for logs and the CLI) are wire/status_name.h, shared with the clients.
#include <grpcpp/support/status.h>

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/io/model_io.h"

namespace pfem::server {

// An error with the gRPC status it maps to.
class ServiceError : public std::runtime_error {
 public:
  ServiceError(grpc::StatusCode code, const std::string& message)
      : std::runtime_error(message), code_(code) {}
  grpc::StatusCode code() const { return code_; }

 private:
  grpc::StatusCode code_;
};

// INVALID_ARGUMENT carrying field errors (message: one "path: message" per line).
[[noreturn]] void throw_invalid(const std::vector<FieldError>& errors);

// The status travels in the response's trailing metadata, which clients cap (8 KiB by
// default: a longer one fails the call as RESOURCE_EXHAUSTED "received initial metadata size
// exceeds limit"). Messages are cut to this many bytes, lines to kMaxStatusLineBytes.
inline constexpr std::size_t kMaxStatusMessageBytes = 4096;
inline constexpr std::size_t kMaxStatusLineBytes = 300;

// `message` within kMaxStatusMessageBytes: its first lines (each cut to kMaxStatusLineBytes),
// then "... and N more (M errors in all)".
std::string bounded_message(const std::string& message);

// The status of the exception currently being handled (call inside a catch block), its
// message bounded.
grpc::Status status_from_current_exception();

// Runs body; returns its status, or the converted exception it threw.
grpc::Status guarded(const std::function<grpc::Status()>& body);

}  // namespace pfem::server
