#include "server/open_results.h"

#include <malloc.h>

namespace pfem::server {

std::shared_ptr<const pfem::v1::Result> OpenResults::open(const std::string& id) {
  std::lock_guard lock(mutex_);
  std::erase_if(open_, [](const auto& entry) { return entry.second.expired(); });
  if (auto shared = open_[id].lock()) return shared;
  auto stored = store_.get_result(id);
  if (!stored) {
    open_.erase(id);
    return nullptr;
  }
  // glibc keeps the freed pages of a large result in its arenas; trimming returns them.
  std::shared_ptr<const pfem::v1::Result> shared(
      new pfem::v1::Result(std::move(*stored)), [](const pfem::v1::Result* result) {
        delete result;
        ::malloc_trim(0);
      });
  open_[id] = shared;
  return shared;
}

}  // namespace pfem::server
