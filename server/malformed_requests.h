#pragma once
// A request whose bytes do not parse as its message gets INVALID_ARGUMENT naming the method,
// not gRPC's own INTERNAL with an empty message (grpcpp's GenericDeserialize answers
// INTERNAL with InitializationErrorString(), which is empty for proto3 messages). The
// handlers never answer INTERNAL without a message ("internal error", "store: ..."), so that
// status, as it is sent, can only be a request that failed to parse.
#include <grpcpp/support/server_interceptor.h>

namespace pfem::server {

class MalformedRequestsFactory : public grpc::experimental::ServerInterceptorFactoryInterface {
 public:
  grpc::experimental::Interceptor* CreateServerInterceptor(
      grpc::experimental::ServerRpcInfo* info) override;
};

}  // namespace pfem::server
