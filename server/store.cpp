#include "server/store.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>

namespace pfem::server {
namespace {

double now_unix() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

std::string serialize(const google::protobuf::MessageLite& message) {
  std::string bytes;
  if (!message.SerializeToString(&bytes)) throw StoreError("cannot serialize a message");
  return bytes;
}

// The last error on db, marked full when the database or the disk is full.
StoreError sqlite_error(sqlite3* db, const std::string& where) {
  return StoreError(std::string(sqlite3_errmsg(db)) + " in: " + where,
                    sqlite3_errcode(db) == SQLITE_FULL);
}

// A Job standing in for a stored record that cannot be parsed.
pfem::v1::Job unreadable_job(const std::string& id, long long state) {
  pfem::v1::Job job;
  job.set_id(id);
  job.set_state(pfem::v1::JobState_IsValid(static_cast<int>(state))
                    ? static_cast<pfem::v1::JobState>(state)
                    : pfem::v1::JOB_STATE_FAILED);
  job.mutable_error()->set_message("stored job record is corrupt");
  return job;
}

}  // namespace

// A prepared statement, reset and cleared on every use (RAII over sqlite3_stmt).
struct Store::Statement {
  sqlite3* db = nullptr;
  sqlite3_stmt* stmt = nullptr;
  std::string sql;

  ~Statement() { sqlite3_finalize(stmt); }
  void check(int rc) const {
    if (rc != SQLITE_OK) throw sqlite_error(db, sql);
  }
  Statement& reset() {
    sqlite3_reset(stmt);
    sqlite3_clear_bindings(stmt);
    return *this;
  }
  Statement& bind(int i, const std::string& text) {
    check(sqlite3_bind_text(stmt, i, text.data(), static_cast<int>(text.size()),
                            SQLITE_TRANSIENT));
    return *this;
  }
  Statement& bind_blob(int i, const std::string& bytes) {
    check(sqlite3_bind_blob(stmt, i, bytes.data(), static_cast<int>(bytes.size()),
                            SQLITE_TRANSIENT));
    return *this;
  }
  Statement& bind(int i, long long v) {
    check(sqlite3_bind_int64(stmt, i, v));
    return *this;
  }
  Statement& bind(int i, double v) {
    check(sqlite3_bind_double(stmt, i, v));
    return *this;
  }
  // Steps once: true when a row is available.
  // Steps once: true when a row is available; resets the statement when done or failing
  // (so no read transaction stays open).
  bool step() {
    const int rc = sqlite3_step(stmt);
    if (rc == SQLITE_ROW) return true;
    sqlite3_reset(stmt);
    if (rc == SQLITE_DONE) return false;
    throw sqlite_error(db, sql);
  }
  void run() {
    while (step()) {
    }
  }
  // Parses column i in place (no copy of the blob: a result may be tens of MB).
  bool parse_blob(int i, google::protobuf::MessageLite* message) const {
    const void* p = sqlite3_column_blob(stmt, i);
    return message->ParseFromArray(p, sqlite3_column_bytes(stmt, i));
  }
  std::string column_text(int i) const {
    const unsigned char* p = sqlite3_column_text(stmt, i);
    return p ? std::string(reinterpret_cast<const char*>(p)) : std::string();
  }
  long long column_int(int i) const { return sqlite3_column_int64(stmt, i); }
};

Store::Store(const std::filesystem::path& data_dir, long long max_bytes) {
  std::error_code ec;
  std::filesystem::create_directories(data_dir, ec);
  if (ec) throw StoreError("cannot create " + data_dir.string() + ": " + ec.message());
  const auto lock_file = (data_dir / "lock").string();
  lock_fd_ = ::open(lock_file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (lock_fd_ < 0) throw StoreError("cannot open " + lock_file + ": " + std::strerror(errno));
  if (::flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    ::close(lock_fd_);
    throw StoreError(data_dir.string() + " is in use by another server (" + lock_file + " is locked)" +
                     (error == EWOULDBLOCK ? "" : std::string(": ") + std::strerror(error)));
  }
  const auto file = (data_dir / "pfem.sqlite3").string();
  if (std::filesystem::exists(file, ec) && std::filesystem::file_size(file, ec) == 0 && !ec) {
    ::close(lock_fd_);
    throw StoreError(file + " exists but is empty (0 bytes): its contents were lost. Restore it "
                     "from a backup, or delete it to start with an empty store");
  }
  const int rc = sqlite3_open_v2(file.c_str(), &db_,
                                 SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE |
                                     SQLITE_OPEN_FULLMUTEX,
                                 nullptr);
  if (rc != SQLITE_OK) {
    const std::string message = db_ ? sqlite3_errmsg(db_) : "out of memory";
    sqlite3_close(db_);
    db_ = nullptr;
    ::close(lock_fd_);
    throw StoreError("cannot open " + file + ": " + message);
  }
  sqlite3_busy_timeout(db_, 5000);
  std::lock_guard lock(mutex_);
  exec("PRAGMA journal_mode=WAL");
  exec("PRAGMA synchronous=NORMAL");
  exec("PRAGMA foreign_keys=ON");
  exec(R"(CREATE TABLE IF NOT EXISTS jobs (
           seq INTEGER PRIMARY KEY AUTOINCREMENT,
           id TEXT NOT NULL UNIQUE,
           state INTEGER NOT NULL,
           created REAL NOT NULL,
           job BLOB NOT NULL,
           request BLOB NOT NULL))");
  exec("CREATE INDEX IF NOT EXISTS jobs_state ON jobs(state, seq)");
  exec(R"(CREATE TABLE IF NOT EXISTS job_states (
           job_id TEXT NOT NULL REFERENCES jobs(id),
           state INTEGER NOT NULL,
           at REAL NOT NULL,
           note TEXT NOT NULL))");
  exec("CREATE INDEX IF NOT EXISTS job_states_job ON job_states(job_id)");
  exec(R"(CREATE TABLE IF NOT EXISTS results (
           job_id TEXT PRIMARY KEY REFERENCES jobs(id),
           result BLOB NOT NULL))");
  exec(R"(CREATE TABLE IF NOT EXISTS models (
           id TEXT PRIMARY KEY,
           created REAL NOT NULL,
           model BLOB NOT NULL))");
  // Version 2: jobs.cancel_requested (a client's cancel of a running job, kept over a crash).
  bool has_cancel_column = false;
  {
    auto& q = prepare("SELECT name FROM pragma_table_info('jobs')");
    while (q.step()) has_cancel_column |= q.column_text(0) == "cancel_requested";
  }
  if (!has_cancel_column) {
    exec("ALTER TABLE jobs ADD COLUMN cancel_requested INTEGER NOT NULL DEFAULT 0");
  }
  exec("PRAGMA user_version=2");
  if (max_bytes > 0) {
    auto& page = prepare("PRAGMA page_size");
    page.step();
    const long long pages = std::max(1LL, max_bytes / std::max(1LL, page.column_int(0)));
    page.reset();
    exec(("PRAGMA max_page_count=" + std::to_string(pages)).c_str());
  }
}

Store::~Store() {
  statements_.clear();
  sqlite3_close(db_);
  ::close(lock_fd_);  // releases the lock
}

void Store::exec(const char* sql) {
  if (sqlite3_exec(db_, sql, nullptr, nullptr, nullptr) != SQLITE_OK) throw sqlite_error(db_, sql);
}

Store::Statement& Store::prepare(const char* sql) {
  for (auto& s : statements_) {
    if (s->sql == sql) return s->reset();
  }
  auto s = std::make_unique<Statement>();
  s->db = db_;
  s->sql = sql;
  if (sqlite3_prepare_v2(db_, sql, -1, &s->stmt, nullptr) != SQLITE_OK) {
    throw sqlite_error(db_, sql);
  }
  statements_.push_back(std::move(s));
  return *statements_.back();
}

namespace {
// BEGIN IMMEDIATE ... COMMIT, rolled back when an exception leaves the scope.
class Transaction {
 public:
  explicit Transaction(sqlite3* db) : db_(db) { run("BEGIN IMMEDIATE"); }
  ~Transaction() {
    if (!done_) sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
  }
  void commit() {
    run("COMMIT");
    done_ = true;
  }

 private:
  void run(const char* sql) {
    if (sqlite3_exec(db_, sql, nullptr, nullptr, nullptr) != SQLITE_OK) {
      throw sqlite_error(db_, sql);
    }
  }
  sqlite3* db_;
  bool done_ = false;
};
}  // namespace

void Store::insert_job(const pfem::v1::Job& job, const pfem::v1::SubmitJobRequest& request) {
  std::lock_guard lock(mutex_);
  Transaction tx(db_);
  prepare("INSERT INTO jobs (id, state, created, job, request) VALUES (?, ?, ?, ?, ?)")
      .bind(1, job.id())
      .bind(2, static_cast<long long>(job.state()))
      .bind(3, job.created_unix())
      .bind_blob(4, serialize(job))
      .bind_blob(5, serialize(request))
      .run();
  prepare("INSERT INTO job_states (job_id, state, at, note) VALUES (?, ?, ?, ?)")
      .bind(1, job.id())
      .bind(2, static_cast<long long>(job.state()))
      .bind(3, now_unix())
      .bind(4, std::string("submitted"))
      .run();
  tx.commit();
}

void Store::write_job_row(const pfem::v1::Job& job, const std::string& note) {
  auto& update = prepare("UPDATE jobs SET state = ?, job = ? WHERE id = ?");
  update.bind(1, static_cast<long long>(job.state())).bind_blob(2, serialize(job)).bind(3, job.id());
  update.run();
  if (sqlite3_changes(db_) != 1) throw StoreError("no job " + job.id());
  prepare("INSERT INTO job_states (job_id, state, at, note) VALUES (?, ?, ?, ?)")
      .bind(1, job.id())
      .bind(2, static_cast<long long>(job.state()))
      .bind(3, now_unix())
      .bind(4, note)
      .run();
}

void Store::update_job(const pfem::v1::Job& job, const std::string& note) {
  std::lock_guard lock(mutex_);
  Transaction tx(db_);
  write_job_row(job, note);
  tx.commit();
}

void Store::finish_job(const pfem::v1::Job& job, const pfem::v1::Result* result,
                       const std::string& note) {
  std::lock_guard lock(mutex_);
  Transaction tx(db_);
  write_job_row(job, note);
  if (result) {
    prepare("INSERT OR REPLACE INTO results (job_id, result) VALUES (?, ?)")
        .bind(1, job.id())
        .bind_blob(2, serialize(*result))
        .run();
  }
  tx.commit();
}

std::optional<pfem::v1::Job> Store::get_job(const std::string& id) {
  std::lock_guard lock(mutex_);
  auto& q = prepare("SELECT job, state FROM jobs WHERE id = ?").bind(1, id);
  if (!q.step()) return std::nullopt;
  pfem::v1::Job job;
  if (!q.parse_blob(0, &job)) job = unreadable_job(id, q.column_int(1));
  q.reset();
  return job;
}

std::optional<pfem::v1::SubmitJobRequest> Store::get_request(const std::string& id) {
  std::lock_guard lock(mutex_);
  auto& q = prepare("SELECT request FROM jobs WHERE id = ?").bind(1, id);
  if (!q.step()) return std::nullopt;
  pfem::v1::SubmitJobRequest request;
  const bool parsed = q.parse_blob(0, &request);
  q.reset();  // before any throw: no read transaction stays open
  if (!parsed) throw StoreError("corrupt request " + id);
  return request;
}

std::optional<pfem::v1::Result> Store::get_result(const std::string& id) {
  std::lock_guard lock(mutex_);
  auto& q = prepare("SELECT result FROM results WHERE job_id = ?").bind(1, id);
  if (!q.step()) return std::nullopt;
  pfem::v1::Result result;
  const bool parsed = q.parse_blob(0, &result);
  q.reset();  // before any throw: no read transaction stays open
  if (!parsed) throw StoreError("corrupt result " + id);
  return result;
}

std::vector<pfem::v1::Job> Store::list_jobs(pfem::v1::JobState state, int limit) {
  std::lock_guard lock(mutex_);
  auto& q = state == pfem::v1::JOB_STATE_UNSPECIFIED
                ? prepare("SELECT job, id, state FROM jobs ORDER BY seq DESC LIMIT ?")
                      .bind(1, static_cast<long long>(limit))
                : prepare("SELECT job, id, state FROM jobs WHERE state = ? ORDER BY seq DESC LIMIT ?")
                      .bind(1, static_cast<long long>(state))
                      .bind(2, static_cast<long long>(limit));
  std::vector<pfem::v1::Job> jobs;
  while (q.step()) {
    pfem::v1::Job job;
    if (!q.parse_blob(0, &job)) job = unreadable_job(q.column_text(1), q.column_int(2));
    jobs.push_back(std::move(job));
  }
  q.reset();
  return jobs;
}

long Store::count_jobs(pfem::v1::JobState state) {
  std::lock_guard lock(mutex_);
  auto& q = prepare("SELECT COUNT(*) FROM jobs WHERE state = ?").bind(1, static_cast<long long>(state));
  q.step();
  const long n = static_cast<long>(q.column_int(0));
  q.reset();
  return n;
}

std::vector<std::pair<pfem::v1::JobState, std::string>> Store::job_history(
    const std::string& id) {
  std::lock_guard lock(mutex_);
  auto& q = prepare("SELECT state, note FROM job_states WHERE job_id = ? ORDER BY rowid").bind(1, id);
  std::vector<std::pair<pfem::v1::JobState, std::string>> history;
  while (q.step()) {
    history.emplace_back(static_cast<pfem::v1::JobState>(q.column_int(0)), q.column_text(1));
  }
  q.reset();
  return history;
}

std::vector<std::string> Store::recover_queued() {
  std::lock_guard lock(mutex_);
  Transaction tx(db_);
  std::vector<std::pair<pfem::v1::Job, bool>> interrupted;  // (job, cancelled by a client)
  {
    auto& q = prepare(
                  "SELECT job, id, state, cancel_requested FROM jobs WHERE state = ? OR "
                  "(state = ? AND cancel_requested = 1) ORDER BY seq")
                  .bind(1, static_cast<long long>(pfem::v1::JOB_STATE_RUNNING))
                  .bind(2, static_cast<long long>(pfem::v1::JOB_STATE_QUEUED));
    while (q.step()) {
      pfem::v1::Job job;
      if (!q.parse_blob(0, &job)) {
        job = unreadable_job(q.column_text(1), pfem::v1::JOB_STATE_FAILED);
      }
      interrupted.emplace_back(std::move(job), q.column_int(3) != 0);
    }
    q.reset();
  }
  for (auto& [job, cancelled] : interrupted) {
    job.clear_progress();
    if (job.state() == pfem::v1::JOB_STATE_FAILED) {
      job.set_finished_unix(now_unix());
      write_job_row(job, "failed: the stored job record is corrupt");
    } else if (cancelled) {
      job.set_state(pfem::v1::JOB_STATE_CANCELLED);
      job.set_finished_unix(now_unix());
      job.mutable_error()->set_message(
          "cancelled by a client (the server stopped before the run ended)");
      write_job_row(job, "cancelled: requested before the server stopped");
    } else {
      job.set_state(pfem::v1::JOB_STATE_QUEUED);
      write_job_row(job, "re-queued: the server stopped while it was running");
    }
  }
  std::vector<std::string> ids;
  auto& q = prepare("SELECT id FROM jobs WHERE state = ? ORDER BY seq")
                .bind(1, static_cast<long long>(pfem::v1::JOB_STATE_QUEUED));
  while (q.step()) ids.push_back(q.column_text(0));
  q.reset();
  tx.commit();
  return ids;
}

void Store::request_cancel(const std::string& id) {
  std::lock_guard lock(mutex_);
  Transaction tx(db_);
  prepare("UPDATE jobs SET cancel_requested = 1 WHERE id = ?").bind(1, id).run();
  if (sqlite3_changes(db_) != 1) throw StoreError("no job " + id);
  prepare(
      "INSERT INTO job_states (job_id, state, at, note) SELECT id, state, ?, ? FROM jobs WHERE id = ?")
      .bind(1, now_unix())
      .bind(2, std::string("cancel requested by a client"))
      .bind(3, id)
      .run();
  tx.commit();
}

void Store::put_model(const std::string& id, const pfem::v1::Model& model) {
  std::lock_guard lock(mutex_);
  prepare("INSERT OR IGNORE INTO models (id, created, model) VALUES (?, ?, ?)")
      .bind(1, id)
      .bind(2, now_unix())
      .bind_blob(3, serialize(model))
      .run();
}

std::optional<pfem::v1::Model> Store::get_model(const std::string& id) {
  std::lock_guard lock(mutex_);
  auto& q = prepare("SELECT model FROM models WHERE id = ?").bind(1, id);
  if (!q.step()) return std::nullopt;
  pfem::v1::Model model;
  const bool parsed = q.parse_blob(0, &model);
  q.reset();  // before any throw: no read transaction stays open
  if (!parsed) throw StoreError("corrupt model " + id);
  return model;
}

std::vector<std::string> Store::model_ids() {
  std::lock_guard lock(mutex_);
  auto& q = prepare("SELECT id FROM models ORDER BY created, id");
  std::vector<std::string> ids;
  while (q.step()) ids.push_back(q.column_text(0));
  q.reset();
  return ids;
}

}  // namespace pfem::server
