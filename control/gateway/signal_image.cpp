#include "control/gateway/signal_image.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <stdexcept>

#include "common/demand.hpp"

namespace vmt::control::gateway {

SignalImage::SignalImage(std::vector<Signal> table) : table_(std::move(table)) {
  const int n = size();
  types_.reserve(n);
  range_.reserve(n);
  for (const Signal& s : table_) {
    types_.push_back(s.type);
    range_.push_back(IsInteger(s.type) ? Range{MinValue(s.type), MaxValue(s.type)} : Range{1, 0});
  }
  by_name_.resize(n);
  for (int i = 0; i < n; ++i) by_name_[i] = i;
  std::sort(by_name_.begin(), by_name_.end(),
            [this](int a, int b) { return table_[a].name < table_[b].name; });
  for (int i = 1; i < n; ++i) {
    if (table_[by_name_[i - 1]].name == table_[by_name_[i]].name) {
      throw std::invalid_argument("SignalImage: signal name '" + table_[by_name_[i]].name +
                                  "' occurs twice");
    }
  }
  cells_.assign(n, 0);
  Reset();
}

void SignalImage::Reset() {
  ++changes_;
  strings_.clear();
  for (int id = 0; id < size(); ++id) {
    const SignalType t = types_[id];
    const double preset = table_[id].preset;
    if (t == SignalType::kString) {
      cells_[id] = static_cast<int64_t>(strings_.size());
      strings_.emplace_back();
    } else if (IsReal(t)) {
      cells_[id] = RealBits(t, preset);
    } else {
      cells_[id] = static_cast<int64_t>(std::llround(preset));
    }
  }
}

void SignalImage::CopyValuesFrom(const SignalImage& other) {
  VMT_DEMAND(other.size() == size(), "gateway: CopyValuesFrom: an image of another table");
  cells_ = other.cells_;
  strings_ = other.strings_;
  ++changes_;
}

void SignalImage::CopyValue(int id, const SignalImage& other) {
  VMT_DEMAND(other.size() == size(), "gateway: CopyValue: an image of another table");
  Check(id, AnyType, "CopyValue");
  if (types_[id] == SignalType::kString)
    SetString(id, other.strings_[other.cells_[id]]);
  else
    Store(id, other.cells_[id]);
}

int SignalImage::Find(std::string_view name) const {
  const auto it =
      std::lower_bound(by_name_.begin(), by_name_.end(), name,
                       [this](int id, std::string_view n) { return table_[id].name < n; });
  if (it == by_name_.end() || table_[*it].name != name) return -1;
  return *it;
}

int SignalImage::Require(std::string_view name) const {
  const int id = Find(name);
  VMT_DEMAND(id >= 0, "gateway: no signal called '%.*s' in the gateway table",
             static_cast<int>(name.size()), name.data());
  return id;
}

void SignalImage::Refuse(int id, const char* accessor) const {
  VMT_DEMAND(id >= 0 && id < size(), "gateway: %s(%d): no such signal id (table has %d)",
             accessor, id, size());
  common::DemandFailed(__FILE__, __LINE__, "an accessor of the signal's type",
                       "gateway: %s(%s): the signal is %s", accessor, table_[id].name.c_str(),
                       ToString(types_[id]));
}

void SignalImage::RefuseRange(int id, int64_t v) const {
  const SignalType t = types_[id];
  common::DemandFailed(__FILE__, __LINE__, "a value within the signal's type",
                       "gateway: SetInt(%s, %lld): outside the range of %s",
                       table_[id].name.c_str(), static_cast<long long>(v), ToString(t));
}

const std::string& SignalImage::String(int id) const {
  Check(id, IsString, "String");
  return strings_[cells_[id]];
}

void SignalImage::SetString(int id, std::string_view v) {
  Check(id, IsString, "SetString");
  VMT_DEMAND(v.size() <= static_cast<size_t>(kStringBytes - 1) &&
                 v.find('\0') == std::string_view::npos,
             "gateway: SetString(%s): %zu bytes or an embedded NUL; a STRING holds at most %d",
             table_[id].name.c_str(), v.size(), kStringBytes - 1);
  std::string& s = strings_[cells_[id]];
  if (s == v) return;
  s.assign(v);
  ++changes_;
}

namespace {

void CheckRegisters(const SignalImage& image, int id, size_t size, const char* what) {
  VMT_DEMAND(id >= 0 && id < image.size(), "gateway: %s(%d): no such signal id", what, id);
  const Signal& s = image.table()[id];
  VMT_DEMAND(s.type != SignalType::kBool, "gateway: %s(%s): a BOOL is a bit", what, s.name.c_str());
  VMT_DEMAND(size == static_cast<size_t>(RegisterCount(s.type)),
             "gateway: %s(%s): %zu registers for %s, which takes %d", what, s.name.c_str(), size,
             ToString(s.type), RegisterCount(s.type));
}

void PutWords(uint64_t v, std::span<uint16_t> out) {
  for (size_t i = 0; i < out.size(); ++i) {
    out[out.size() - 1 - i] = static_cast<uint16_t>(v >> (16 * i));
  }
}

uint64_t GetWords(std::span<const uint16_t> in) {
  uint64_t v = 0;
  for (uint16_t w : in) v = (v << 16) | w;
  return v;
}

}  // namespace

void ToRegisters(const SignalImage& image, int id, std::span<uint16_t> out) {
  CheckRegisters(image, id, out.size(), "ToRegisters");
  const SignalType t = image.table()[id].type;
  switch (t) {
    case SignalType::kReal:
      PutWords(std::bit_cast<uint32_t>(static_cast<float>(image.Real(id))), out);
      return;
    case SignalType::kLreal:
      PutWords(std::bit_cast<uint64_t>(image.Real(id)), out);
      return;
    case SignalType::kString: {
      const std::string& s = image.String(id);
      for (size_t i = 0; i < out.size(); ++i) {
        const auto byte = [&s](size_t k) -> uint16_t {
          return k < s.size() ? static_cast<unsigned char>(s[k]) : 0;
        };
        out[i] = static_cast<uint16_t>(byte(2 * i) << 8 | byte(2 * i + 1));
      }
      return;
    }
    default:
      // Two's complement within the register width: the cast keeps the low bits.
      PutWords(static_cast<uint64_t>(image.Int(id)), out);
      return;
  }
}

void FromRegisters(SignalImage& image, int id, std::span<const uint16_t> in) {
  CheckRegisters(image, id, in.size(), "FromRegisters");
  const SignalType t = image.table()[id].type;
  const uint64_t v = GetWords(in);
  switch (t) {
    case SignalType::kInt:
      image.SetInt(id, static_cast<int16_t>(v));
      return;
    case SignalType::kDint:
      image.SetInt(id, static_cast<int32_t>(v));
      return;
    case SignalType::kUint:
    case SignalType::kWord:
    case SignalType::kUdint:
    case SignalType::kDword:
      image.SetInt(id, static_cast<int64_t>(v));
      return;
    case SignalType::kReal:
      image.SetReal(id, std::bit_cast<float>(static_cast<uint32_t>(v)));
      return;
    case SignalType::kLreal:
      image.SetReal(id, std::bit_cast<double>(v));
      return;
    case SignalType::kString: {
      std::string s;
      for (uint16_t w : in) {
        s.push_back(static_cast<char>(w >> 8));
        s.push_back(static_cast<char>(w & 0xff));
      }
      s.resize(std::min(s.find('\0'), static_cast<size_t>(kStringBytes - 1)));
      image.SetString(id, s);
      return;
    }
    case SignalType::kBool:
      return;  // rejected by CheckRegisters
  }
}

}  // namespace vmt::control::gateway
