#include "server/auth.h"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <stdexcept>

#include "server/hashing.h"

namespace pfem::server {
namespace {

std::string trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(" \t\r\n");
  return std::string(s.substr(first, last - first + 1));
}

}  // namespace

TokenAuth TokenAuth::from_tokens(const std::vector<std::string>& tokens) {
  TokenAuth auth;
  for (const auto& t : tokens) {
    if (!t.empty()) auth.digests_.push_back(sha256_raw(t));
  }
  return auth;
}

TokenAuth TokenAuth::from_file(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error("--token-file: cannot read " + file.string());
  std::vector<std::string> tokens;
  std::string line;
  while (std::getline(in, line)) {
    const std::string token = trim(line);
    if (token.empty() || token.front() == '#') continue;
    tokens.push_back(token);
  }
  if (tokens.empty()) throw std::runtime_error("--token-file: no token in " + file.string());
  return from_tokens(tokens);
}

bool TokenAuth::accepts(std::string_view authorization) const {
  static constexpr std::string_view kScheme = "bearer ";
  if (authorization.size() <= kScheme.size()) return false;
  for (std::size_t i = 0; i < kScheme.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(authorization[i])) != kScheme[i]) return false;
  }
  const std::string digest = sha256_raw(trim(authorization.substr(kScheme.size())));
  bool match = false;
  for (const auto& d : digests_) match |= constant_time_equal(digest, d);  // no early exit
  return match;
}

}  // namespace pfem::server
