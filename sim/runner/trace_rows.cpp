#include "sim/runner/trace_rows.hpp"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace vmt::sim {
namespace {

// A value's six decimals as one integer, rounded as printf rounds (to nearest, ties to even, on
// the double's exact binary value): |v| * 10^6 = m * 5^6 * 2^(e + 6) with m the 53-bit mantissa,
// an integer product and one shift. False where the integer would not fit in 64 bits (|v| past
// 9e12, infinities, NaN): those take the general path.
bool ScaledMicros(double v, uint64_t& micros) {
  const uint64_t bits = std::bit_cast<uint64_t>(v);
  const int biased = static_cast<int>((bits >> 52) & 0x7ff);
  uint64_t m = bits & ((uint64_t{1} << 52) - 1);
  if (biased == 0x7ff || std::fabs(v) >= 9e12) return false;
  if (biased != 0) m |= uint64_t{1} << 52;
  const int shift = (biased == 0 ? 1 : biased) - 1075 + 6;                // v = m * 2^(shift - 6)
  const unsigned __int128 p = static_cast<unsigned __int128>(m) * 15625;  // m * 5^6
  if (shift >= 0) {
    micros = static_cast<uint64_t>(p << shift);  // below 9e18 by the range check
    return true;
  }
  if (shift <= -100) {  // p < 2^67: far below half a millionth
    micros = 0;
    return true;
  }
  const int down = -shift;
  uint64_t q = static_cast<uint64_t>(p >> down);
  const unsigned __int128 rest = p & ((static_cast<unsigned __int128>(1) << down) - 1);
  const unsigned __int128 half = static_cast<unsigned __int128>(1) << (down - 1);
  if (rest > half || (rest == half && (q & 1))) ++q;
  micros = q;
  return true;
}

// "00" to "99": two digits per division.
constexpr char kDigitPairs[] =
    "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
    "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
    "8081828384858687888990919293949596979899";

// A row written straight into its string, sized up front for its longest form (every field at
// its cut of 31 characters with the comma), so that a field costs no bounds checks. A field
// whose value has the bits it had in the row before is copied as it was written then.
class RowWriter {
 public:
  RowWriter(size_t fields, std::vector<TraceRowWriter::Field>& last, std::string& buffer)
      : last_(last), row_(buffer) {
    if (row_.size() < 31 * fields + 1 + kSlack) row_.resize(31 * fields + 1 + kSlack);
    p_ = row_.data();
    last_.resize(fields);
  }
  void First(double v) { Field(v, 31); }
  /// No "-0.000000": a zero of either sign is written as 0.
  void Next(double v) {
    *p_++ = ',';
    Field(v == 0 ? 0.0 : v, 30);
  }
  std::string_view Done() {
    *p_++ = '\n';
    return {row_.data(), static_cast<size_t>(p_ - row_.data())};
  }

 private:
  static constexpr size_t kSlack = 32;  // a field is copied as a whole 32-byte block
  static_assert(sizeof(TraceRowWriter::Field::text) == kSlack);

  void Field(double v, size_t width) {
    TraceRowWriter::Field& f = last_[field_++];
    const uint64_t bits = std::bit_cast<uint64_t>(v);
    if (f.size > 0 && f.bits == bits) {
      std::memcpy(p_, f.text, kSlack);
      p_ += f.size;
      return;
    }
    char* const start = p_;
    Fixed6(v, width);
    f.bits = bits;
    f.size = static_cast<uint8_t>(p_ - start);
    std::memcpy(f.text, start, f.size);
  }

  // What printf's "%.6f" writes, byte for byte, at most `width` characters (a value past
  // 1e23, a drive gone wild, is cut there, as the trace has always cut it). Nearly every trace
  // value takes the integer path (ScaledMicros); the rest std::to_chars with a precision, which
  // is exact as printf is but runs multi-precision arithmetic: formatting was a sixth of a
  // kinematic run's instructions with it alone.
  void Fixed6(double v, size_t width) {
    uint64_t micros = 0;
    if (!ScaledMicros(v, micros)) {
      char buf[400];  // the longest fixed form of a double: 309 digits, sign, point, 6 decimals
      const std::to_chars_result r =
          std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, 6);
      const size_t n = std::min(static_cast<size_t>(r.ptr - buf), width);
      std::memcpy(p_, buf, n);
      p_ += n;
      return;
    }
    // Backwards from the last decimal into a block: three pairs of decimals, the point, the
    // whole part (at most 13 digits below 9e12), the sign; then the block is copied whole.
    char block[64] = {};
    char* const end = block + 40;
    char* q = end;
    uint64_t whole = micros / 1000000;
    uint32_t decimals = static_cast<uint32_t>(micros % 1000000);
    for (int k = 0; k < 3; ++k, decimals /= 100) {
      q -= 2;
      std::memcpy(q, kDigitPairs + 2 * (decimals % 100), 2);
    }
    *--q = '.';
    while (whole >= 100) {
      q -= 2;
      std::memcpy(q, kDigitPairs + 2 * (whole % 100), 2);
      whole /= 100;
    }
    if (whole >= 10) {
      q -= 2;
      std::memcpy(q, kDigitPairs + 2 * whole, 2);
    } else {
      *--q = static_cast<char>('0' + whole);
    }
    if (std::signbit(v)) *--q = '-';
    std::memcpy(p_, q, kSlack);  // q >= block + 18: the 32 bytes lie within the block
    p_ += end - q;               // at most 22 characters, below every width
  }

  std::vector<TraceRowWriter::Field>& last_;
  size_t field_ = 0;
  std::string& row_;  ///< at least the longest row long: never resized while written
  char* p_;
};

}  // namespace

std::string TraceHeader(const MachineModel& m, bool nc) {
  std::string h = "t";
  for (const DriveParams& d : m.drives) {
    const std::string& n = d.info.name;
    h += "," + n + ".cmd," + n + ".pos," + n + ".vel";
    if (d.spindle || d.info.kind == control::AxisKind::kRotary) h += "," + n + ".rpm";
    if (d.parameter_sets.size() > 1) h += "," + n + ".set";  // S-0-0254, current set
  }
  for (const DogClutch& k : m.clutches) h += "," + k.name + ".state";
  if (nc) h += ",nc.state,nc.line";
  return h + "\n";
}

std::string TraceRow(double t, const MachineModel& m, const control::AmplifierTelegram& at,
                     const control::MasterTelegram& mdt, const std::vector<ClutchState>& clutches,
                     const control::channel::Channel* channel) {
  return std::string(TraceRowWriter().Row(t, m, at, mdt, clutches, channel));
}

std::string_view TraceRowWriter::Row(double t, const MachineModel& m,
                                     const control::AmplifierTelegram& at,
                                     const control::MasterTelegram& mdt,
                                     const std::vector<ClutchState>& clutches,
                                     const control::channel::Channel* channel) {
  RowWriter row(1 + 5 * m.drives.size() + clutches.size() + 2, last_, buffer_);
  row.First(t);
  for (size_t d = 0; d < m.drives.size(); ++d) {
    const control::DriveFeedback& fb = at.feedback[d];
    row.Next(mdt.setpoints[d].mode == control::DriveMode::kOff ? 0.0 : mdt.setpoints[d].value);
    row.Next(fb.position);
    row.Next(fb.velocity);
    if (m.drives[d].spindle || m.drives[d].info.kind == control::AxisKind::kRotary)
      row.Next(fb.velocity / 6.0);
    if (m.drives[d].parameter_sets.size() > 1) row.Next(fb.parameter_set);
  }
  for (ClutchState c : clutches) row.Next(static_cast<int>(c));
  if (channel) {
    row.Next(static_cast<int>(channel->state()));
    row.Next(channel->line());
  }
  return row.Done();
}

}  // namespace vmt::sim
