#pragma once
// The request fuzzer's input: one byte naming the method, then the request message's
// protobuf encoding. Shared by the fuzzer and the seed writer.
namespace pfem::fuzz {

enum class RequestKind : unsigned char { kSubmitJob = 0, kEvaluate = 1, kValidateModel = 2 };
inline constexpr unsigned char kRequestKinds = 3;

}  // namespace pfem::fuzz
