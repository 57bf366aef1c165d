#include "server/status.h"

#include <algorithm>
#include <iostream>
#include <new>

#include "server/store.h"

namespace pfem::server {

void throw_invalid(const std::vector<FieldError>& errors) {
  std::string message;
  for (const auto& e : errors) {
    if (!message.empty()) message += '\n';
    message += e.to_string();
  }
  throw ServiceError(grpc::StatusCode::INVALID_ARGUMENT, message);
}

namespace {

grpc::Status unbounded_status_of_current_exception() {
  try {
    throw;
  } catch (const ServiceError& e) {
    return {e.code(), e.what()};
  } catch (const ModelError& e) {
    std::string message;
    for (const auto& fe : e.errors()) {
      if (!message.empty()) message += '\n';
      message += fe.to_string();
    }
    if (message.empty()) message = e.what();
    return {grpc::StatusCode::INVALID_ARGUMENT, message};
  } catch (const StoreError& e) {
    std::cerr << "pfem-server: store error: " << e.what() << '\n';
    return {e.full() ? grpc::StatusCode::RESOURCE_EXHAUSTED : grpc::StatusCode::INTERNAL,
            std::string("store: ") + e.what()};
  } catch (const std::bad_alloc&) {
    return {grpc::StatusCode::RESOURCE_EXHAUSTED, "out of memory"};
  } catch (const std::exception& e) {
    std::cerr << "pfem-server: internal error: " << e.what() << '\n';
    return {grpc::StatusCode::INTERNAL, "internal error"};
  } catch (...) {
    std::cerr << "pfem-server: internal error (unknown exception)\n";
    return {grpc::StatusCode::INTERNAL, "internal error"};
  }
}

}  // namespace

std::string bounded_message(const std::string& message) {
  if (message.size() <= kMaxStatusMessageBytes) return message;
  const std::size_t total = std::count(message.begin(), message.end(), '\n') + 1;
  std::string kept;
  std::size_t lines = 0;
  for (std::size_t start = 0; start < message.size(); ++lines) {
    std::size_t end = message.find('\n', start);
    if (end == std::string::npos) end = message.size();
    std::string line = message.substr(start, end - start);
    if (line.size() > kMaxStatusLineBytes) {
      line = line.substr(0, kMaxStatusLineBytes) + "... (" + std::to_string(line.size()) +
             " characters)";
    }
    if (kept.size() + line.size() + 100 > kMaxStatusMessageBytes) break;
    kept += (kept.empty() ? "" : "\n") + line;
    start = end + 1;
  }
  if (lines < total) {
    kept += "\n... and " + std::to_string(total - lines) + " more (" + std::to_string(total) +
            " in all)";
  }
  return kept;
}

grpc::Status status_from_current_exception() {
  const grpc::Status status = unbounded_status_of_current_exception();
  return {status.error_code(), bounded_message(status.error_message())};
}

grpc::Status guarded(const std::function<grpc::Status()>& body) {
  try {
    return body();
  } catch (...) {
    return status_from_current_exception();
  }
}

}  // namespace pfem::server
