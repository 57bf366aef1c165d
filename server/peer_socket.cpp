#include "server/peer_socket.h"

#include <netdb.h>
#include <netinet/in.h>
#include <sys/socket.h>

#include <cerrno>
#include <cstdlib>
#include <filesystem>

namespace pfem::server {
namespace {

// (numeric host, port) of a socket address; port -1 for other families.
std::pair<std::string, int> endpoint(const sockaddr_storage& a, socklen_t size) {
  char host[NI_MAXHOST];
  char port[NI_MAXSERV];
  if ((a.ss_family != AF_INET && a.ss_family != AF_INET6) ||
      getnameinfo(reinterpret_cast<const sockaddr*>(&a), size, host, sizeof host, port, sizeof port,
                  NI_NUMERICHOST | NI_NUMERICSERV) != 0) {
    return {"", -1};
  }
  return {host, std::atoi(port)};
}

}  // namespace

int find_peer_socket(int local_port, const std::string& peer_addr, int peer_port) {
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator("/proc/self/fd", ec)) {
    const std::string name = entry.path().filename().string();
    char* end = nullptr;
    const long fd = std::strtol(name.c_str(), &end, 10);
    if (*end != '\0') continue;
    sockaddr_storage local{}, peer{};
    socklen_t local_size = sizeof local, peer_size = sizeof peer;
    if (getsockname(int(fd), reinterpret_cast<sockaddr*>(&local), &local_size) != 0 ||
        getpeername(int(fd), reinterpret_cast<sockaddr*>(&peer), &peer_size) != 0) {
      continue;  // not a socket, or not connected
    }
    if (endpoint(local, local_size).second == local_port &&
        endpoint(peer, peer_size) == std::pair{peer_addr, peer_port}) {
      return int(fd);
    }
  }
  return -1;
}

bool peer_closed(int fd) {
  char byte;
  const auto n = recv(fd, &byte, 1, MSG_PEEK | MSG_DONTWAIT);
  if (n > 0) return false;  // the client sent more (a pipelined request): still there
  if (n == 0) return true;  // orderly close
  return errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR;
}

}  // namespace pfem::server
