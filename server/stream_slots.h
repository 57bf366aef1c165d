#pragma once
// Caps on the streams open at once (WatchJob, GetResult): in total (--max-streams) and per
// client (--max-streams-per-client; a client is its peer address without the port). Each open
// stream holds a server thread and, for GetResult, the result it sends; slow or absent
// readers cannot hold more than these. A stream over a cap is refused with
// RESOURCE_EXHAUSTED naming the cap.
//
// Thread-safety: every method may be called from any thread.
#include <map>
#include <mutex>
#include <string>

namespace pfem::server {

class StreamSlots {
 public:
  StreamSlots(long max_total, long max_per_client)
      : max_total_(max_total), max_per_client_(max_per_client) {}

  // One stream's slot, given back when it is destroyed.
  class Slot {
   public:
    Slot(StreamSlots& slots, std::string client) : slots_(&slots), client_(std::move(client)) {}
    ~Slot();
    Slot(Slot&& other) noexcept : slots_(other.slots_), client_(std::move(other.client_)) {
      other.slots_ = nullptr;
    }
    Slot(const Slot&) = delete;
    Slot& operator=(const Slot&) = delete;
    Slot& operator=(Slot&&) = delete;

   private:
    StreamSlots* slots_;
    std::string client_;
  };

  // A slot for a stream of the client with gRPC peer string `peer` ("ipv4:127.0.0.1:5432").
  // Throws ServiceError(RESOURCE_EXHAUSTED) when a cap is reached.
  Slot acquire(const std::string& peer);

 private:
  void release(const std::string& client);

  const long max_total_;
  const long max_per_client_;
  std::mutex mutex_;
  long open_ = 0;
  std::map<std::string, long> per_client_;
};

}  // namespace pfem::server
