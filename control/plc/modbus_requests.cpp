// The Modbus TCP server's requests: one complete frame checked in full, applied, answered
// (modbus_server.hpp says which request gets which answer).

#include <modbus.h>

#include <algorithm>
#include <array>
#include <span>

#include "control/plc/modbus_server_state.hpp"

namespace vmt::control::plc::modbus_detail {
namespace {

// Protocol limits (Modbus Application Protocol 1.1b3, 6.1-6.17).
constexpr int kMaxReadBits = 2000;
constexpr int kMaxReadRegisters = 125;
constexpr int kMaxWriteBits = 1968;
constexpr int kMaxWriteRegisters = 123;
constexpr int kMaxWriteReadWrite = 121;

constexpr int kAxdWritten = 4;
constexpr int kMaxAxisNumber = 32;

// The unit ids a Modbus TCP client uses for "the server at this address" besides its own.
constexpr int kUnitAny = 0;
constexpr int kUnitTcp = 0xFF;

bool IsWrite(int function) {
  switch (function) {
    case MODBUS_FC_WRITE_SINGLE_COIL:
    case MODBUS_FC_WRITE_SINGLE_REGISTER:
    case MODBUS_FC_WRITE_MULTIPLE_COILS:
    case MODBUS_FC_WRITE_MULTIPLE_REGISTERS:
    case MODBUS_FC_WRITE_AND_READ_REGISTERS:
      return true;
    default:
      return false;
  }
}

}  // namespace

bool ServerState::InAxd(int a) const {
  return axd_register >= 0 && a >= axd_register && a < axd_register + kAxdRegisters;
}

bool ServerState::InStatus(int a) const {
  return status_register >= 0 && a >= status_register &&
         a < status_register + static_cast<int>(status_words.size());
}

bool ServerState::Readable(ModbusAddress::Area area, int address, int quantity) const {
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
bool ServerState::WholeSignals(int address, int quantity) const {
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

void ServerState::FillBits(ModbusAddress::Area area, int address, int quantity,
                           uint8_t* tab) const {
  for (int a = address; a < address + quantity; ++a) tab[a] = image->Bool(Owner(area, a)) ? 1 : 0;
}

void ServerState::FillRegisters(ModbusAddress::Area area, int address, int quantity,
                                uint16_t* tab) const {
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

void ServerState::ApplyRegisters(int address, int quantity, const uint8_t* data) {
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

// The PLC role: free, this client's, or left unused by its holder for plc_role_timeout_ms.
bool ServerState::MayWrite(const Client& c) const {
  if (plc_client == 0 || plc_client == c.id) return true;
  const int timeout = options.plc_role_timeout_ms;
  return timeout > 0 && Clock::now() - plc_written_at >= std::chrono::milliseconds(timeout);
}

Reply ServerState::Send(Client& c, const uint8_t* adu, int length) {
  if (modbus_set_socket(ctx, c.fd) != 0 || modbus_reply(ctx, adu, length, mapping) < 0) {
    return Reply::kDrop;
  }
  ++stats.requests_served;
  if (IsWrite(adu[kMbapBytes])) {
    // A write that succeeded: its client is the PLC (it may have taken the role just now).
    ++stats.writes;
    plc_client = c.id;
    plc_written_at = Clock::now();
  }
  return Reply::kSent;
}

Reply ServerState::Exception(Client& c, uint8_t* adu, int code) {
  // libmodbus answers with function + 0x80; for a request whose code already has the high bit
  // that would wrap, so clear it: the reply carries the same code with the bit set.
  adu[kMbapBytes] &= 0x7f;
  if (modbus_set_socket(ctx, c.fd) != 0 || modbus_reply_exception(ctx, adu, code) < 0) {
    return Reply::kDrop;
  }
  ++stats.exceptions_sent;
  return Reply::kSent;
}

// The write of `value` to the cycle register, already known to be alone in its request.
Reply ServerState::Cycle(Client& c, uint8_t* adu, int length, int value) {
  const uint32_t next = cycle + 1;
  if (value != static_cast<int>(next & 0xffff)) {
    return Exception(c, adu, MODBUS_EXCEPTION_ILLEGAL_DATA_VALUE);
  }
  if (options.on_cycle) {
    try {
      options.on_cycle(next);
    } catch (...) {
      // The caller's failure, not the peer's: the client learns the cycle did not complete.
      return Exception(c, adu, MODBUS_EXCEPTION_SLAVE_OR_SERVER_FAILURE);
    }
  }
  cycle = next;
  ++stats.cycles;
  mapping->tab_registers[cycle_register] = static_cast<uint16_t>(value);
  return Send(c, adu, length);
}

// The AXD_WR block's four written registers, `data` their eight bytes; the request is known to
// write exactly B..B+3. Returns an exception code, or 0 when the drive has answered.
int ServerState::Axd(const uint8_t* data) {
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

// A write request (IsWrite) from the PLC role's holder, or from a client that may take it.
Reply ServerState::ServeWrite(Client& c, uint8_t* adu, int length) {
  const uint8_t* pdu = adu + kMbapBytes;
  const int pdu_length = length - kMbapBytes;
  const auto exception = [&](int code) { return Exception(c, adu, code); };
  constexpr int kValue = MODBUS_EXCEPTION_ILLEGAL_DATA_VALUE;
  constexpr int kAddress = MODBUS_EXCEPTION_ILLEGAL_DATA_ADDRESS;
  const int address = pdu_length >= 3 ? Word(pdu + 1) : 0;
  const int quantity = pdu_length >= 5 ? Word(pdu + 3) : 0;

  switch (pdu[0]) {
    case MODBUS_FC_WRITE_SINGLE_COIL: {
      if (pdu_length != 5 || (quantity != 0xff00 && quantity != 0)) return exception(kValue);
      const int id = Owner(ModbusAddress::kCoil, address);
      if (id < 0) return exception(kAddress);
      image->SetBool(id, quantity != 0);
      return Send(c, adu, length);
    }
    case MODBUS_FC_WRITE_SINGLE_REGISTER: {
      if (pdu_length != 5) return exception(kValue);
      if (address == cycle_register) return Cycle(c, adu, length, quantity);
      // The AXD_WR block is written whole (FC16 / FC23), never a register of it alone.
      if (!WholeSignals(address, 1)) return exception(kAddress);
      ApplyRegisters(address, 1, pdu + 3);
      return Send(c, adu, length);
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
      return Send(c, adu, length);
    }
    case MODBUS_FC_WRITE_MULTIPLE_REGISTERS: {
      if (pdu_length < 6 || quantity < 1 || quantity > kMaxWriteRegisters ||
          pdu[5] != 2 * quantity || pdu_length != 6 + pdu[5]) {
        return exception(kValue);
      }
      if (quantity == 1 && address == cycle_register) {
        return Cycle(c, adu, length, Word(pdu + 6));
      }
      if (address == axd_register && quantity == kAxdWritten) {
        const int code = Axd(pdu + 6);
        return code != 0 ? exception(code) : Send(c, adu, length);
      }
      if (!WholeSignals(address, quantity)) return exception(kAddress);
      ApplyRegisters(address, quantity, pdu + 6);
      return Send(c, adu, length);
    }
    default: {  // MODBUS_FC_WRITE_AND_READ_REGISTERS
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
        return Send(c, adu, length);
      }
      ApplyRegisters(write_address, write_quantity, pdu + 10);
      // libmodbus copies the written words into the mapping before it reads the range back, so
      // registers written by this request read back as sent (STRING bytes after the NUL too).
      FillRegisters(ModbusAddress::kHoldingRegister, address, quantity, mapping->tab_registers);
      return Send(c, adu, length);
    }
  }
}

Reply ServerState::Serve(Client& c, uint8_t* adu, int length) {
  const uint8_t* pdu = adu + kMbapBytes;
  const int pdu_length = length - kMbapBytes;
  const int function = pdu[0];
  const auto exception = [&](int code) { return Exception(c, adu, code); };
  const int unit = adu[kMbapBytes - 1];
  if (unit != options.unit_id && unit != kUnitAny && unit != kUnitTcp) {
    ++stats.wrong_unit;
    return exception(MODBUS_EXCEPTION_GATEWAY_TARGET);
  }
  if (IsWrite(function)) {
    if (!MayWrite(c)) {
      ++stats.writes_refused;
      return exception(MODBUS_EXCEPTION_ILLEGAL_FUNCTION);
    }
    return ServeWrite(c, adu, length);
  }
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
      return Send(c, adu, length);
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
      return Send(c, adu, length);
    }
    default:
      return exception(MODBUS_EXCEPTION_ILLEGAL_FUNCTION);
  }
}

}  // namespace vmt::control::plc::modbus_detail
