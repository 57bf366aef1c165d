#pragma once
// The results GetResult streams are sending, shared: a stored result is read and decoded once
// however many streams send it at once, and freed (its memory given back to the system) when
// the last of them ends. 60 streams of one 20 MB result had held a copy each (1.8 GB).
//
// Thread-safety: open() may be called from any thread.
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "pfem/v1/service.pb.h"
#include "server/store.h"

namespace pfem::server {

class OpenResults {
 public:
  explicit OpenResults(Store& store) : store_(store) {}

  // Job `id`'s stored result, or nullptr when none is stored. Throws StoreError.
  std::shared_ptr<const pfem::v1::Result> open(const std::string& id);

 private:
  Store& store_;
  std::mutex mutex_;
  std::map<std::string, std::weak_ptr<const pfem::v1::Result>> open_;
};

}  // namespace pfem::server
