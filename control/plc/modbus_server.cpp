#include "control/plc/modbus_server.hpp"

#include <arpa/inet.h>
#include <modbus.h>
#include <netdb.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <utility>

#include "common/demand.hpp"
#include "control/plc/modbus_server_state.hpp"

namespace vmt::control::plc {
namespace {

using gateway::ModbusAddress;
using gateway::SignalImage;
using modbus_detail::Clock;
using modbus_detail::kAxdRegisters;

constexpr int kMaxClients = 1024;
// Connections waiting for accept: a burst beyond it would stall in the connect (SYN retries)
// instead of making room (modbus_server.hpp).
constexpr int kBacklog = 64;

std::string HostPort(const std::string& host, int port) {
  const std::string h = host.empty() ? "*" : host;
  if (h.find(':') != std::string::npos) return "[" + h + "]:" + std::to_string(port);
  return h + ":" + std::to_string(port);
}

bool Loopback(const sockaddr* a) {
  if (a->sa_family == AF_INET) {
    return (ntohl(reinterpret_cast<const sockaddr_in*>(a)->sin_addr.s_addr) >> 24) == 127;
  }
  if (a->sa_family == AF_INET6) {
    const in6_addr& v6 = reinterpret_cast<const sockaddr_in6*>(a)->sin6_addr;
    return IN6_IS_ADDR_LOOPBACK(&v6) || (IN6_IS_ADDR_V4MAPPED(&v6) && v6.s6_addr[12] == 127);
  }
  return false;
}

// A numeric IPv4 or IPv6 address as an IPv6 one (IPv4 v4-mapped, as accept reports them).
in6_addr ClientAddress(const std::string& text) {
  in6_addr a{};
  in_addr v4{};
  if (inet_pton(AF_INET, text.c_str(), &v4) == 1) {
    a.s6_addr[10] = a.s6_addr[11] = 0xff;
    std::memcpy(&a.s6_addr[12], &v4, 4);
    return a;
  }
  if (inet_pton(AF_INET6, text.c_str(), &a) == 1) return a;
  throw std::invalid_argument("ModbusServer: allowed client " + text +
                              " is not a numeric IPv4 or IPv6 address");
}

// Options outside their ranges are refused before anything is opened.
void CheckOptions(const ModbusServer::Options& o) {
  if (o.port < 0 || o.port > 65535) {
    throw std::invalid_argument("ModbusServer: port " + std::to_string(o.port) +
                                " outside 0..65535");
  }
  if (o.max_clients < 1 || o.max_clients > kMaxClients) {
    throw std::invalid_argument("ModbusServer: max_clients " + std::to_string(o.max_clients) +
                                " outside 1.." + std::to_string(kMaxClients));
  }
  if (o.unit_id < 1 || o.unit_id > 247) {
    throw std::invalid_argument("ModbusServer: unit id " + std::to_string(o.unit_id) +
                                " outside 1..247");
  }
  if (o.client_timeout_ms < 0 || o.plc_role_timeout_ms < 0) {
    throw std::invalid_argument("ModbusServer: a negative timeout");
  }
}

// Which signal owns each coil, input and register; a signal whose Modbus place does not fit its
// type or direction, or that shares a place with another, is refused.
void MapSignals(modbus_detail::ServerState& s, const SignalImage& image) {
  for (int id = 0; id < image.size(); ++id) {
    const gateway::Signal& sig = image.table()[id];
    const ModbusAddress& m = sig.modbus;
    const bool bit_area = m.area == ModbusAddress::kCoil || m.area == ModbusAddress::kDiscreteInput;
    const int count = bit_area ? 1 : gateway::RegisterCount(sig.type);
    // FromRegisters / ToRegisters abort on a count that does not fit the type; refuse such a
    // table here rather than when a client touches it.
    if ((sig.type == gateway::SignalType::kBool) != bit_area || m.count != count || m.address < 0 ||
        m.address + m.count > 65536) {
      throw std::invalid_argument("ModbusServer: signal " + sig.name + " has Modbus " +
                                  gateway::ToString(m.area) + " " + std::to_string(m.address) +
                                  " x" + std::to_string(m.count) + ", which does not fit its type");
    }
    // What vmt drives is read only to every client (modbus_server.hpp).
    const bool writable_area =
        m.area == ModbusAddress::kCoil || m.area == ModbusAddress::kHoldingRegister;
    if (writable_area && !gateway::PlcWrites(sig.direction)) {
      throw std::invalid_argument("ModbusServer: signal " + sig.name + " is written by vmt (" +
                                  gateway::ToString(sig.direction) + ") but lies in the " +
                                  gateway::ToString(m.area) + " area, which clients write");
    }
    std::vector<int>& owner = s.owner[m.area];
    if (static_cast<int>(owner.size()) < m.address + m.count) owner.resize(m.address + m.count, -1);
    for (int a = m.address; a < m.address + m.count; ++a) {
      if (owner[a] >= 0) {
        throw std::invalid_argument("ModbusServer: signals " + image.table()[owner[a]].name +
                                    " and " + sig.name + " share " + gateway::ToString(m.area) +
                                    " " + std::to_string(a));
      }
      owner[a] = id;
    }
  }
}

// The cycle register and the AXD_WR block among the holding registers; the holding registers
// the mapping needs.
int PlaceHoldingBlocks(modbus_detail::ServerState& s) {
  const ModbusServer::Options& o = s.options;
  int holding = static_cast<int>(s.owner[ModbusAddress::kHoldingRegister].size());
  if (o.cycle_register) {
    const int r = *o.cycle_register;
    if (r < 0 || r > 65535) {
      throw std::invalid_argument("ModbusServer: cycle register " + std::to_string(r) +
                                  " outside 0..65535");
    }
    if (s.Owner(ModbusAddress::kHoldingRegister, r) >= 0) {
      throw std::invalid_argument("ModbusServer: cycle register " + std::to_string(r) +
                                  " belongs to signal " +
                                  s.Sig(s.Owner(ModbusAddress::kHoldingRegister, r)).name);
    }
    s.cycle_register = r;
    holding = std::max(holding, r + 1);
  }
  if (o.axd_wr_register.has_value() != static_cast<bool>(o.axd_wr)) {
    throw std::invalid_argument(
        "ModbusServer: an AXD_WR block needs both its register and its writer");
  }
  if (o.axd_wr_register) {
    const int b = *o.axd_wr_register;
    if (b < 0 || b + kAxdRegisters > 65536) {
      throw std::invalid_argument("ModbusServer: AXD_WR block " + std::to_string(b) + ".." +
                                  std::to_string(b + kAxdRegisters - 1) + " outside 0..65535");
    }
    for (int a = b; a < b + kAxdRegisters; ++a) {
      if (s.Owner(ModbusAddress::kHoldingRegister, a) >= 0) {
        throw std::invalid_argument("ModbusServer: AXD_WR block register " + std::to_string(a) +
                                    " belongs to signal " +
                                    s.Sig(s.Owner(ModbusAddress::kHoldingRegister, a)).name);
      }
      if (a == s.cycle_register) {
        throw std::invalid_argument("ModbusServer: AXD_WR block register " + std::to_string(a) +
                                    " is the cycle register");
      }
    }
    s.axd_register = b;
    holding = std::max(holding, b + kAxdRegisters);
  }
  return holding;
}

// The NC status block among the input registers; the input registers the mapping needs.
int PlaceStatusBlock(modbus_detail::ServerState& s) {
  const ModbusServer::Options& o = s.options;
  int input = static_cast<int>(s.owner[ModbusAddress::kInputRegister].size());
  if (o.status_register) {
    const int b = *o.status_register;
    if (o.status_count < 1 || b < 0 || b + o.status_count > 65536) {
      throw std::invalid_argument("ModbusServer: status block " + std::to_string(b) + " x" +
                                  std::to_string(o.status_count) + " outside 0..65535");
    }
    for (int a = b; a < b + o.status_count; ++a) {
      if (s.Owner(ModbusAddress::kInputRegister, a) >= 0) {
        throw std::invalid_argument("ModbusServer: status block register " + std::to_string(a) +
                                    " belongs to signal " +
                                    s.Sig(s.Owner(ModbusAddress::kInputRegister, a)).name);
      }
    }
    s.status_register = b;
    s.status_words.assign(static_cast<size_t>(o.status_count), 0);
    input = std::max(input, b + o.status_count);
  }
  return input;
}

// The listening socket on the options' host and port (port 0: one the system picks).
void Listen(modbus_detail::ServerState& s) {
  const ModbusServer::Options& o = s.options;
  const std::string where = HostPort(o.host, o.port);
  addrinfo hints{};
  hints.ai_flags = AI_PASSIVE | AI_NUMERICSERV;
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* found = nullptr;
  const std::string service = std::to_string(o.port);
  const int gai =
      getaddrinfo(o.host.empty() ? nullptr : o.host.c_str(), service.c_str(), &hints, &found);
  if (gai != 0) {
    throw std::runtime_error("ModbusServer: cannot listen on " + where + ": " +
                             (gai == EAI_SYSTEM ? std::strerror(errno) : gai_strerror(gai)));
  }
  std::string failure = "no address";
  for (addrinfo* ai = found; ai != nullptr && s.listen_fd < 0; ai = ai->ai_next) {
    const int fd =
        socket(ai->ai_family, ai->ai_socktype | SOCK_NONBLOCK | SOCK_CLOEXEC, ai->ai_protocol);
    if (fd < 0) {
      failure = std::string("socket: ") + std::strerror(errno);
      continue;
    }
    const int one = 1;
    const char* step = nullptr;
    // SO_REUSEADDR: a restarted simulation can listen again while old connections linger.
    if (setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one) != 0) {
      step = "setsockopt(SO_REUSEADDR)";
    } else if (bind(fd, ai->ai_addr, ai->ai_addrlen) != 0) {
      step = "bind";
    } else if (!Loopback(ai->ai_addr) && !o.allow_remote) {
      close(fd);
      freeaddrinfo(found);
      throw std::invalid_argument(
          "ModbusServer: " + where +
          " is not a loopback address: clients on the network could connect and write; "
          "allow that explicitly (vmt serve --allow-remote)");
    } else if (listen(fd, std::max(o.max_clients, kBacklog)) != 0) {
      step = "listen";
    }
    if (step != nullptr) {
      failure = std::string(step) + ": " + std::strerror(errno);
      close(fd);
      continue;
    }
    s.listen_fd = fd;
    s.remote = !Loopback(ai->ai_addr);
  }
  freeaddrinfo(found);
  if (s.listen_fd < 0) {
    throw std::runtime_error("ModbusServer: cannot listen on " + where + ": " + failure);
  }
  sockaddr_storage bound{};
  socklen_t bound_length = sizeof bound;
  if (getsockname(s.listen_fd, reinterpret_cast<sockaddr*>(&bound), &bound_length) != 0) {
    throw std::runtime_error("ModbusServer: getsockname on " + where + ": " + std::strerror(errno));
  }
  s.port = bound.ss_family == AF_INET6 ? ntohs(reinterpret_cast<sockaddr_in6*>(&bound)->sin6_port)
                                       : ntohs(reinterpret_cast<sockaddr_in*>(&bound)->sin_port);
}

}  // namespace

struct ModbusServer::State : modbus_detail::ServerState {};

ModbusServer::ModbusServer(SignalImage& image, Options options)
    : state_(std::make_unique<State>()) {
  State& s = *state_;
  s.image = &image;
  s.options = std::move(options);
  const Options& o = s.options;
  CheckOptions(o);
  for (const std::string& a : o.allowed_clients) s.allowed.push_back(ClientAddress(a));

  MapSignals(s, image);
  const int holding = PlaceHoldingBlocks(s);
  const int input = PlaceStatusBlock(s);
  s.ctx = modbus_new_tcp("127.0.0.1", MODBUS_TCP_DEFAULT_PORT);
  if (s.ctx == nullptr) {
    throw std::runtime_error(std::string("ModbusServer: modbus_new_tcp: ") +
                             modbus_strerror(errno));
  }
  // libmodbus sleeps for the response timeout before some of its own exception replies; every
  // request is checked before libmodbus sees it, but keep that sleep negligible regardless.
  if (modbus_set_response_timeout(s.ctx, 0, 1000) != 0) {
    throw std::runtime_error(std::string("ModbusServer: modbus_set_response_timeout: ") +
                             modbus_strerror(errno));
  }
  s.mapping = modbus_mapping_new(static_cast<int>(s.owner[ModbusAddress::kCoil].size()),
                                 static_cast<int>(s.owner[ModbusAddress::kDiscreteInput].size()),
                                 holding, input);
  if (s.mapping == nullptr) {
    throw std::runtime_error(std::string("ModbusServer: modbus_mapping_new: ") +
                             modbus_strerror(errno));
  }

  Listen(s);
}

ModbusServer::~ModbusServer() = default;
ModbusServer::ModbusServer(ModbusServer&&) noexcept = default;
ModbusServer& ModbusServer::operator=(ModbusServer&&) noexcept = default;

namespace {
// Cleared on every way out, so that DropClients can tell a call from on_cycle.
struct Polling {
  bool& flag;
  explicit Polling(bool& f) : flag(f) { flag = true; }
  ~Polling() { flag = false; }
};
}  // namespace

void ModbusServer::Poll(int timeout_ms) {
  Polling polling(state_->polling);
  state_->PollOnce(timeout_ms, Clock::time_point::max());
}

void ModbusServer::ServeUntil(std::chrono::steady_clock::time_point deadline) {
  Polling polling(state_->polling);
  // A late caller (catching up on cycles) still has each client's next request answered: the
  // PLC is heard, and a turn of requests is small.
  bool first_turn = true;
  do {
    state_->PollOnce(-1, deadline, first_turn);
    first_turn = false;
  } while (Clock::now() < deadline);
}

void ModbusServer::SetStatus(std::span<const uint16_t> words) {
  State& s = *state_;
  VMT_DEMAND(words.size() == s.status_words.size(),
             "ModbusServer::SetStatus: %zu words for a status block of %zu", words.size(),
             s.status_words.size());
  std::copy(words.begin(), words.end(), s.status_words.begin());
}

void ModbusServer::DropClients() {
  State& s = *state_;
  VMT_DEMAND(!s.polling, "ModbusServer::DropClients called from inside Poll (on_cycle)");
  for (modbus_detail::Client& c : s.clients) s.Drop(c);
  s.clients.clear();
}

int ModbusServer::port() const { return state_->port; }
const ModbusServer::Stats& ModbusServer::stats() const { return state_->stats; }
int ModbusServer::clients() const { return state_->open_clients; }
bool ModbusServer::remote() const { return state_->remote; }
uint32_t ModbusServer::cycle() const { return state_->cycle; }

}  // namespace vmt::control::plc
