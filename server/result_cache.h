#pragma once
// The Evaluate cache: completed runs keyed by a hash of the canonical model (parameter values
// applied) and the run options, least recently used evicted first. Concurrent requests with
// the same key share one run (single flight).
//
// Thread-safety: every method may be called from any thread.
#include <condition_variable>
#include <cstddef>
#include <functional>
#include <list>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "engine/analysis/run.h"

namespace pfem::server {

class ResultCache {
 public:
  using Entry = std::shared_ptr<const RunResult>;

  explicit ResultCache(std::size_t capacity) : capacity_(capacity) {}

  // The cached run for key, or compute() run once for all concurrent callers of that key.
  // Only completed runs are kept for later calls. *hit tells whether the result came from the
  // cache or from another caller's concurrent run. A compute() that throws makes every waiter compute on its own.
  Entry get_or_compute(const std::string& key, const std::function<RunResult()>& compute,
                       bool* hit);

  std::size_t size() const;
  long hits() const;
  long misses() const;

 private:
  struct Flight {
    bool done = false;
    Entry result;  // null when compute() threw
  };

  std::size_t capacity_;
  mutable std::mutex mutex_;
  std::condition_variable flight_cv_;
  std::list<std::pair<std::string, Entry>> lru_;  // most recent first
  std::map<std::string, std::list<std::pair<std::string, Entry>>::iterator> index_;
  std::map<std::string, std::shared_ptr<Flight>> flights_;
  long hits_ = 0;
  long misses_ = 0;
};

}  // namespace pfem::server
