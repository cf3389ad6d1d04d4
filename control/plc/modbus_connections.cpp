// The Modbus TCP server's connections: accepting (the allowed addresses, the client limit),
// reading, serving the buffered requests in turn within a deadline, closing idle connections.

#include <arpa/inet.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstring>
#include <ctime>
#include <new>

#include "control/plc/modbus_server_state.hpp"

namespace vmt::control::plc::modbus_detail {

ServerState::~ServerState() {
  for (Client& c : clients) {
    if (c.fd >= 0) close(c.fd);
  }
  if (listen_fd >= 0) close(listen_fd);
  if (mapping != nullptr) modbus_mapping_free(mapping);
  if (ctx != nullptr) modbus_free(ctx);
}

void ServerState::Drop(Client& c) {
  if (c.closed) return;
  close(c.fd);
  c.fd = -1;
  c.closed = true;
  --open_clients;
  ++stats.clients_dropped;
  if (plc_client == c.id) plc_client = 0;  // the next connection that writes is the PLC
}

// A complete frame, or a header so wrong that the connection must close, is at the front.
bool ServerState::HasFrame(const Client& c) const {
  if (c.closed || c.have - c.at < kMbapBytes) return false;
  const uint8_t* adu = c.buf.data() + c.at;
  const int length_field = Word(adu + 4);
  if (Word(adu + 2) != 0 || length_field < 2 || length_field > kMaxLengthField) return true;
  return c.have - c.at >= 6 + static_cast<size_t>(length_field);
}

// Serves the frame at the front of c.buf (HasFrame); false if the connection must close.
bool ServerState::ServeOneBuffered(Client& c) {
  uint8_t* adu = c.buf.data() + c.at;
  const int length_field = Word(adu + 4);
  // A wrong header leaves no trustworthy frame boundary to resynchronise on.
  if (Word(adu + 2) != 0 || length_field < 2 || length_field > kMaxLengthField) return false;
  const size_t frame = 6 + static_cast<size_t>(length_field);
  c.heard_at = Clock::now();
  if (Serve(c, adu, static_cast<int>(frame)) == Reply::kDrop) return false;
  c.at += frame;
  return true;
}

// One request per client in turn, starting where the last round stopped, until no client has a
// complete request left or the deadline has passed (after the first turn, with `first_turn`).
void ServerState::ServeInTurn(Clock::time_point deadline, bool first_turn) {
  const size_t n = clients.size();
  if (n == 0) return;
  for (bool more = true; more; first_turn = false) {
    more = false;
    for (size_t k = 0; k < n; ++k) {
      const size_t i = (next_turn + k) % n;
      Client& c = clients[i];
      if (!HasFrame(c)) continue;
      if (!first_turn && Clock::now() >= deadline) {
        next_turn = i;
        return;
      }
      try {
        if (!ServeOneBuffered(c)) Drop(c);
      } catch (...) {
        // Nothing a peer sends should get here (requests are checked before use); if anything
        // does, losing that one connection is the contained failure.
        Drop(c);
      }
      more = more || HasFrame(c);
    }
  }
  next_turn = 0;
}

void ServerState::Read(Client& c) {
  if (c.at > 0) {
    std::memmove(c.buf.data(), c.buf.data() + c.at, c.have - c.at);
    c.have -= c.at;
    c.at = 0;
  }
  if (c.have == c.buf.size()) return;  // full of requests to serve first
  const ssize_t n = recv(c.fd, c.buf.data() + c.have, c.buf.size() - c.have, 0);
  if (n > 0) {
    c.have += static_cast<size_t>(n);
  } else if (n == 0) {
    c.peer_closed = true;  // its complete requests are still answered; a partial one is not
  } else if (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) {
    Drop(c);
  }
}

bool ServerState::Allowed(const sockaddr_storage& peer) const {
  in6_addr a{};
  if (peer.ss_family == AF_INET) {
    const in_addr v4 = reinterpret_cast<const sockaddr_in&>(peer).sin_addr;
    if ((ntohl(v4.s_addr) >> 24) == 127) return true;
    a.s6_addr[10] = a.s6_addr[11] = 0xff;
    std::memcpy(&a.s6_addr[12], &v4, 4);
  } else if (peer.ss_family == AF_INET6) {
    a = reinterpret_cast<const sockaddr_in6&>(peer).sin6_addr;
    if (IN6_IS_ADDR_LOOPBACK(&a) || (IN6_IS_ADDR_V4MAPPED(&a) && a.s6_addr[12] == 127)) {
      return true;
    }
  } else {
    return false;
  }
  if (options.allowed_clients.empty()) return true;
  return std::any_of(allowed.begin(), allowed.end(),
                     [&](const in6_addr& x) { return std::memcmp(&x, &a, sizeof a) == 0; });
}

// Full: closes the longest idle connection that does not hold the PLC role. False if there is
// none (max_clients 1 and the PLC connected).
bool ServerState::MakeRoom() {
  Client* idlest = nullptr;
  for (Client& c : clients) {
    if (c.closed || c.id == plc_client) continue;
    if (idlest == nullptr || c.heard_at < idlest->heard_at) idlest = &c;
  }
  if (idlest == nullptr) return false;
  Drop(*idlest);
  ++stats.clients_evicted;
  return true;
}

void ServerState::Accept() {
  for (int i = 0; i < kMaxAcceptsPerPoll; ++i) {
    sockaddr_storage peer{};
    socklen_t peer_length = sizeof peer;
    const int fd = accept4(listen_fd, reinterpret_cast<sockaddr*>(&peer), &peer_length,
                           SOCK_NONBLOCK | SOCK_CLOEXEC);
    if (fd < 0) {
      if (errno == EINTR || errno == ECONNABORTED) continue;
      return;  // EAGAIN: none pending; EMFILE and the like: retried next Poll
    }
    if (!Allowed(peer)) {
      close(fd);
      ++stats.clients_refused;
      ++stats.clients_not_allowed;
      continue;
    }
    if (open_clients >= options.max_clients && !MakeRoom()) {
      close(fd);
      ++stats.clients_refused;
      continue;
    }
    const int one = 1;
    if (setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one) != 0) {
      // Without it replies still arrive, only later (Nagle): not worth refusing the client.
    }
    try {
      clients.push_back(Client{.fd = fd, .id = next_client_id++, .heard_at = Clock::now()});
    } catch (const std::bad_alloc&) {
      close(fd);
      ++stats.clients_refused;
      return;
    }
    ++open_clients;
    ++stats.clients_accepted;
    // Its first request may already be here.
    Read(clients.back());
  }
}

void ServerState::CloseIdle(Clock::time_point now) {
  for (Client& c : clients) {
    if (c.closed) continue;
    if (c.peer_closed && !HasFrame(c)) {
      Drop(c);  // also discards a partly received request
    } else if (options.client_timeout_ms > 0 &&
               now - c.heard_at >= std::chrono::milliseconds(options.client_timeout_ms)) {
      Drop(c);
      ++stats.clients_timed_out;
    }
  }
}

void ServerState::PollOnce(int timeout_ms, Clock::time_point deadline, bool first_turn) {
  const Clock::time_point start = Clock::now();
  Clock::time_point until =
      timeout_ms < 0 ? Clock::time_point::max() : start + std::chrono::milliseconds(timeout_ms);
  until = std::min(until, deadline);
  // An idle connection is closed on time even when nothing else happens.
  if (options.client_timeout_ms > 0) {
    for (const Client& c : clients) {
      if (!c.closed) {
        until = std::min(until, c.heard_at + std::chrono::milliseconds(options.client_timeout_ms));
      }
    }
  }
  bool pending = false;
  try {
    fds.clear();
    fds.push_back({listen_fd, POLLIN, 0});
    for (const Client& c : clients) {
      pending = pending || HasFrame(c) || c.peer_closed;
      // A closed peer would wake poll for ever, and a full buffer is served before more is read.
      const bool listen = !c.closed && !c.peer_closed && c.have - c.at < c.buf.size();
      fds.push_back({listen ? c.fd : -1, POLLIN, 0});
    }
  } catch (const std::bad_alloc&) {
    return;  // nothing served this time; the peers wait in their sockets
  }
  timespec wait{};
  if (!pending && until > start) {
    const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(until - start).count();
    wait.tv_sec = static_cast<time_t>(std::min<int64_t>(ns / 1000000000, INT_MAX));
    wait.tv_nsec = static_cast<long>(ns % 1000000000);
  }
  const bool forever = !pending && until == Clock::time_point::max();
  const int ready = ppoll(fds.data(), fds.size(), forever ? nullptr : &wait, nullptr);
  if (ready > 0) {
    // fds[i + 1] is clients[i]: Accept below appends only after this loop.
    const size_t polled = clients.size();
    for (size_t i = 0; i < polled; ++i) {
      if (fds[i + 1].fd >= 0 && fds[i + 1].revents != 0) Read(clients[i]);
    }
    if (fds[0].revents != 0) Accept();
  }
  ServeInTurn(deadline, first_turn);
  CloseIdle(Clock::now());
  const size_t before = clients.size();
  std::erase_if(clients, [](const Client& c) { return c.closed; });
  if (clients.size() != before) next_turn = 0;
}

}  // namespace vmt::control::plc::modbus_detail
