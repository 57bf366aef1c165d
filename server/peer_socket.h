#pragma once
// Finding out whether an HTTP client has gone while its call runs. cpp-httplib 0.11 gives a
// handler its peer's address and port but not its socket, so the socket is looked up among
// this process's descriptors (Linux /proc/self/fd) by its two ends.
#include <string>

namespace pfem::server {

// The connected TCP socket whose local port is local_port and whose peer is peer_addr
// (numeric, as getnameinfo prints it) : peer_port; -1 when there is none.
int find_peer_socket(int local_port, const std::string& peer_addr, int peer_port);

// True when the peer of a connected socket has closed it or reset it (data still unread
// from the peer counts as open).
bool peer_closed(int fd);

}  // namespace pfem::server
