#pragma once
// Content hashes: SHA-256 (OpenSSL) of a message's canonical serialization, used as model
// ids (PutModel) and as the Evaluate cache key, and for token comparison.
#include <google/protobuf/message_lite.h>

#include <string>
#include <string_view>

namespace pfem::server {

// 64 lowercase hex digits.
std::string sha256_hex(std::string_view bytes);
// 32 raw bytes.
std::string sha256_raw(std::string_view bytes);

// Deterministic serialization (stable field order, map entries sorted): equal messages give
// equal bytes within one build of the schema.
std::string canonical_bytes(const google::protobuf::MessageLite& message);

// Constant-time equality of two equal-length byte strings (false when lengths differ).
bool constant_time_equal(std::string_view a, std::string_view b);

}  // namespace pfem::server
