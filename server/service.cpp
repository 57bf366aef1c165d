#include "server/service.h"

#include <chrono>
#include <optional>

#include "engine/io/model_io.h"
#include "server/hashing.h"
#include "server/requests.h"
#include "server/status.h"

namespace pfem::server {
namespace {

bool finished(pfem::v1::JobState s) {
  return s == pfem::v1::JOB_STATE_SUCCEEDED || s == pfem::v1::JOB_STATE_FAILED ||
         s == pfem::v1::JOB_STATE_CANCELLED;
}

void require_job_id(const pfem::v1::JobRequest& request) {
  constexpr std::size_t kMaxJobId = 64;  // ids are 16 hex digits
  if (request.job_id().empty()) throw_invalid({{"job_id", "required"}});
  if (request.job_id().size() > kMaxJobId) {
    throw_invalid({{"job_id", "too long (" + std::to_string(request.job_id().size()) +
                                  " characters; job ids have 16)"}});
  }
}

// Streams one column in slices of GradientService::kChunkValues values.
template <typename Values>
bool write_column(grpc::ServerWriter<pfem::v1::GetResultResponse>* writer,
                  pfem::v1::HistoriesKind kind, int column, const Values& values) {
  const int n = values.size();
  int offset = 0;
  do {
    pfem::v1::GetResultResponse message;
    auto* chunk = message.mutable_chunk();
    chunk->set_kind(kind);
    chunk->set_column(column);
    chunk->set_offset(offset);
    const int end = std::min(n, offset + GradientService::kChunkValues);
    chunk->mutable_values()->Reserve(end - offset);
    for (int i = offset; i < end; ++i) chunk->add_values(values[i]);
    if (!writer->Write(message)) return false;
    offset = end;
  } while (offset < n);
  return true;
}

}  // namespace

grpc::Status GradientService::handle(const std::function<grpc::Status()>& body) {
  if (draining_) return {grpc::StatusCode::UNAVAILABLE, "server is shutting down"};
  ++in_flight_;
  const grpc::Status status = guarded(body);
  --in_flight_;
  return status;
}

grpc::Status GradientService::ValidateModel(grpc::ServerContext* /*context*/,
                                            const pfem::v1::ValidateModelRequest* request,
                                            pfem::v1::ValidateModelResponse* response) {
  return handle([&] {
    *response = check_validate_request(request->model(), limits_);
    return grpc::Status::OK;
  });
}

grpc::Status GradientService::SubmitJob(grpc::ServerContext* /*context*/,
                                        const pfem::v1::SubmitJobRequest* request,
                                        pfem::v1::SubmitJobResponse* response) {
  return handle([&] {
    check_submit_request(*request, limits_);
    response->set_job_id(jobs_.submit(*request));
    return grpc::Status::OK;
  });
}

grpc::ServerWriteReactor<pfem::v1::Job>* GradientService::WatchJob(
    grpc::CallbackServerContext* context, const pfem::v1::JobRequest* request) {
  if (draining_) {
    return JobWatchers::refuse({grpc::StatusCode::UNAVAILABLE, "server is shutting down"});
  }
  std::optional<StreamSlots::Slot> slot;
  const grpc::Status status = guarded([&] {
    require_job_id(*request);
    slot.emplace(streams_.acquire(context->peer()));
    jobs_.get(request->job_id());  // NOT_FOUND now, not from the stream
    return grpc::Status::OK;
  });
  if (!status.ok()) return JobWatchers::refuse(status);
  return watchers_.watch(request->job_id(), std::move(*slot));
}

grpc::Status GradientService::GetJob(grpc::ServerContext* /*context*/,
                                     const pfem::v1::JobRequest* request,
                                     pfem::v1::Job* response) {
  return handle([&] {
    require_job_id(*request);
    *response = jobs_.get(request->job_id());
    return grpc::Status::OK;
  });
}

grpc::Status GradientService::GetResult(grpc::ServerContext* context,
                                        const pfem::v1::JobRequest* request,
                                        grpc::ServerWriter<pfem::v1::GetResultResponse>* writer) {
  return handle([&] {
    require_job_id(*request);
    const auto slot = streams_.acquire(context->peer());
    const auto job = jobs_.get(request->job_id());
    if (!finished(job.state())) {
      throw ServiceError(grpc::StatusCode::FAILED_PRECONDITION,
                         "job '" + job.id() + "' is " + pfem::v1::JobState_Name(job.state()) +
                             "; its result is available once it has finished");
    }
    const auto result = results_.open(job.id());
    if (!result) {
      throw ServiceError(grpc::StatusCode::NOT_FOUND,
                         "job '" + job.id() + "' has no result (" +
                             pfem::v1::JobState_Name(job.state()) + ": " +
                             job.error().message() + ")");
    }
    pfem::v1::GetResultResponse first;
    auto* header = first.mutable_header();
    *header->mutable_job() = job;
    *header->mutable_summary() = result->summary();
    for (const auto& c : result->responses().columns()) header->add_response_columns(c.name());
    for (const auto& c : result->sensitivities().columns()) {
      header->add_sensitivity_columns(c.name());
    }
    header->set_rows(result->responses().time_size());
    if (!writer->Write(first)) return grpc::Status(grpc::StatusCode::CANCELLED, "reader left");
    const auto send = [&](pfem::v1::HistoriesKind kind, const pfem::v1::Histories& h) {
      if (!write_column(writer, kind, -1, h.time())) return false;
      for (int j = 0; j < h.columns_size(); ++j) {
        if (!write_column(writer, kind, j, h.columns(j).values())) return false;
      }
      return true;
    };
    if (!send(pfem::v1::HISTORIES_KIND_RESPONSES, result->responses())) {
      return grpc::Status(grpc::StatusCode::CANCELLED, "reader left");
    }
    if (result->sensitivities().columns_size() > 0 &&
        !send(pfem::v1::HISTORIES_KIND_SENSITIVITIES, result->sensitivities())) {
      return grpc::Status(grpc::StatusCode::CANCELLED, "reader left");
    }
    return grpc::Status::OK;
  });
}

grpc::Status GradientService::CancelJob(grpc::ServerContext* /*context*/,
                                        const pfem::v1::JobRequest* request,
                                        pfem::v1::Job* response) {
  return handle([&] {
    require_job_id(*request);
    *response = jobs_.cancel(request->job_id());
    return grpc::Status::OK;
  });
}

grpc::Status GradientService::ListJobs(grpc::ServerContext* /*context*/,
                                       const pfem::v1::ListJobsRequest* request,
                                       pfem::v1::ListJobsResponse* response) {
  return handle([&] {
    std::vector<FieldError> errors;
    if (request->limit() < 0) errors.push_back({"limit", "must be >= 0"});
    if (!pfem::v1::JobState_IsValid(request->state())) {
      errors.push_back({"state", "unknown job state " + std::to_string(request->state())});
    }
    if (!errors.empty()) throw_invalid(errors);
    const int limit = request->limit() == 0 ? 100 : request->limit();
    for (auto& job : store_.list_jobs(request->state(), limit)) {
      if (!finished(job.state())) {
        try {
          job = jobs_.get(job.id());  // the live snapshot (progress) of an active job
        } catch (const ServiceError&) {
        }
      }
      *response->add_jobs() = std::move(job);
    }
    return grpc::Status::OK;
  });
}

grpc::Status GradientService::PutModel(grpc::ServerContext* /*context*/,
                                       const pfem::v1::PutModelRequest* request,
                                       pfem::v1::PutModelResponse* response) {
  return handle([&] {
    const auto errors = validate_model(request->model());
    if (!errors.empty()) throw_invalid(errors);
    const std::string id = sha256_hex(canonical_bytes(request->model()));
    store_.put_model(id, request->model());
    response->set_model_id(id);
    return grpc::Status::OK;
  });
}

grpc::Status GradientService::Evaluate(grpc::ServerContext* context,
                                       const pfem::v1::EvaluateRequest* request,
                                       pfem::v1::EvaluateResponse* response) {
  return handle([&] {
    const auto deadline = context->deadline();
    const auto should_stop = [context, deadline] {
      if (context->IsCancelled()) return grpc::StatusCode::CANCELLED;
      if (std::chrono::system_clock::now() > deadline) return grpc::StatusCode::DEADLINE_EXCEEDED;
      return grpc::StatusCode::OK;
    };
    evaluator_.evaluate(*request, should_stop, response);
    return grpc::Status::OK;
  });
}

}  // namespace pfem::server
