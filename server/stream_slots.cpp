#include "server/stream_slots.h"

#include "server/status.h"

namespace pfem::server {

StreamSlots::Slot::~Slot() {
  if (slots_) slots_->release(client_);
}

StreamSlots::Slot StreamSlots::acquire(const std::string& peer) {
  std::string client = peer.substr(0, peer.rfind(':'));
  std::lock_guard lock(mutex_);
  if (open_ >= max_total_) {
    throw ServiceError(grpc::StatusCode::RESOURCE_EXHAUSTED,
                       "max-streams limit reached: " + std::to_string(open_) +
                           " WatchJob and GetResult streams are open, the limit is " +
                           std::to_string(max_total_));
  }
  long& mine = per_client_[client];
  if (mine >= max_per_client_) {
    throw ServiceError(grpc::StatusCode::RESOURCE_EXHAUSTED,
                       "max-streams-per-client limit reached: " + std::to_string(mine) +
                           " WatchJob and GetResult streams of " + client +
                           " are open, the limit is " + std::to_string(max_per_client_));
  }
  ++mine;
  ++open_;
  return Slot(*this, std::move(client));
}

void StreamSlots::release(const std::string& client) {
  std::lock_guard lock(mutex_);
  --open_;
  if (--per_client_[client] == 0) per_client_.erase(client);
}

}  // namespace pfem::server
