#pragma once
// The credentials of the main port (--listen): TLS (--tls-cert/--tls-key) or plaintext, and
// with --token-file the bearer token checked from a call's metadata by gRPC's server auth
// filter, before any message of the call is read: an unauthenticated peer's request body is
// never taken in (8 unauthenticated 60 MB requests at once had raised the RSS by 380 MB when
// the check was in the handler), and every service of the port needs the token, the health
// service too (without a token: --health-listen).
//
// gRPC's C++ InsecureServerCredentials() refuses an auth metadata processor (an assertion);
// the C core's plaintext credentials take one, so both kinds are built from the C API here.
#include <grpcpp/security/server_credentials.h>

#include <filesystem>
#include <memory>

#include "server/auth.h"

namespace pfem::server {

struct PortSecurity {
  std::filesystem::path tls_cert;  // empty: plaintext
  std::filesystem::path tls_key;
};

// `auth` must outlive the server the credentials are used by; a disabled `auth` checks
// nothing. Throws std::runtime_error naming the flag when a TLS file cannot be read.
std::shared_ptr<grpc::ServerCredentials> port_credentials(const PortSecurity& security,
                                                          const TokenAuth& auth);

}  // namespace pfem::server
