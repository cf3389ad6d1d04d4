// Data access of running MTC200 programs: TLD(...) reads and writes the channel's tool list,
// OTD(...) its zero offsets, MTD(...) the machine data pages of fast measurement. A measuring
// program takes its correction value into the machining this way (fast-measurement manual 2.1
// CORRECTION, 5.5, 5.6):
//   TLD(1,3,,1,11,) = TLD(1,3,,1,11,) + MTD(105,,1,13)
//   OTD(,,4,1) = OTD(,,4,1) + MTD(105,,1,13)
//
// TLD(memory, T, -, D, element, -). The manual's examples disagree about where the T number
// stands: 2.1 describes TLD(,1,12,,11,) as "T number 12" (position 3), 5.6 writes
// TLD(1,3,,1,11,) and TLD(1,3,,1,12,) for "wear register L1 / L2 of T3" in its program, its
// step list and its introduction (position 2; 5.5 calls the same line T5, which fits neither).
// Position 2 fits the most examples and the one complete program, so T is position 2; the 2.1
// form cannot be accepted beside it (its position 2 would be T1), so a value at position 3 is an
// error that says where T goes. The element (11 = wear L1) is position 5 in all of them.
// Position 4 is 1 in 5.6 and omitted in 2.1: the cutting edge D (omitted: the active D if T is
// the active tool, else D1). Position 1 is 1 in 5.6 and omitted in 2.1, which says "in the
// current process"; OTD's example names "the current NC memory" and "the active process" for its
// two omitted positions. vmt reads position 1 of TLD and OTD as the NC memory and position 2 of
// OTD as the process: a process 1 in 5.6 would be the second process (processes count from 0,
// 3.1 BASISMESSPAGE), the NC memory of a lathe program is the first. These are vmt's choices.
// Elements: 11, 12, 13 are wear L1, L2, L3 (5.5, 5.6); 1, 2, 3 for the geometry lengths L1, L2,
// L3 are vmt's numbering (the manual gives none), readable only: the set-up lengths are the
// operator's, a measuring program corrects the wear.
//
// OTD(memory, process, table, axis): table 4..9 is the shift of G54..G59 (2.1: "OTD(,,4,1) ...
// the shift according to G54"), axis the channel axis number 1.. (1: X in the example).
//
// MTD(page, LV1, LV2, element): measure::ReadMtd / WriteMtd; an omitted control variable is
// "the current one", never 0 (process 0 is the master process).
//
// Writes take effect in the tables at once: the interpreter runs ahead of the axes, so a block
// read ahead before the write keeps the translation it was planned with, the next block that
// starts (UpdateTranslation) moves with the new one. During an interruption a write is the same
// as the operator's edit (REPOS manual 2.5, SetZeroOffset): the return to the contour compares
// TranslationOf the interrupted state with the tables as they are.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "control/channel/channel.hpp"
#include "control/measure/measuring_pages.hpp"

namespace vmt::control::channel {

namespace {

using Arg = nc::InstructionArg;

/// vmt runs one NC memory; 5.6 numbers it 1 (see above).
constexpr int kNcMemory = 1;

bool Omitted(const Arg& a) { return a.kind == Arg::Kind::kOmitted; }

/// "TLD(1,3,,1,11,)": the address as the program computed it, for the error texts.
std::string AddressText(nc::Instruction data, const std::vector<Arg>& args) {
  std::string s = std::string(nc::InstructionName(data)) + "(";
  for (size_t i = 0; i < args.size(); ++i) {
    if (i) s += ",";
    if (Omitted(args[i])) continue;
    if (args[i].kind == Arg::Kind::kName) {
      s += args[i].name;
      continue;
    }
    char number[32];
    std::snprintf(number, sizeof number, "%.12g", args[i].value);
    s += number;
  }
  return s + ")";
}

/// Argument `i` (0-based) as a whole number in lo..hi, or an error naming it as `what`.
std::string WholeNumber(const std::vector<Arg>& args, size_t i, const char* what, int lo, int hi,
                        int& out) {
  const std::string where = "argument " + std::to_string(i + 1) + " (" + what + ")";
  if (Omitted(args[i])) return where + " is missing";
  const double v = args[i].value;
  if (!std::isfinite(v) || v != std::floor(v) || v < lo || v > hi)
    return where + " must be a whole number in " + std::to_string(lo) + ".." + std::to_string(hi);
  out = static_cast<int>(v);
  return "";
}

}  // namespace

nc::DataAccess Channel::MakeDataAccess() {
  // One function for both directions: `value` is read into, or written from.
  auto access = [this](nc::Instruction data, const std::vector<Arg>& args, double& value,
                       bool write) -> std::string {
    const std::string at = AddressText(data, args);
    auto fail = [&](const std::string& text) { return at + ": " + text; };
    std::string error;
    auto memory = [&]() -> std::string {
      int m = 0;
      if (Omitted(args[0])) return "";
      const std::string e = WholeNumber(args, 0, "NC memory", kNcMemory, kNcMemory, m);
      return e.empty() ? e : e + " (vmt has one NC memory, 1)";
    };
    if (write && !std::isfinite(value)) return fail("the value to write is not a number");
    for (size_t i = 0; i < args.size(); ++i)
      if (args[i].kind == Arg::Kind::kName)  // reads make names variables; the written place not
        return fail("argument " + std::to_string(i + 1) + " is the name " + args[i].name +
                    ", not a number");

    if (data == nc::Instruction::kTld) {
      if (args.size() != 6) return fail("TLD has 6 arguments: (memory, T, , D, element, )");
      if (!(error = memory()).empty()) return fail(error);
      if (!Omitted(args[2]) || !Omitted(args[5]))
        return fail("argument " + std::string(Omitted(args[2]) ? "6" : "3") +
                    " is not used: the T number is argument 2, as in TLD(1,3,,1,11,) for T3");
      int tool = 0, element = 0;
      if (!(error = WholeNumber(args, 1, "T number", 0, 999999, tool)).empty()) return fail(error);
      int edge = modal().tool == tool && modal().correction != 0 ? modal().correction : 1;
      if (!Omitted(args[3]) && !(error = WholeNumber(args, 3, "D", 1, 99, edge)).empty())
        return fail(error);
      if (!WholeNumber(args, 4, "element", 1, 13, element).empty() || (element > 3 && element < 11))
        return fail(
            "argument 5 (element) must be 1, 2, 3 (the lengths L1, L2, L3, read only) or "
            "11, 12, 13 (wear L1, L2, L3)");
      axes::ToolEdge* e = nullptr;
      for (axes::ToolEdge& candidate : tools_.edges)
        if (candidate.tool == tool && candidate.edge == edge) e = &candidate;
      if (!e)
        return fail("T" + std::to_string(tool) + " D" + std::to_string(edge) +
                    " is not in the tool list");
      const auto l = static_cast<size_t>(element > 10 ? element - 11 : element - 1);
      if (element >= 11) {
        if (write)
          e->wear[l] = value;
        else
          value = e->wear[l];
        return "";
      }
      if (write)
        return fail("the length L" + std::to_string(l + 1) +
                    " is the set-up's and cannot be written by the program; its wear is element " +
                    std::to_string(l + 11));
      for (size_t a = 0; a < config_.axes.size(); ++a)
        if (axes::LengthRegister(config_.axes[a].name) == static_cast<int>(l)) {
          value = a < e->length.size() ? e->length[a] : 0;
          return "";
        }
      static constexpr const char* kAxis[] = {"Z", "X", "Y"};
      return fail("the length L" + std::to_string(l + 1) + " lies along " + kAxis[l] +
                  ", which this channel does not have");
    }

    if (data == nc::Instruction::kOtd) {
      if (args.size() != 4) return fail("OTD has 4 arguments: (memory, process, table, axis)");
      if (!(error = memory()).empty()) return fail(error);
      int process = 0, table = 0, axis = 0;
      const int own = config_.process.number;
      if (!Omitted(args[1]) &&
          !(error = WholeNumber(args, 1, "process", own, own, process)).empty())
        return fail(error + " (this channel's process is " + std::to_string(own) + ")");
      if (!(error = WholeNumber(args, 2, "table, 4..9 for G54..G59", 4, 9, table)).empty())
        return fail(error);
      const int n = static_cast<int>(config_.axes.size());
      if (!(error = WholeNumber(args, 3, "channel axis", 1, n, axis)).empty()) return fail(error);
      const int g = table + 50;  // measure::OtdTable: G54..G59 are tables 4..9
      if (write) {
        SetZeroOffset(g, static_cast<size_t>(axis - 1), value);
      } else {
        value = zero_offsets_.Offset(g, static_cast<size_t>(axis - 1));
      }
      return "";
    }

    // MTD
    if (!measuring_.pages()) return fail("no machine data pages (fast measurement is not set up)");
    if (args.size() != 4) return fail("MTD has 4 arguments: (page, LV1, LV2, element)");
    if (Omitted(args[0]) || Omitted(args[3]))
      return fail("the page (argument 1) and the element (argument 4) must be given");
    measure::MtdAddress address;
    address.page = args[0].value;
    if (!Omitted(args[1])) address.lv1 = args[1].value;
    if (!Omitted(args[2])) address.lv2 = args[2].value;
    address.element = args[3].value;
    const int process = config_.process.number;
    if (write) return measure::WriteMtd(*measuring_.pages(), address, process, value);
    const measure::MtdRead read = measure::ReadMtd(*measuring_.pages(), address, process);
    value = read.value;
    return read.error;
  };
  nc::DataAccess d;
  d.read = [access](nc::Instruction data, const std::vector<Arg>& args, double& value) {
    return access(data, args, value, false);
  };
  d.write = [access](nc::Instruction data, const std::vector<Arg>& args, double value) {
    return access(data, args, value, true);
  };
  return d;
}

}  // namespace vmt::control::channel
