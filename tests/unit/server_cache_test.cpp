// The Evaluate cache: single flight for concurrent identical keys, LRU eviction, only
// completed runs kept, a throwing computation retried by the next caller.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include "server/result_cache.h"

namespace {

using pfem::server::ResultCache;

pfem::RunResult result(double v, pfem::RunStatus status = pfem::RunStatus::kCompleted) {
  pfem::RunResult r;
  r.responses.columns = {"x"};
  r.responses.time = {0.0};
  r.responses.rows = {{v}};
  r.summary.status = status;
  return r;
}

TEST(ServerCache, ConcurrentIdenticalKeysShareOneRun) {
  ResultCache cache(8);
  std::atomic<int> runs{0}, hits{0};
  std::vector<std::thread> threads;
  for (int i = 0; i < 16; ++i) {
    threads.emplace_back([&] {
      bool hit = false;
      const auto r = cache.get_or_compute("k", [&] {
        ++runs;
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
        return result(7.0);
      }, &hit);
      hits += hit;
      EXPECT_EQ(r->responses.rows[0][0], 7.0);
    });
  }
  for (auto& t : threads) t.join();
  EXPECT_EQ(runs.load(), 1);
  EXPECT_EQ(hits.load(), 15);
  EXPECT_EQ(cache.misses(), 1);
}

TEST(ServerCache, EvictsTheLeastRecentlyUsedAndKeepsOnlyCompletedRuns) {
  ResultCache cache(2);
  int runs = 0;
  const auto compute = [&](double v) {
    return [&runs, v] {
      ++runs;
      return result(v);
    };
  };
  bool hit = false;
  cache.get_or_compute("a", compute(1), &hit);
  cache.get_or_compute("b", compute(2), &hit);
  cache.get_or_compute("a", compute(1), &hit);  // a is now the most recent
  EXPECT_TRUE(hit);
  cache.get_or_compute("c", compute(3), &hit);  // evicts b
  EXPECT_EQ(cache.size(), 2u);
  cache.get_or_compute("b", compute(2), &hit);
  EXPECT_FALSE(hit);
  EXPECT_EQ(runs, 4);

  cache.get_or_compute("failed", [] { return result(0, pfem::RunStatus::kFailed); }, &hit);
  cache.get_or_compute("failed", [] { return result(0, pfem::RunStatus::kFailed); }, &hit);
  EXPECT_FALSE(hit);  // failures are not kept

  EXPECT_THROW(cache.get_or_compute("t", []() -> pfem::RunResult { throw std::runtime_error("x"); }, &hit),
               std::runtime_error);
  const auto r = cache.get_or_compute("t", [] { return result(5); }, &hit);
  EXPECT_FALSE(hit);
  EXPECT_EQ(r->responses.rows[0][0], 5.0);
}

}  // namespace
