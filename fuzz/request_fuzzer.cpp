// libFuzzer target: the server's request checks (server/requests.h) on request messages as
// they arrive on the wire. The first byte picks the method (request_kind.h), the rest is the
// message's protobuf encoding. Expected outcomes: the request passes, or ServiceError (the
// status the client gets). Anything else is a defect (the client would get INTERNAL).
#include <cstddef>
#include <cstdint>

#include <google/protobuf/stubs/logging.h>

#include "fuzz/request_kind.h"
#include "server/requests.h"
#include "server/status.h"

namespace {

template <typename Message>
bool parse(Message* message, const std::uint8_t* data, std::size_t size) {
  return message->ParseFromArray(data, static_cast<int>(size));
}

void check(pfem::fuzz::RequestKind kind, const std::uint8_t* data, std::size_t size) {
  const pfem::server::Limits limits;
  switch (kind) {
    case pfem::fuzz::RequestKind::kSubmitJob: {
      pfem::v1::SubmitJobRequest request;
      if (parse(&request, data, size)) pfem::server::check_submit_request(request, limits);
      return;
    }
    case pfem::fuzz::RequestKind::kEvaluate: {
      pfem::v1::EvaluateRequest request;
      if (parse(&request, data, size) && request.has_model()) {
        pfem::server::check_evaluate_request(request, request.model(), limits);
      }
      return;
    }
    case pfem::fuzz::RequestKind::kValidateModel: {
      pfem::v1::ValidateModelRequest request;
      if (parse(&request, data, size)) pfem::server::check_validate_request(request.model(), limits);
      return;
    }
  }
}

}  // namespace

// Invalid UTF-8 in a string field fails the parse (INVALID_ARGUMENT on the wire) and
// protobuf logs it: thousands of lines a second here.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  google::protobuf::SetLogHandler(nullptr);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const auto kind = static_cast<pfem::fuzz::RequestKind>(data[0] % pfem::fuzz::kRequestKinds);
  try {
    check(kind, data + 1, size - 1);
  } catch (const pfem::server::ServiceError&) {
  }
  return 0;
}
