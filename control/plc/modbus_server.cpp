#include "control/plc/modbus_server.hpp"

#include <modbus.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <new>
#include <stdexcept>
#include <utility>
#include <vector>

#include "common/demand.hpp"

namespace vmt::control::plc {
namespace {

using gateway::ModbusAddress;
using gateway::SignalImage;

// MBAP header: transaction id, protocol id, length (unit id + PDU), unit id.
constexpr int kMbapBytes = 7;
constexpr int kMaxLengthField = 1 + MODBUS_MAX_PDU_LENGTH;
// Room for many pipelined requests per recv; a partial frame left over is always < 260 bytes.
constexpr size_t kClientBuffer = 4096;
// Bounds on the work one Poll does for one peer, so that a flooding client cannot keep Poll from
// returning; what is left is served by the next Poll.
constexpr int kMaxReadsPerPoll = 16;
constexpr int kMaxAcceptsPerPoll = 16;

// Protocol limits (Modbus Application Protocol 1.1b3, 6.1-6.17).
constexpr int kMaxReadBits = 2000;
constexpr int kMaxReadRegisters = 125;
constexpr int kMaxWriteBits = 1968;
constexpr int kMaxWriteRegisters = 123;
constexpr int kMaxWriteReadWrite = 121;

// The AXD_WR block (header): B+0 axis, B+1 ident, B+2..3 value written together; B+4, B+5 read.
constexpr int kAxdRegisters = 6;
constexpr int kAxdWritten = 4;
constexpr int kMaxAxisNumber = 32;

int Word(const uint8_t* p) { return p[0] << 8 | p[1]; }

std::string HostPort(const std::string& host, int port) {
  const std::string h = host.empty() ? "*" : host;
  if (h.find(':') != std::string::npos) return "[" + h + "]:" + std::to_string(port);
  return h + ":" + std::to_string(port);
}

struct Client {
  int fd = -1;
  std::vector<uint8_t> buf = std::vector<uint8_t>(kClientBuffer);
  size_t have = 0;
  bool closed = false;
};

enum class Reply { kSent, kDrop };

}  // namespace

struct ModbusServer::State {
  SignalImage* image = nullptr;
  Options options;
  int listen_fd = -1;
  int port = 0;
  modbus_t* ctx = nullptr;  // formats and sends replies; never reads from a socket
  modbus_mapping_t* mapping = nullptr;
  // By ModbusAddress::Area, by address: the id of the signal there, -1 for none.
  std::array<std::vector<int>, 4> owner;
  int cycle_register = -1;
  uint32_t cycle = 0;
  int axd_register = -1;                      // B, -1: no AXD_WR block
  std::array<uint16_t, kAxdRegisters> axd{};  // what B..B+5 read
  int status_register = -1;                   // -1: no status block
  std::vector<uint16_t> status_words;         // what the status block reads
  std::vector<Client> clients;                // closed ones until the end of Poll
  int open_clients = 0;
  std::vector<pollfd> fds;
  Stats stats;
  bool polling = false;  // inside Poll: the clients vector is being worked on

  ~State() {
    for (Client& c : clients) {
      if (c.fd >= 0) close(c.fd);
    }
    if (listen_fd >= 0) close(listen_fd);
    if (mapping != nullptr) modbus_mapping_free(mapping);
    if (ctx != nullptr) modbus_free(ctx);
  }

  const gateway::Signal& Sig(int id) const { return image->table()[id]; }

  int Owner(ModbusAddress::Area area, int address) const {
    const std::vector<int>& o = owner[area];
    return address >= 0 && address < static_cast<int>(o.size()) ? o[address] : -1;
  }

  bool InAxd(int a) const {
    return axd_register >= 0 && a >= axd_register && a < axd_register + kAxdRegisters;
  }

  bool InStatus(int a) const {
    return status_register >= 0 && a >= status_register &&
           a < status_register + static_cast<int>(status_words.size());
  }

  bool Readable(ModbusAddress::Area area, int address, int quantity) const {
    for (int a = address; a < address + quantity; ++a) {
      const bool special =
          (area == ModbusAddress::kHoldingRegister && (a == cycle_register || InAxd(a))) ||
          (area == ModbusAddress::kInputRegister && InStatus(a));
      if (!special && Owner(area, a) < 0) return false;
    }
    return true;
  }

  // Every register of [address, address + quantity) belongs to a holding signal lying wholly
  // inside the range: the partial-write rule of the header.
  bool WholeSignals(int address, int quantity) const {
    const int end = address + quantity;
    for (int a = address; a < end;) {
      const int id = Owner(ModbusAddress::kHoldingRegister, a);
      if (id < 0) return false;
      const ModbusAddress& m = Sig(id).modbus;
      if (m.address != a || m.address + m.count > end) return false;
      a += m.count;
    }
    return true;
  }

  void FillBits(ModbusAddress::Area area, int address, int quantity, uint8_t* tab) const {
    for (int a = address; a < address + quantity; ++a) tab[a] = image->Bool(Owner(area, a)) ? 1 : 0;
  }

  void FillRegisters(ModbusAddress::Area area, int address, int quantity, uint16_t* tab) const {
    std::array<uint16_t, gateway::kStringBytes / 2> words{};
    const int end = address + quantity;
    for (int a = address; a < end;) {
      if (area == ModbusAddress::kHoldingRegister && a == cycle_register) {
        tab[a++] = static_cast<uint16_t>(cycle);
        continue;
      }
      if (area == ModbusAddress::kHoldingRegister && InAxd(a)) {
        tab[a] = axd[static_cast<size_t>(a - axd_register)];
        ++a;
        continue;
      }
      if (area == ModbusAddress::kInputRegister && InStatus(a)) {
        tab[a] = status_words[static_cast<size_t>(a - status_register)];
        ++a;
        continue;
      }
      const int id = Owner(area, a);
      const ModbusAddress& m = Sig(id).modbus;
      gateway::ToRegisters(*image, id, std::span<uint16_t>(words.data(), m.count));
      // A read may start or end inside a multi-register signal.
      for (int k = std::max(a, m.address); k < std::min(end, m.address + m.count); ++k) {
        tab[k] = words[k - m.address];
      }
      a = m.address + m.count;
    }
  }

  void ApplyRegisters(int address, int quantity, const uint8_t* data) {
    std::array<uint16_t, gateway::kStringBytes / 2> words{};
    for (int a = address; a < address + quantity;) {
      const int id = Owner(ModbusAddress::kHoldingRegister, a);
      const int count = Sig(id).modbus.count;
      for (int k = 0; k < count; ++k) {
        words[k] = static_cast<uint16_t>(Word(data + 2 * (a - address + k)));
      }
      gateway::FromRegisters(*image, id, std::span<const uint16_t>(words.data(), count));
      a += count;
    }
  }

  Reply Send(int fd, const uint8_t* adu, int length) {
    if (modbus_set_socket(ctx, fd) != 0 || modbus_reply(ctx, adu, length, mapping) < 0) {
      return Reply::kDrop;
    }
    ++stats.requests_served;
    switch (adu[kMbapBytes]) {
      case MODBUS_FC_WRITE_SINGLE_COIL:
      case MODBUS_FC_WRITE_SINGLE_REGISTER:
      case MODBUS_FC_WRITE_MULTIPLE_COILS:
      case MODBUS_FC_WRITE_MULTIPLE_REGISTERS:
      case MODBUS_FC_MASK_WRITE_REGISTER:
      case MODBUS_FC_WRITE_AND_READ_REGISTERS:
        ++stats.writes;
    }
    return Reply::kSent;
  }

  Reply Exception(int fd, uint8_t* adu, int code) {
    // libmodbus answers with function + 0x80; for a request whose code already has the high bit
    // that would wrap, so clear it: the reply carries the same code with the bit set.
    adu[kMbapBytes] &= 0x7f;
    if (modbus_set_socket(ctx, fd) != 0 || modbus_reply_exception(ctx, adu, code) < 0) {
      return Reply::kDrop;
    }
    ++stats.exceptions_sent;
    return Reply::kSent;
  }

  // The write of `value` to the cycle register, already known to be alone in its request.
  Reply Cycle(int fd, uint8_t* adu, int length, int value) {
    const uint32_t next = cycle + 1;
    if (value != static_cast<int>(next & 0xffff)) {
      return Exception(fd, adu, MODBUS_EXCEPTION_ILLEGAL_DATA_VALUE);
    }
    if (options.on_cycle) {
      try {
        options.on_cycle(next);
      } catch (...) {
        // The caller's failure, not the peer's: the client learns the cycle did not complete.
        return Exception(fd, adu, MODBUS_EXCEPTION_SLAVE_OR_SERVER_FAILURE);
      }
    }
    cycle = next;
    ++stats.cycles;
    mapping->tab_registers[cycle_register] = static_cast<uint16_t>(value);
    return Send(fd, adu, length);
  }

  // The AXD_WR block's four written registers, `data` their eight bytes; the request is known to
  // write exactly B..B+3. Returns an exception code, or 0 when the drive has answered.
  int Axd(const uint8_t* data) {
    const int axis = Word(data);
    const int ident = Word(data + 2);
    const auto value = static_cast<int32_t>(static_cast<uint32_t>(Word(data + 4)) << 16 |
                                            static_cast<uint32_t>(Word(data + 6)));
    if (axis < 1 || axis > kMaxAxisNumber || ident < 1) return MODBUS_EXCEPTION_ILLEGAL_DATA_VALUE;
    AxdWrStatus status;
    try {
      status = options.axd_wr(axis, ident, value);
    } catch (...) {
      return MODBUS_EXCEPTION_SLAVE_OR_SERVER_FAILURE;
    }
    for (int k = 0; k < kAxdWritten; ++k)
      axd[static_cast<size_t>(k)] = static_cast<uint16_t>(Word(data + 2 * k));
    axd[4] = static_cast<uint16_t>(static_cast<int>(status) + 1);
    axd[5] = static_cast<uint16_t>(axd[5] + 1);
    ++stats.axd_writes;
    return 0;
  }

  // One complete frame: the header is checked, `length` is 7 + the PDU's length (>= 1).
  Reply Serve(int fd, uint8_t* adu, int length) {
    const uint8_t* pdu = adu + kMbapBytes;
    const int pdu_length = length - kMbapBytes;
    const int function = pdu[0];
    const auto exception = [&](int code) { return Exception(fd, adu, code); };
    constexpr int kValue = MODBUS_EXCEPTION_ILLEGAL_DATA_VALUE;
    constexpr int kAddress = MODBUS_EXCEPTION_ILLEGAL_DATA_ADDRESS;
    const int address = pdu_length >= 3 ? Word(pdu + 1) : 0;
    const int quantity = pdu_length >= 5 ? Word(pdu + 3) : 0;

    switch (function) {
      case MODBUS_FC_READ_COILS:
      case MODBUS_FC_READ_DISCRETE_INPUTS: {
        const auto area =
            function == MODBUS_FC_READ_COILS ? ModbusAddress::kCoil : ModbusAddress::kDiscreteInput;
        if (pdu_length != 5 || quantity < 1 || quantity > kMaxReadBits) return exception(kValue);
        if (!Readable(area, address, quantity)) return exception(kAddress);
        FillBits(area, address, quantity,
                 area == ModbusAddress::kCoil ? mapping->tab_bits : mapping->tab_input_bits);
        return Send(fd, adu, length);
      }
      case MODBUS_FC_READ_HOLDING_REGISTERS:
      case MODBUS_FC_READ_INPUT_REGISTERS: {
        const auto area = function == MODBUS_FC_READ_HOLDING_REGISTERS
                              ? ModbusAddress::kHoldingRegister
                              : ModbusAddress::kInputRegister;
        if (pdu_length != 5 || quantity < 1 || quantity > kMaxReadRegisters) {
          return exception(kValue);
        }
        if (!Readable(area, address, quantity)) return exception(kAddress);
        FillRegisters(area, address, quantity,
                      area == ModbusAddress::kHoldingRegister ? mapping->tab_registers
                                                              : mapping->tab_input_registers);
        return Send(fd, adu, length);
      }
      case MODBUS_FC_WRITE_SINGLE_COIL: {
        if (pdu_length != 5 || (quantity != 0xff00 && quantity != 0)) return exception(kValue);
        const int id = Owner(ModbusAddress::kCoil, address);
        if (id < 0) return exception(kAddress);
        image->SetBool(id, quantity != 0);
        return Send(fd, adu, length);
      }
      case MODBUS_FC_WRITE_SINGLE_REGISTER: {
        if (pdu_length != 5) return exception(kValue);
        if (address == cycle_register) return Cycle(fd, adu, length, quantity);
        // The AXD_WR block is written whole (FC16 / FC23), never a register of it alone.
        if (!WholeSignals(address, 1)) return exception(kAddress);
        ApplyRegisters(address, 1, pdu + 3);
        return Send(fd, adu, length);
      }
      case MODBUS_FC_WRITE_MULTIPLE_COILS: {
        if (pdu_length < 6 || quantity < 1 || quantity > kMaxWriteBits ||
            pdu[5] != (quantity + 7) / 8 || pdu_length != 6 + pdu[5]) {
          return exception(kValue);
        }
        for (int a = address; a < address + quantity; ++a) {
          if (Owner(ModbusAddress::kCoil, a) < 0) return exception(kAddress);
        }
        for (int i = 0; i < quantity; ++i) {
          image->SetBool(Owner(ModbusAddress::kCoil, address + i), (pdu[6 + i / 8] >> (i % 8)) & 1);
        }
        return Send(fd, adu, length);
      }
      case MODBUS_FC_WRITE_MULTIPLE_REGISTERS: {
        if (pdu_length < 6 || quantity < 1 || quantity > kMaxWriteRegisters ||
            pdu[5] != 2 * quantity || pdu_length != 6 + pdu[5]) {
          return exception(kValue);
        }
        if (quantity == 1 && address == cycle_register) {
          return Cycle(fd, adu, length, Word(pdu + 6));
        }
        if (address == axd_register && quantity == kAxdWritten) {
          const int code = Axd(pdu + 6);
          return code != 0 ? exception(code) : Send(fd, adu, length);
        }
        if (!WholeSignals(address, quantity)) return exception(kAddress);
        ApplyRegisters(address, quantity, pdu + 6);
        return Send(fd, adu, length);
      }
      case MODBUS_FC_WRITE_AND_READ_REGISTERS: {
        const int write_address = pdu_length >= 7 ? Word(pdu + 5) : 0;
        const int write_quantity = pdu_length >= 9 ? Word(pdu + 7) : 0;
        if (pdu_length < 10 || quantity < 1 || quantity > kMaxReadRegisters || write_quantity < 1 ||
            write_quantity > kMaxWriteReadWrite || pdu[9] != 2 * write_quantity ||
            pdu_length != 10 + pdu[9]) {
          return exception(kValue);
        }
        const bool axd_write = write_address == axd_register && write_quantity == kAxdWritten;
        if ((!axd_write && !WholeSignals(write_address, write_quantity)) ||
            !Readable(ModbusAddress::kHoldingRegister, address, quantity)) {
          return exception(kAddress);
        }
        if (axd_write) {
          if (const int code = Axd(pdu + 10); code != 0) return exception(code);
          // B..B+3 now hold the request's words, which libmodbus also copies in before the
          // read: the read back shows them, the result and the count.
          FillRegisters(ModbusAddress::kHoldingRegister, address, quantity, mapping->tab_registers);
          return Send(fd, adu, length);
        }
        ApplyRegisters(write_address, write_quantity, pdu + 10);
        // libmodbus copies the written words into the mapping before it reads the range back, so
        // registers written by this request read back as sent (STRING bytes after the NUL too).
        FillRegisters(ModbusAddress::kHoldingRegister, address, quantity, mapping->tab_registers);
        return Send(fd, adu, length);
      }
      default:
        return exception(MODBUS_EXCEPTION_ILLEGAL_FUNCTION);
    }
  }

  // Serves the complete frames in c.buf; false if the connection must close.
  bool ServeBuffered(Client& c) {
    size_t at = 0;
    while (c.have - at >= kMbapBytes) {
      uint8_t* adu = c.buf.data() + at;
      const int protocol = Word(adu + 2);
      const int length_field = Word(adu + 4);
      // A wrong header leaves no trustworthy frame boundary to resynchronise on.
      if (protocol != 0 || length_field < 2 || length_field > kMaxLengthField) return false;
      const size_t frame = 6 + static_cast<size_t>(length_field);
      if (c.have - at < frame) break;
      if (Serve(c.fd, adu, static_cast<int>(frame)) == Reply::kDrop) return false;
      at += frame;
    }
    if (at > 0) {
      std::memmove(c.buf.data(), c.buf.data() + at, c.have - at);
      c.have -= at;
    }
    return true;
  }

  void Drop(Client& c) {
    if (c.closed) return;
    close(c.fd);
    c.fd = -1;
    c.closed = true;
    --open_clients;
    ++stats.clients_dropped;
  }

  void Read(Client& c) {
    try {
      for (int i = 0; i < kMaxReadsPerPoll && !c.closed; ++i) {
        const ssize_t n = recv(c.fd, c.buf.data() + c.have, c.buf.size() - c.have, 0);
        if (n > 0) {
          c.have += static_cast<size_t>(n);
          if (!ServeBuffered(c)) Drop(c);
        } else if (n == 0) {
          Drop(c);  // also discards a partly received request
        } else if (errno == EAGAIN || errno == EWOULDBLOCK) {
          return;
        } else if (errno != EINTR) {
          Drop(c);
        }
      }
    } catch (...) {
      // Nothing a peer sends should get here (requests are checked before use); if anything
      // does, losing that one connection is the contained failure.
      Drop(c);
    }
  }

  void Accept() {
    for (int i = 0; i < kMaxAcceptsPerPoll; ++i) {
      const int fd = accept4(listen_fd, nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC);
      if (fd < 0) {
        if (errno == EINTR || errno == ECONNABORTED) continue;
        return;  // EAGAIN: none pending; EMFILE and the like: retried next Poll
      }
      if (open_clients >= options.max_clients) {
        close(fd);
        ++stats.clients_refused;
        continue;
      }
      const int one = 1;
      if (setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one) != 0) {
        // Without it replies still arrive, only later (Nagle): not worth refusing the client.
      }
      try {
        clients.push_back(Client{.fd = fd});
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
};

ModbusServer::ModbusServer(SignalImage& image, Options options)
    : state_(std::make_unique<State>()) {
  State& s = *state_;
  s.image = &image;
  s.options = std::move(options);
  const Options& o = s.options;
  if (o.port < 0 || o.port > 65535) {
    throw std::invalid_argument("ModbusServer: port " + std::to_string(o.port) +
                                " outside 0..65535");
  }
  if (o.max_clients < 1) {
    throw std::invalid_argument("ModbusServer: max_clients " + std::to_string(o.max_clients) +
                                " < 1");
  }

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
    } else if (listen(fd, std::max(o.max_clients, 4)) != 0) {
      step = "listen";
    }
    if (step != nullptr) {
      failure = std::string(step) + ": " + std::strerror(errno);
      close(fd);
      continue;
    }
    s.listen_fd = fd;
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

ModbusServer::~ModbusServer() = default;
ModbusServer::ModbusServer(ModbusServer&&) noexcept = default;
ModbusServer& ModbusServer::operator=(ModbusServer&&) noexcept = default;

void ModbusServer::Poll(int timeout_ms) {
  State& s = *state_;
  // Cleared on every way out, so that DropClients can tell a call from on_cycle.
  struct Polling {
    bool& flag;
    explicit Polling(bool& f) : flag(f) { flag = true; }
    ~Polling() { flag = false; }
  } polling(s.polling);
  try {
    s.fds.clear();
    s.fds.push_back({s.listen_fd, POLLIN, 0});
    for (const Client& c : s.clients) s.fds.push_back({c.fd, POLLIN, 0});
  } catch (const std::bad_alloc&) {
    return;  // nothing served this time; the peers wait in their sockets
  }
  const int ready = poll(s.fds.data(), s.fds.size(), timeout_ms < 0 ? -1 : timeout_ms);
  if (ready <= 0) return;  // timeout; EINTR (or EFAULT/ENOMEM): the caller polls again

  // s.fds[i + 1] is s.clients[i]: Accept below appends only after this loop.
  const size_t polled = s.clients.size();
  for (size_t i = 0; i < polled; ++i) {
    if (s.fds[i + 1].revents != 0) s.Read(s.clients[i]);
  }
  if (s.fds[0].revents != 0) s.Accept();
  std::erase_if(s.clients, [](const Client& c) { return c.closed; });
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
  for (Client& c : s.clients) s.Drop(c);
  s.clients.clear();
}

int ModbusServer::port() const { return state_->port; }
const ModbusServer::Stats& ModbusServer::stats() const { return state_->stats; }
int ModbusServer::clients() const { return state_->open_clients; }
uint32_t ModbusServer::cycle() const { return state_->cycle; }

}  // namespace vmt::control::plc
