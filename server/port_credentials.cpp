#include "server/port_credentials.h"

#include <grpc/grpc.h>
#include <grpc/grpc_security.h>
#include <grpc/slice.h>

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>

namespace pfem::server {
namespace {

std::string read_file(const std::filesystem::path& file, const char* flag) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error(std::string(flag) + ": cannot read " + file.string());
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string_view view(const grpc_slice& slice) {
  return {reinterpret_cast<const char*>(GRPC_SLICE_START_PTR(slice)), GRPC_SLICE_LENGTH(slice)};
}

// grpc_auth_metadata_processor::process: the first `authorization` entry decides, at once (in
// the filter's thread; TokenAuth::accepts is a few hashes).
void check_token(void* state, grpc_auth_context*, const grpc_metadata* metadata, size_t count,
                 grpc_process_auth_metadata_done_cb done, void* user_data) {
  const auto* auth = static_cast<const TokenAuth*>(state);
  bool accepted = false;
  for (size_t i = 0; i < count; ++i) {
    if (view(metadata[i].key) == "authorization") {
      accepted = auth->accepts(view(metadata[i].value));
      break;
    }
  }
  if (accepted) {
    done(user_data, nullptr, 0, nullptr, 0, GRPC_STATUS_OK, nullptr);
  } else {
    done(user_data, nullptr, 0, nullptr, 0, GRPC_STATUS_UNAUTHENTICATED,
         "missing or invalid bearer token");
  }
}

// C core credentials in the C++ API (ServerBuilder::AddListeningPort).
class CoreCredentials final : public grpc::ServerCredentials {
 public:
  explicit CoreCredentials(grpc_server_credentials* credentials) : credentials_(credentials) {}
  ~CoreCredentials() override { grpc_server_credentials_release(credentials_); }
  CoreCredentials(const CoreCredentials&) = delete;
  CoreCredentials& operator=(const CoreCredentials&) = delete;

  void require_token(const TokenAuth& auth) {
    grpc_server_credentials_set_auth_metadata_processor(
        credentials_, {check_token, nullptr, const_cast<TokenAuth*>(&auth)});
  }
  void SetAuthMetadataProcessor(const std::shared_ptr<grpc::AuthMetadataProcessor>&) override {
    throw std::logic_error("port_credentials: the token check is set by require_token");
  }

 private:
  int AddPortToServer(const std::string& address, grpc_server* server) override {
    return grpc_server_add_http2_port(server, address.c_str(), credentials_);
  }

  grpc_server_credentials* credentials_;
};

grpc_server_credentials* tls_credentials(const PortSecurity& security) {
  const std::string key = read_file(security.tls_key, "--tls-key");
  const std::string cert = read_file(security.tls_cert, "--tls-cert");
  grpc_ssl_pem_key_cert_pair pair{key.c_str(), cert.c_str()};
  return grpc_ssl_server_credentials_create_ex(nullptr, &pair, 1,
                                               GRPC_SSL_DONT_REQUEST_CLIENT_CERTIFICATE, nullptr);
}

}  // namespace

std::shared_ptr<grpc::ServerCredentials> port_credentials(const PortSecurity& security,
                                                          const TokenAuth& auth) {
  auto credentials = std::make_shared<CoreCredentials>(
      security.tls_cert.empty() ? grpc_insecure_server_credentials_create()
                                : tls_credentials(security));
  if (auth.enabled()) credentials->require_token(auth);
  return credentials;
}

}  // namespace pfem::server
