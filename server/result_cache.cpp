#include "server/result_cache.h"

namespace pfem::server {

ResultCache::Entry ResultCache::get_or_compute(const std::string& key,
                                               const std::function<RunResult()>& compute,
                                               bool* hit) {
  std::unique_lock lock(mutex_);
  for (;;) {
    if (const auto it = index_.find(key); it != index_.end()) {
      lru_.splice(lru_.begin(), lru_, it->second);
      ++hits_;
      if (hit) *hit = true;
      return it->second->second;
    }
    const auto f = flights_.find(key);
    if (f == flights_.end()) break;
    auto flight = f->second;  // another caller is running it: wait for that run
    flight_cv_.wait(lock, [&] { return flight->done; });
    if (flight->result) {
      ++hits_;
      if (hit) *hit = true;
      return flight->result;
    }
    if (flights_.count(key)) continue;
    break;  // that run threw: run it ourselves
  }
  auto flight = std::make_shared<Flight>();
  flights_[key] = flight;
  ++misses_;
  if (hit) *hit = false;
  lock.unlock();

  Entry result;
  try {
    result = std::make_shared<const RunResult>(compute());
  } catch (...) {
    lock.lock();
    flight->done = true;
    flights_.erase(key);
    flight_cv_.notify_all();
    throw;
  }

  lock.lock();
  const bool keep = result->summary.status == RunStatus::kCompleted;
  flight->done = true;
  flight->result = result;  // waiters share even a failed run; only completed ones are kept
  flights_.erase(key);
  if (keep && capacity_ > 0) {
    lru_.emplace_front(key, result);
    index_[key] = lru_.begin();
    while (lru_.size() > capacity_) {
      index_.erase(lru_.back().first);
      lru_.pop_back();
    }
  }
  flight_cv_.notify_all();
  return result;
}

std::size_t ResultCache::size() const {
  std::lock_guard lock(mutex_);
  return lru_.size();
}

long ResultCache::hits() const {
  std::lock_guard lock(mutex_);
  return hits_;
}

long ResultCache::misses() const {
  std::lock_guard lock(mutex_);
  return misses_;
}

}  // namespace pfem::server
