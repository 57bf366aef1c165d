// The SQLite job store: round trips, state log, ordering, recovery after a restart, WAL.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <filesystem>
#include <thread>

#include "server/store.h"

namespace {

namespace fs = std::filesystem;
using pfem::server::Store;

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("pfem_store_test_" + name + "_" +
                                                    std::to_string(::getpid()));
  fs::remove_all(dir);
  return dir;
}

pfem::v1::Job make_job(const std::string& id, pfem::v1::JobState state) {
  pfem::v1::Job job;
  job.set_id(id);
  job.set_state(state);
  job.set_model_name("model-" + id);
  job.set_created_unix(1000.0);
  return job;
}

pfem::v1::SubmitJobRequest make_request(double rho) {
  pfem::v1::SubmitJobRequest request;
  request.mutable_model()->set_name("tiny");
  request.mutable_model()->mutable_fluid()->set_rho(rho);
  request.mutable_options()->set_t_end(0.01);
  return request;
}

pfem::v1::Result make_result() {
  pfem::v1::Result result;
  result.mutable_summary()->set_status(pfem::v1::RUN_STATUS_COMPLETED);
  result.mutable_summary()->set_steps(3);
  auto* h = result.mutable_responses();
  for (double t : {0.0, 0.1, 0.2}) h->add_time(t);
  auto* c = h->add_columns();
  c->set_name("bottom_p");
  for (double v : {1.0, 1.0 / 3.0, -2.5e-300}) c->add_values(v);
  return result;
}

TEST(ServerStore, JobRoundTripAndStateLog) {
  const auto dir = fresh_dir("roundtrip");
  Store store(dir);
  store.insert_job(make_job("a", pfem::v1::JOB_STATE_QUEUED), make_request(1000.0));
  auto job = store.get_job("a");
  ASSERT_TRUE(job);
  EXPECT_EQ(job->model_name(), "model-a");
  EXPECT_EQ(job->state(), pfem::v1::JOB_STATE_QUEUED);
  EXPECT_EQ(store.get_request("a")->model().fluid().rho(), 1000.0);
  EXPECT_FALSE(store.get_job("missing"));
  EXPECT_FALSE(store.get_result("a"));

  job->set_state(pfem::v1::JOB_STATE_RUNNING);
  store.update_job(*job, "started");
  job->set_state(pfem::v1::JOB_STATE_SUCCEEDED);
  const auto result = make_result();
  store.finish_job(*job, &result, "succeeded");

  EXPECT_EQ(store.get_job("a")->state(), pfem::v1::JOB_STATE_SUCCEEDED);
  const auto stored = store.get_result("a");
  ASSERT_TRUE(stored);
  EXPECT_EQ(stored->SerializeAsString(), result.SerializeAsString());
  const auto history = store.job_history("a");
  ASSERT_EQ(history.size(), 3u);
  EXPECT_EQ(history[0].first, pfem::v1::JOB_STATE_QUEUED);
  EXPECT_EQ(history[1].first, pfem::v1::JOB_STATE_RUNNING);
  EXPECT_EQ(history[2].first, pfem::v1::JOB_STATE_SUCCEEDED);
  EXPECT_EQ(history[2].second, "succeeded");
  EXPECT_TRUE(fs::exists(dir / "pfem.sqlite3-wal"));  // WAL mode
  fs::remove_all(dir);
}

TEST(ServerStore, UpdatingAnUnknownJobThrows) {
  const auto dir = fresh_dir("unknown");
  Store store(dir);
  EXPECT_THROW(store.update_job(make_job("nope", pfem::v1::JOB_STATE_RUNNING)),
               pfem::server::StoreError);
  fs::remove_all(dir);
}

TEST(ServerStore, ListsNewestFirstAndCountsByState) {
  const auto dir = fresh_dir("list");
  Store store(dir);
  for (int i = 0; i < 5; ++i) {
    store.insert_job(make_job(std::string("j").append(std::to_string(i)),
                              i % 2 ? pfem::v1::JOB_STATE_QUEUED : pfem::v1::JOB_STATE_FAILED),
                     make_request(1.0 + i));
  }
  const auto all = store.list_jobs(pfem::v1::JOB_STATE_UNSPECIFIED, 100);
  ASSERT_EQ(all.size(), 5u);
  EXPECT_EQ(all.front().id(), "j4");
  EXPECT_EQ(all.back().id(), "j0");
  const auto two = store.list_jobs(pfem::v1::JOB_STATE_UNSPECIFIED, 2);
  ASSERT_EQ(two.size(), 2u);
  const auto queued = store.list_jobs(pfem::v1::JOB_STATE_QUEUED, 100);
  ASSERT_EQ(queued.size(), 2u);
  EXPECT_EQ(queued[0].id(), "j3");
  EXPECT_EQ(store.count_jobs(pfem::v1::JOB_STATE_FAILED), 3);
  EXPECT_EQ(store.count_jobs(pfem::v1::JOB_STATE_RUNNING), 0);
  fs::remove_all(dir);
}

TEST(ServerStore, SurvivesARestartAndRequeuesInterruptedJobs) {
  const auto dir = fresh_dir("restart");
  const auto result = make_result();
  {
    Store store(dir);
    store.insert_job(make_job("done", pfem::v1::JOB_STATE_QUEUED), make_request(1.0));
    store.insert_job(make_job("running", pfem::v1::JOB_STATE_QUEUED), make_request(2.0));
    store.insert_job(make_job("waiting", pfem::v1::JOB_STATE_QUEUED), make_request(3.0));
    auto done = make_job("done", pfem::v1::JOB_STATE_SUCCEEDED);
    store.finish_job(done, &result, "succeeded");
    auto running = make_job("running", pfem::v1::JOB_STATE_RUNNING);
    running.mutable_progress()->set_step(7);
    store.update_job(running, "started");
  }  // the "server" stops without finishing `running`
  Store store(dir);
  const auto queued = store.recover_queued();
  ASSERT_EQ(queued.size(), 2u);
  EXPECT_EQ(queued[0], "running");  // submission order
  EXPECT_EQ(queued[1], "waiting");
  const auto running = store.get_job("running");
  EXPECT_EQ(running->state(), pfem::v1::JOB_STATE_QUEUED);
  EXPECT_EQ(running->progress().step(), 0);
  EXPECT_EQ(store.get_request("running")->model().fluid().rho(), 2.0);
  EXPECT_EQ(store.get_result("done")->SerializeAsString(), result.SerializeAsString());
  EXPECT_EQ(store.get_job("done")->state(), pfem::v1::JOB_STATE_SUCCEEDED);
  EXPECT_EQ(store.job_history("running").back().first, pfem::v1::JOB_STATE_QUEUED);
  fs::remove_all(dir);
}

TEST(ServerStore, ModelsByIdAndConcurrentWriters) {
  const auto dir = fresh_dir("concurrent");
  Store store(dir);
  pfem::v1::Model model;
  model.set_name("m");
  model.mutable_mesh()->set_h(0.01);
  store.put_model("abc", model);
  store.put_model("abc", model);  // idempotent
  EXPECT_EQ(store.get_model("abc")->mesh().h(), 0.01);
  EXPECT_FALSE(store.get_model("xyz"));

  std::vector<std::thread> threads;
  for (int t = 0; t < 8; ++t) {
    threads.emplace_back([&store, t] {
      for (int i = 0; i < 25; ++i) {
        std::string id = "t";  // built by appends (GCC 12 warns falsely on chained + here)
        id.append(std::to_string(t)).append("_").append(std::to_string(i));
        store.insert_job(make_job(id, pfem::v1::JOB_STATE_QUEUED), make_request(1.0));
        store.update_job(make_job(id, pfem::v1::JOB_STATE_RUNNING));
      }
    });
  }
  for (auto& th : threads) th.join();
  EXPECT_EQ(store.count_jobs(pfem::v1::JOB_STATE_RUNNING), 200);
  fs::remove_all(dir);
}


// A blob that does not parse throws StoreError, and leaves no read transaction open on the
// store's connection: a reader held there would keep every checkpoint from truncating the WAL
// (it had, for a corrupt request, result or model, until that statement ran again).
TEST(ServerStore, ACorruptBlobLeavesNoReadTransactionOpen) {
  const fs::path dir = fresh_dir("corrupt_blob");
  Store store(dir);
  store.insert_job(make_job("j1", pfem::v1::JOB_STATE_QUEUED), make_request(1000.0));
  store.finish_job(make_job("j1", pfem::v1::JOB_STATE_SUCCEEDED), nullptr);
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open((dir / "pfem.sqlite3").string().c_str(), &db), SQLITE_OK);
  sqlite3_busy_timeout(db, 2000);
  const auto exec = [&](const char* sql) {
    return sqlite3_exec(db, sql, nullptr, nullptr, nullptr);
  };
  ASSERT_EQ(exec("UPDATE jobs SET request = x'ffffffff' WHERE id = 'j1'"), SQLITE_OK);
  ASSERT_EQ(exec("INSERT INTO results (job_id, result) VALUES ('j1', x'ffffffff')"), SQLITE_OK);
  ASSERT_EQ(exec("INSERT INTO models (id, created, model) VALUES ('m1', 0, x'ffffffff')"),
            SQLITE_OK);
  EXPECT_THROW(store.get_request("j1"), pfem::server::StoreError);
  EXPECT_THROW(store.get_result("j1"), pfem::server::StoreError);
  EXPECT_THROW(store.get_model("m1"), pfem::server::StoreError);
  int log_frames = -1;
  int checkpointed = -1;
  EXPECT_EQ(sqlite3_wal_checkpoint_v2(db, nullptr, SQLITE_CHECKPOINT_TRUNCATE, &log_frames,
                                      &checkpointed),
            SQLITE_OK)
      << sqlite3_errmsg(db);
  EXPECT_EQ(log_frames, 0);  // the WAL truncated: no reader in the way
  sqlite3_close(db);
  fs::remove_all(dir);
}

}  // namespace
