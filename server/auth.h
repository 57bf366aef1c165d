#pragma once
// Bearer-token authentication: `authorization: Bearer <token>` metadata checked against the
// tokens of --token-file (one per line; blank lines and lines starting with '#' ignored).
// Tokens are kept as SHA-256 digests and compared in constant time, every token every time.
// Missing or wrong tokens give UNAUTHENTICATED with the same message, revealing nothing else.
//
// Thread-safety: immutable after construction; accepts() may be called from any thread.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace pfem::server {

class TokenAuth {
 public:
  TokenAuth() = default;  // disabled: every call passes
  // Reads the token file; throws std::runtime_error when it cannot be read or has no token.
  static TokenAuth from_file(const std::filesystem::path& file);
  static TokenAuth from_tokens(const std::vector<std::string>& tokens);

  bool enabled() const { return !digests_.empty(); }
  // True when `authorization` is "Bearer <a known token>" (scheme case-insensitive).
  bool accepts(std::string_view authorization) const;

 private:
  std::vector<std::string> digests_;
};

}  // namespace pfem::server
