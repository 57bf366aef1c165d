// TLS: a server with --tls-cert/--tls-key answers a client that trusts its certificate (with
// the bearer token on top), and nothing else: a plaintext client or one trusting another CA
// fails with UNAVAILABLE. The certificates are made here with OpenSSL (self-signed, P-256,
// SAN 127.0.0.1).
#include "tests/integration/service_test_support.h"

#include <openssl/evp.h>
#include <openssl/pem.h>
#include <openssl/x509.h>
#include <openssl/x509v3.h>

#include <fstream>

namespace {

using namespace pfem::testing;

struct Pem {
  std::string cert;
  std::string key;
};

std::string bio_string(BIO* bio) {
  char* data = nullptr;
  const long n = BIO_get_mem_data(bio, &data);
  std::string s(data, static_cast<std::size_t>(n));
  BIO_free(bio);
  return s;
}

void add_extension(X509* cert, int nid, const char* value) {
  X509V3_CTX ctx;
  X509V3_set_ctx_nodb(&ctx);
  X509V3_set_ctx(&ctx, cert, cert, nullptr, nullptr, 0);
  X509_EXTENSION* ext = X509V3_EXT_conf_nid(nullptr, &ctx, nid, value);
  X509_add_ext(cert, ext, -1);
  X509_EXTENSION_free(ext);
}

Pem self_signed() {
  EVP_PKEY* key = EVP_EC_gen("P-256");
  X509* cert = X509_new();
  X509_set_version(cert, 2);
  ASN1_INTEGER_set(X509_get_serialNumber(cert), 1);
  X509_gmtime_adj(X509_getm_notBefore(cert), -60);
  X509_gmtime_adj(X509_getm_notAfter(cert), 3600);
  X509_set_pubkey(cert, key);
  X509_NAME* name = X509_get_subject_name(cert);
  X509_NAME_add_entry_by_txt(name, "CN", MBSTRING_ASC,
                             reinterpret_cast<const unsigned char*>("localhost"), -1, -1, 0);
  X509_set_issuer_name(cert, name);
  add_extension(cert, NID_subject_alt_name, "DNS:localhost,IP:127.0.0.1");
  add_extension(cert, NID_basic_constraints, "critical,CA:TRUE");
  X509_sign(cert, key, EVP_sha256());
  BIO* cert_bio = BIO_new(BIO_s_mem());
  PEM_write_bio_X509(cert_bio, cert);
  BIO* key_bio = BIO_new(BIO_s_mem());
  PEM_write_bio_PrivateKey(key_bio, key, nullptr, nullptr, 0, nullptr, nullptr);
  X509_free(cert);
  EVP_PKEY_free(key);
  return {bio_string(cert_bio), bio_string(key_bio)};
}

grpc::Status list_jobs(const pfem::client::ConnectionOptions& connection) {
  auto stub = pfem::v1::GradientService::NewStub(pfem::client::make_channel(connection));
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(5));
  pfem::client::authorize(context, connection);
  pfem::v1::ListJobsResponse response;
  return stub->ListJobs(&context, {}, &response);
}

TEST(ServiceTls, OnlyClientsTrustingTheCertificateGetThrough) {
  TempDir dir("tls");
  const Pem pem = self_signed();
  const Pem other = self_signed();
  std::ofstream(dir.path / "cert.pem") << pem.cert;
  std::ofstream(dir.path / "key.pem") << pem.key;
  std::ofstream(dir.path / "tokens") << "tls-token\n";
  auto options = local_options(dir.path / "data");
  options.tls_cert = dir.path / "cert.pem";
  options.tls_key = dir.path / "key.pem";
  options.token_file = dir.path / "tokens";
  pfem::server::Server server(options, FakeEngine{}.function());

  pfem::client::ConnectionOptions connection;
  connection.server = server.address();
  connection.token = "tls-token";
  connection.tls_ca_pem = pem.cert;
  EXPECT_TRUE(list_jobs(connection).ok());

  connection.token.clear();
  EXPECT_EQ(list_jobs(connection).error_code(), grpc::StatusCode::UNAUTHENTICATED);

  connection.token = "tls-token";
  connection.tls_ca_pem = other.cert;
  EXPECT_EQ(list_jobs(connection).error_code(), grpc::StatusCode::UNAVAILABLE);

  connection.tls_ca_pem.clear();  // plaintext to a TLS port
  EXPECT_EQ(list_jobs(connection).error_code(), grpc::StatusCode::UNAVAILABLE);
}

TEST(ServiceTls, UnreadableKeyFilesStopTheServerNamingTheFlag) {
  TempDir dir("tls_bad");
  auto options = local_options(dir.path / "data");
  options.tls_cert = dir.path / "missing-cert.pem";
  options.tls_key = dir.path / "missing-key.pem";
  try {
    pfem::server::Server server(options, FakeEngine{}.function());
    FAIL() << "started without its certificate";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("--tls-key: cannot read"), std::string::npos) << e.what();
  }
}

}  // namespace
