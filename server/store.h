#pragma once
// The job store: one SQLite database (WAL) under the server's data dir.
//
// Tables: jobs (one row per job: state, the Job message, the SubmitJobRequest), job_states
// (every state change, with time and message), results (the Result message of a finished
// job), models (models stored by PutModel, keyed by their hash). Messages are stored as
// serialized protobuf blobs.
//
// Thread-safety: every method may be called from any thread; one connection is shared under
// a mutex (statements are short; SQLite's busy timeout covers other processes). Errors throw
// StoreError.
#include <sqlite3.h>

#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "pfem/v1/service.pb.h"

namespace pfem::server {

class StoreError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Store {
 public:
  // Opens (creating when needed) data_dir/pfem.sqlite3, WAL mode, busy timeout 5 s. One Store
  // at a time owns a data dir (a lock on data_dir/lock): a second server would re-queue and
  // run the first one's jobs again.
  explicit Store(const std::filesystem::path& data_dir);
  ~Store();
  Store(const Store&) = delete;
  Store& operator=(const Store&) = delete;

  // A new job (state from job.state(), normally QUEUED) with the request that created it.
  void insert_job(const pfem::v1::Job& job, const pfem::v1::SubmitJobRequest& request);
  // Replaces the job's row (state, Job message) and logs the state change with `note`.
  void update_job(const pfem::v1::Job& job, const std::string& note = {});
  // Finishes a job in one transaction: the final Job, and its result when there is one.
  void finish_job(const pfem::v1::Job& job, const pfem::v1::Result* result,
                  const std::string& note = {});

  std::optional<pfem::v1::Job> get_job(const std::string& id);
  std::optional<pfem::v1::SubmitJobRequest> get_request(const std::string& id);
  std::optional<pfem::v1::Result> get_result(const std::string& id);
  // Newest first; state UNSPECIFIED = every state; limit > 0.
  std::vector<pfem::v1::Job> list_jobs(pfem::v1::JobState state, int limit);
  long count_jobs(pfem::v1::JobState state);
  // (state, note) of every logged change of one job, oldest first.
  std::vector<std::pair<pfem::v1::JobState, std::string>> job_history(const std::string& id);

  // Start-up recovery: jobs left RUNNING by a server that died become QUEUED again.
  // Returns the ids of every QUEUED job, oldest submission first.
  std::vector<std::string> recover_queued();

  // Models stored by PutModel.
  void put_model(const std::string& id, const pfem::v1::Model& model);
  std::optional<pfem::v1::Model> get_model(const std::string& id);
  // Ids of every stored model, oldest first.
  std::vector<std::string> model_ids();

 private:
  struct Statement;
  Statement& prepare(const char* sql);  // cached per SQL text; call with mutex_ held
  void exec(const char* sql);           // call with mutex_ held
  void write_job_row(const pfem::v1::Job& job, const std::string& note);

  int lock_fd_ = -1;
  std::mutex mutex_;
  sqlite3* db_ = nullptr;
  std::vector<std::unique_ptr<Statement>> statements_;
};

}  // namespace pfem::server
