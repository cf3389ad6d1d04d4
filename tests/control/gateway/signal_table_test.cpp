#include "control/gateway/signal_table.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>
#include <string>

#include "control/gateway/signal_catalog.hpp"
#include "tests/control/gateway/lathe_layout.hpp"

namespace vmt::control::gateway {
namespace {

using ::testing::HasSubstr;
using testing::LatheLayout;

const Signal* ByName(const std::vector<Signal>& table, const std::string& name) {
  for (const Signal& s : table) {
    if (s.name == name) return &s;
  }
  return nullptr;
}

std::string Missing(const std::vector<Signal>& table, const std::vector<std::string>& names) {
  std::string missing;
  for (const std::string& n : names) {
    if (ByName(table, n) == nullptr) missing += n + " ";
  }
  return missing;
}

TEST(SignalTable, RepositioningManualNamesAppear) {
  const auto table = BuildSignalTable(LatheLayout());
  EXPECT_EQ(Missing(table, {"P00C.REPOS", "P00C.RESTA", "P00S.REPOS", "P00S.CREST", "P00C.JOGM0",
                            "P00C.JOGM1", "P00C.JOGM2", "P00C.MGPOS", "P00C.MGNEG", "A03C.M3",
                            "A03C.M4", "A03C.M5", "A03C.M19", "P00.EV29", "P00.EV30"}),
            "");
}

TEST(SignalTable, CAxisManualNamesAppear) {
  const auto table = BuildSignalTable(LatheLayout());
  EXPECT_EQ(
      Missing(table,
              {"A01C.HOMLS",    "A01C.READY",    "A01C.JGPOS",    "A01C.JGNEG",    "A01C.HOME",
               "A01C.ENABL",    "A01C.STRBP",    "A01C.QDDS",     "A01C.OTRVL",    "A01C.MTAS",
               "A03C.GEAR1",    "A03C.GEAR2",    "A03C.GEAR3",    "A01S.RF",       "A01S.HOMED",
               "A01S.MVPOS",    "A01S.MVNEG",    "A01S.BBDIG",    "A01S.IDDS",     "A01S.WP0",
               "A01S.WP7",      "A03S.N_NCMD",   "A03S.N_NMIN",   "A03S.MD_MDX",   "A03S.NC_NMAX",
               "A03S.INPOS",    "A03S.P_PX",     "A03S.LOAD90",   "A03S.SYNCHRON", "A03.ROTMOD",
               "A03.ROTMOD_Q",  "A03.SPMOD",     "A03.SPMOD_Q",   "A03.AXD.65012", "A03.AXD.65013",
               "A03.AXD.65014", "A03.AXD.65015", "A04.AXD.65012", "P00S.STOP",     "P00S.REV"}),
      "");
}

TEST(SignalTable, FastMeasurementManualNamesAppear) {
  const auto table = BuildSignalTable(LatheLayout());
  EXPECT_EQ(
      Missing(
          table,
          {"P00.Q9992", "P00.Q9992_Q", "P00.Q9998", "P00.Q9998_Q", "P00.Q9999", "P00.Q9999_Q",
           "P00.EV7", "P00.EV29", "P00.EV30", "P00S.RUN", "P00S.STOP", "P00S.REV", "P00C.REV",
           "A01C.QDDS", "A02C.QDDS", "A01S.IDDS", "P00.MSG_WR", "P00.MSG_WR_N",
           // QMFB1Axx inputs
           "QMFB1A00.ENABLE", "QMFB1A00.RESET", "QMFB1A00.Q_Nummer", "QMFB1A00.Koll_EV",
           "QMFB1A00.Mess_EV", "QMFB1A00.Touch_EV", "QMFB1A00.BasisPage", "QMFB1A00.MessProc",
           "QMFB1A00.ACHS_NR_1", "QMFB1A00.ACHS_NR_2", "QMFB1A00.ACHS_NR_3", "QMFB1A00.I_MT_OK1",
           "QMFB1A00.I_MTast1", "QMFB1A00.I_MT_OK2", "QMFB1A00.I_MTast2", "QMFB1A00.IDDS_1",
           "QMFB1A00.IDDS_2", "QMFB1A00.IDDS_3", "QMFB1A00.AXDdisabl", "QMFB1A00.MTDdisabl",
           // QMFB1Axx outputs
           "QMFB1A00.Init_OK_1", "QMFB1A00.Init_OK_2", "QMFB1A00.Init_OK_3", "QMFB1A00.QDDS_1",
           "QMFB1A00.QDDS_2", "QMFB1A00.QDDS_3", "QMFB1A00.Q_MTst1", "QMFB1A00.Q_MTst2",
           "QMFB1A00.Q_MTstOK", "QMFB1A00.Q_MTstKol", "QMFB1A00.Q_MTstKmp", "QMFB1A00.Q_MTst",
           "QMFB1A00.FEHLER", "QMFB1A00.FEHLER_NR", "QMFB1A00.AXDaktiv", "QMFB1A00.MTDaktiv",
           "QMFB1A00.P_Dat_ovr"}),
      "");
}

TEST(SignalTable, BlockSearchManualNamesAppear) {
  const auto table = BuildSignalTable(LatheLayout());
  std::vector<std::string> names = {"P00.bahn_state.block_search_active_r",
                                    "P00.bahn_state.block_search_state_r",
                                    "P00.bahn_state.covered_distance_r",
                                    "P00.bahn_state.dist_prog_start",
                                    "P00.bahn_state.block_count_r",
                                    "P00.bahn_state.block_search_path_deviation_r",
                                    "P00.bahn_state.stop_conditions_r",
                                    "P00.bahn_lc_control.block_search.command_r",
                                    "P00.bahn_lc_control.block_search.state_r",
                                    "P00.bahn_lc_control.block_search.enable_w",
                                    "P00.SuspendAxisOutput",
                                    "P00.SuspendOutput",
                                    "P00.mc_command_file_offset_w",
                                    "P00.distance_from_program_start"};
  for (const char* object :
       {"type", "auto_return", "no_hold_at_restart", "deviation_max", "breakpoint_position",
        "distance_prog_start", "covered_distance", "pos_start_offset", "pos_start_name",
        "pos_start_type", "pos_start_count", "pos_end_offset", "pos_end_name", "pos_end_type",
        "pos_end_count", "intern_block_count", "block_number", "block_number_pass",
        "block_nbr_prog_name"}) {
    names.push_back(std::string("P00.mc_cmd_bs_") + object + "_w");
    names.push_back(std::string("P00.mc_cmd_bs_") + object + "_r");
  }
  EXPECT_EQ(Missing(table, names), "");
}

TEST(SignalTable, NamesAreUnique) {
  GatewayLayout layout = LatheLayout();
  layout.processes = {0, 1};
  layout.q_functions = {100};
  layout.events = {5};
  const auto table = BuildSignalTable(layout);
  std::set<std::string> names;
  for (const Signal& s : table) EXPECT_TRUE(names.insert(s.name).second) << s.name;
  EXPECT_NE(ByName(table, "P01C.REPOS"), nullptr);
  EXPECT_NE(ByName(table, "P01.Q100_Q"), nullptr);
  EXPECT_NE(ByName(table, "P01.EV5"), nullptr);
}

TEST(SignalTable, ModbusAddressesAreDenseAndUniquePerArea) {
  GatewayLayout layout = LatheLayout();
  layout.processes = {0, 1};
  const auto table = BuildSignalTable(layout);
  std::map<ModbusAddress::Area, int> next;
  for (const Signal& s : table) {
    // Table order is address order within each area, without gaps.
    EXPECT_EQ(s.modbus.address, next[s.modbus.area]) << s.name;
    EXPECT_EQ(s.modbus.count, RegisterCount(s.type)) << s.name;
    next[s.modbus.area] += s.modbus.count;
  }
  EXPECT_EQ(next.size(), 4u);
}

TEST(SignalTable, ModbusAreaFollowsTypeAndDirection) {
  const auto table = BuildSignalTable(LatheLayout());
  const auto area = [&](const char* name) { return ByName(table, name)->modbus.area; };
  EXPECT_EQ(area("P00C.REPOS"), ModbusAddress::kCoil);
  EXPECT_EQ(area("P00S.CREST"), ModbusAddress::kDiscreteInput);
  EXPECT_EQ(area("P00.EV7"), ModbusAddress::kCoil);  // shared: the PLC writes it too
  EXPECT_EQ(area("P00C.FOVR"), ModbusAddress::kHoldingRegister);
  EXPECT_EQ(area("P00.bahn_state.block_search_state_r"), ModbusAddress::kInputRegister);
  EXPECT_EQ(area("QROTMODE"), ModbusAddress::kCoil);
  EXPECT_EQ(area("IROTMODE"), ModbusAddress::kDiscreteInput);
  EXPECT_EQ(ByName(table, "P00.bahn_state.dist_prog_start")->modbus.count, 4);
  EXPECT_EQ(ByName(table, "P00.mc_cmd_bs_pos_start_name_w")->modbus.count, 42);
  EXPECT_EQ(ByName(table, "A03.AXD.65013")->modbus.count, 2);
}

TEST(SignalTable, KnownTypesAndDirections) {
  const auto table = BuildSignalTable(LatheLayout());
  struct Expect {
    const char* name;
    SignalType type;
    Direction direction;
  };
  const Expect expects[] = {
      {"P00C.REPOS", SignalType::kBool, Direction::kPlcToNc},
      {"P00C.RESTA", SignalType::kBool, Direction::kPlcToNc},
      {"P00S.REPOS", SignalType::kBool, Direction::kNcToPlc},
      {"P00S.CREST", SignalType::kBool, Direction::kNcToPlc},
      {"A01C.JGPOS", SignalType::kBool, Direction::kPlcToNc},
      {"A01S.MVPOS", SignalType::kBool, Direction::kNcToPlc},
      {"A03.ROTMOD", SignalType::kBool, Direction::kNcToPlc},
      {"A03.ROTMOD_Q", SignalType::kBool, Direction::kPlcToNc},
      {"A03.SPMOD", SignalType::kBool, Direction::kNcToPlc},
      {"A03.SPMOD_Q", SignalType::kBool, Direction::kPlcToNc},
      {"A03.AXD.65012", SignalType::kWord, Direction::kShared},
      {"A03.AXD.65013", SignalType::kDint, Direction::kShared},
      {"P00.Q9999", SignalType::kBool, Direction::kNcToPlc},
      {"P00.Q9999_Q", SignalType::kBool, Direction::kPlcToNc},
      {"P00.EV29", SignalType::kBool, Direction::kShared},
      {"QMFB1A00.ENABLE", SignalType::kBool, Direction::kPlcToNc},
      {"QMFB1A00.ACHS_NR_1", SignalType::kInt, Direction::kPlcToNc},
      // The block runs in the PLC: its outputs are the PLC's to write too.
      {"QMFB1A00.FEHLER_NR", SignalType::kInt, Direction::kPlcToNc},
      {"QMFB1A00.Q_MTstKol", SignalType::kBool, Direction::kPlcToNc},
      {"P00.mc_cmd_bs_type_w", SignalType::kUint, Direction::kPlcToNc},
      {"P00.mc_cmd_bs_type_r", SignalType::kUint, Direction::kNcToPlc},
      {"P00.mc_cmd_bs_deviation_max_w", SignalType::kUdint, Direction::kPlcToNc},
      {"P00.mc_cmd_bs_covered_distance_w", SignalType::kLreal, Direction::kPlcToNc},
      {"P00.mc_cmd_bs_pos_start_count_w", SignalType::kInt, Direction::kPlcToNc},
      {"P00.mc_cmd_bs_block_nbr_prog_name_w", SignalType::kString, Direction::kPlcToNc},
      {"P00.mc_command_file_offset_w", SignalType::kDint, Direction::kPlcToNc},
      {"P00.bahn_state.block_search_active_r", SignalType::kBool, Direction::kNcToPlc},
      {"P00.bahn_state.block_search_state_r", SignalType::kInt, Direction::kNcToPlc},
      {"P00.bahn_state.covered_distance_r", SignalType::kDint, Direction::kNcToPlc},
      {"P00.bahn_state.block_count_r", SignalType::kUdint, Direction::kNcToPlc},
      {"P00.bahn_state.stop_conditions_r", SignalType::kDint, Direction::kNcToPlc},
      {"P00.bahn_lc_control.block_search.command_r", SignalType::kBool, Direction::kNcToPlc},
      // The PLC's signal in the handshake, though the manual spells it state_r (twincat 7).
      {"P00.bahn_lc_control.block_search.state_r", SignalType::kBool, Direction::kPlcToNc},
      {"P00.bahn_lc_control.block_search.enable_w", SignalType::kBool, Direction::kPlcToNc},
      {"P00C.FOVR", SignalType::kInt, Direction::kPlcToNc},
      {"P00S.ERRNR", SignalType::kInt, Direction::kNcToPlc},
      {"QROTMODE", SignalType::kBool, Direction::kPlcToMachine},
      {"ISPMODE", SignalType::kBool, Direction::kMachineToPlc},
  };
  for (const Expect& e : expects) {
    const Signal* s = ByName(table, e.name);
    ASSERT_NE(s, nullptr) << e.name;
    EXPECT_EQ(s->type, e.type) << e.name;
    EXPECT_EQ(s->direction, e.direction) << e.name;
  }
}

TEST(SignalTable, UnitsAndPresetsComeFromTheManuals) {
  const auto table = BuildSignalTable(LatheLayout());
  EXPECT_EQ(ByName(table, "P00.mc_cmd_bs_deviation_max_w")->unit, "0.1 um");
  EXPECT_THAT(ByName(table, "P00.mc_cmd_bs_deviation_max_w")->meaning, HasSubstr("[0.1 um]"));
  EXPECT_EQ(ByName(table, "A03.AXD.65013")->unit, "0.0001 1/min");
  EXPECT_EQ(ByName(table, "A03.AXD.65015")->unit, "0.0001 deg");
  EXPECT_EQ(ByName(table, "QMFB1A00.Q_Nummer")->preset, 9992);
  EXPECT_EQ(ByName(table, "QMFB1A00.Koll_EV")->preset, 29);
  EXPECT_EQ(ByName(table, "QMFB1A00.Mess_EV")->preset, 30);
  EXPECT_EQ(ByName(table, "QMFB1A00.Touch_EV")->preset, 7);
  EXPECT_EQ(ByName(table, "QMFB1A00.BasisPage")->preset, 90);
  EXPECT_EQ(ByName(table, "P00C.FOVR")->preset, 100);
  EXPECT_THAT(ByName(table, "P00C.REPOS")->source,
              HasSubstr("mtc200-repositioning-and-nc-block-restart.md 7.1"));
  EXPECT_EQ(ByName(table, "P00C.REPOS")->scope, Scope::kProcess);
  EXPECT_EQ(ByName(table, "A04S.HOMED")->instance, 4);
  EXPECT_EQ(ByName(table, "A04S.HOMED")->instance_name, "C");
}

TEST(SignalTable, AliasesAreInstantiated) {
  const auto table = BuildSignalTable(LatheLayout());
  EXPECT_THAT(ByName(table, "P00S.STOP")->aliases, ::testing::Contains("P00SSTOP"));
  EXPECT_THAT(ByName(table, "A02C.JGPOS")->aliases, ::testing::Contains("A02CJGPOS"));
  EXPECT_THAT(ByName(table, "QMFB1A00.Q_MTstKol")->aliases, ::testing::Contains("Q_MTstKOl"));
}

TEST(SignalTable, SpindleSignalsOnlyOnSpindleCapableAxes) {
  const auto table = BuildSignalTable(LatheLayout());
  EXPECT_EQ(ByName(table, "A01C.M3"), nullptr);
  EXPECT_EQ(ByName(table, "A01S.N_NCMD"), nullptr);
  EXPECT_EQ(ByName(table, "A01.ROTMOD"), nullptr);
  EXPECT_EQ(ByName(table, "A04.ROTMOD"), nullptr);  // the C servo: the spindle's number is used
  EXPECT_NE(ByName(table, "A03C.M3"), nullptr);
  EXPECT_NE(ByName(table, "A03C.SOVR"), nullptr);
  // AXD idents: on the spindle and on the rotary axis of the changeover, not on X.
  EXPECT_EQ(ByName(table, "A01.AXD.65012"), nullptr);
  EXPECT_NE(ByName(table, "A03.AXD.65012"), nullptr);
  EXPECT_NE(ByName(table, "A04.AXD.65012"), nullptr);
  // Every axis gets the common axis signals.
  EXPECT_NE(ByName(table, "A04C.JGPOS"), nullptr);
}

TEST(SignalTable, VmtNamesAreMarked) {
  const auto table = BuildSignalTable(LatheLayout());
  for (const char* name :
       {"P00C.AUTO", "P00C.MANU", "P00C.MDI", "P00C.SBL", "P00C.OPSTP", "P00C.START", "P00C.STOP",
        "P00C.RESET", "P00C.ENABL", "P00C.FOVR", "P00S.AUTO", "P00S.MANU", "P00S.MDI",
        "P00S.ERROR", "P00S.ERRNR", "A03C.SOVR", "P00.backward_motion_w",
        "P00.bahn_state.backward_motion_r"}) {
    const Signal* s = ByName(table, name);
    ASSERT_NE(s, nullptr) << name;
    EXPECT_EQ(s->source.rfind("vmt", 0), 0u) << name << ": " << s->source;
  }
  // And nothing named by a manual says vmt.
  for (const char* name : {"P00C.REPOS", "P00S.STOP", "A01S.MVPOS", "A03S.INPOS"}) {
    EXPECT_NE(ByName(table, name)->source.rfind("vmt", 0), 0u) << name;
  }
}

TEST(SignalTable, TableOrderIsProcessesAxesGlobalIo) {
  const auto table = BuildSignalTable(LatheLayout());
  ASSERT_FALSE(table.empty());
  EXPECT_EQ(table.front().name, "P00C.REPOS");
  EXPECT_EQ(table.back().name, "ISPMODE");
  int last_rank = 0;
  for (const Signal& s : table) {
    const int rank = s.scope == Scope::kProcess  ? 0
                     : s.scope == Scope::kGlobal ? 2
                     : s.scope == Scope::kIo     ? 3
                                                 : 1;
    EXPECT_GE(rank, last_rank) << s.name;
    last_rank = rank;
  }
}

TEST(SignalTable, SameLayoutSameTable) {
  const auto a = BuildSignalTable(LatheLayout());
  const auto b = BuildSignalTable(LatheLayout());
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].name, b[i].name);
    EXPECT_EQ(a[i].modbus.address, b[i].modbus.address);
  }
}

TEST(SignalTable, EmptyLayoutHasOnlyGlobalSignals) {
  const auto table = BuildSignalTable(GatewayLayout{});
  ASSERT_FALSE(table.empty());
  for (const Signal& s : table) EXPECT_EQ(s.scope, Scope::kGlobal) << s.name;
}

std::string LayoutError(const GatewayLayout& layout) {
  try {
    BuildSignalTable(layout);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(SignalTable, RejectsBadLayouts) {
  GatewayLayout layout = LatheLayout();
  layout.axes[1].number = 0;
  EXPECT_THAT(LayoutError(layout),
              HasSubstr("GatewayLayout.axes[].number[1]: 0 is out of range 1..32"));

  layout = LatheLayout();
  layout.axes[2].number = 33;
  EXPECT_THAT(LayoutError(layout), HasSubstr("33 is out of range 1..32"));

  layout = LatheLayout();
  layout.axes[3].number = 1;
  EXPECT_THAT(LayoutError(layout), HasSubstr("axes[].number[3]: 1 is repeated"));

  layout = LatheLayout();
  layout.axes[3].name = "X";
  EXPECT_THAT(LayoutError(layout), HasSubstr("axes[3].name: 'X' is repeated"));

  layout = LatheLayout();
  layout.processes = {0, 100};
  EXPECT_THAT(LayoutError(layout), HasSubstr("processes[1]: 100 is out of range 0..99"));

  layout = LatheLayout();
  layout.processes = {1, 1};
  EXPECT_THAT(LayoutError(layout), HasSubstr("processes[1]: 1 is repeated"));

  layout = LatheLayout();
  layout.io.push_back({"P00C.REPOS", true, "clash"});
  EXPECT_THAT(LayoutError(layout),
              HasSubstr("GatewayLayout.io: signal name 'P00C.REPOS' occurs twice"));

  layout = LatheLayout();
  layout.io.push_back({"BAD NAME", false, ""});
  EXPECT_THAT(LayoutError(layout), HasSubstr("io[4].name: 'BAD NAME'"));

  layout = LatheLayout();
  layout.q_functions = {9999};
  EXPECT_THAT(LayoutError(layout), HasSubstr("Q9999 is already in the manuals' table"));

  layout = LatheLayout();
  layout.events = {29};
  EXPECT_THAT(LayoutError(layout), HasSubstr("event 29 is already in the manuals' table"));

  layout = LatheLayout();
  layout.events = {1000};
  EXPECT_THAT(LayoutError(layout), HasSubstr("events[0]: 1000 is out of range 0..999"));
}

TEST(SignalTable, InstanceName) {
  EXPECT_EQ(InstanceName("PxxC.REPOS", 0), "P00C.REPOS");
  EXPECT_EQ(InstanceName("AxxC.JGPOS", 12), "A12C.JGPOS");
  EXPECT_EQ(InstanceName("AxxCJGPOS", 3), "A03CJGPOS");
  EXPECT_EQ(InstanceName("QMFB1A00.ENABLE", 5), "QMFB1A00.ENABLE");
  EXPECT_THROW(InstanceName("PxxC.REPOS", 100), std::out_of_range);
  EXPECT_THROW(InstanceName("AxxC.JGPOS", -1), std::out_of_range);
}

// The catalog itself: placeholders match scopes, nothing is listed twice, every value table
// belongs to a family.
TEST(SignalCatalog, PatternsMatchScopes) {
  std::set<std::string_view> patterns;
  for (const SignalFamily& f : SignalFamilies()) {
    EXPECT_TRUE(patterns.insert(f.pattern).second) << f.pattern;
    EXPECT_FALSE(f.meaning.empty()) << f.pattern;
    EXPECT_FALSE(f.source.empty()) << f.pattern;
    const std::string_view prefix = f.pattern.substr(0, 3);
    switch (f.scope) {
      case Scope::kProcess:
        EXPECT_EQ(prefix, "Pxx") << f.pattern;
        break;
      case Scope::kAxis:
      case Scope::kSpindle:
      case Scope::kChangeover:
        EXPECT_EQ(prefix, "Axx") << f.pattern;
        break;
      case Scope::kGlobal:
        EXPECT_NE(prefix, "Pxx") << f.pattern;
        EXPECT_NE(prefix, "Axx") << f.pattern;
        break;
      case Scope::kIo:
        ADD_FAILURE() << f.pattern << ": I/O comes from the layout";
        break;
    }
    // A preset must fit the type (BOOL signals start FALSE).
    if (f.type == SignalType::kBool) {
      EXPECT_EQ(f.preset, 0) << f.pattern;
    }
    if (IsInteger(f.type)) {
      EXPECT_GE(f.preset, MinValue(f.type)) << f.pattern;
      EXPECT_LE(f.preset, MaxValue(f.type)) << f.pattern;
    }
  }
}

TEST(SignalTypes, ValueErrorNamesWhatDoesNotFit) {
  EXPECT_EQ(ValueError(SignalType::kInt, -32768), "");
  EXPECT_EQ(ValueError(SignalType::kInt, 32767), "");
  EXPECT_EQ(ValueError(SignalType::kInt, 32768), "32768 is outside INT's range -32768..32767");
  EXPECT_EQ(ValueError(SignalType::kUint, -1), "-1 is outside UINT's range 0..65535");
  EXPECT_EQ(ValueError(SignalType::kUdint, 4294967295.0), "");
  EXPECT_EQ(ValueError(SignalType::kDint, 2.5), "2.5 is not an integer: DINT");
  EXPECT_EQ(ValueError(SignalType::kBool, 1), "");
  EXPECT_EQ(ValueError(SignalType::kBool, 2), "BOOL holds 0 or 1 (true or false)");
  EXPECT_EQ(ValueError(SignalType::kLreal, 1e300), "");
  EXPECT_EQ(ValueError(SignalType::kReal, 1e300), "outside REAL's range");
  EXPECT_EQ(ValueError(SignalType::kLreal, std::nan("")), "a signal value must be a finite number");
  EXPECT_NE(ValueError(SignalType::kString, 0), "");
}

TEST(SignalCatalog, ValuesBelongToFamiliesAndAreUnique) {
  std::set<std::string_view> patterns;
  for (const SignalFamily& f : SignalFamilies()) patterns.insert(f.pattern);
  std::set<std::pair<std::string_view, int64_t>> seen;
  for (const ValueName& v : SignalValues()) {
    EXPECT_TRUE(patterns.count(v.pattern)) << v.pattern;
    EXPECT_TRUE(seen.insert({v.pattern, v.value}).second) << v.pattern << " " << v.value;
    if (v.bit_mask) {
      EXPECT_TRUE(std::has_single_bit(static_cast<uint64_t>(v.value))) << v.name;
    }
  }
}

TEST(SignalCatalog, BlockSearchStatesAndStopConditions) {
  std::map<std::string_view, int64_t> values;
  for (const ValueName& v : SignalValues()) {
    if (!v.name.empty()) values[v.name] = v.value;
  }
  EXPECT_EQ(values["HLI_BS_INACTIVE"], 0);
  EXPECT_EQ(values["HLI_BS_WAIT_FOR_PLC_ON"], 1);
  EXPECT_EQ(values["HLI_BS_ACTIVE"], 2);
  EXPECT_EQ(values["HLI_BS_WAIT_FOR_PLC_OFF"], 3);
  EXPECT_EQ(values["HLI_BS_WAIT_RETURN_TO_CONTOUR"], 4);
  EXPECT_EQ(values["HLI_BS_RETURNING_TO_CONTOUR"], 5);
  EXPECT_EQ(values["HLI_BS_WAIT_FOR_CONTINUE_CONTOUR"], 6);
  EXPECT_EQ(values["HLI_SC_FEEDHOLD"], 0x0001);
  EXPECT_EQ(values["HLI_SC_SINGLE_BLOCK"], 0x0004);
  EXPECT_EQ(values["HLI_SC_PLC_ACKNOWLEDGE"], 0x0020);
  EXPECT_EQ(values["HLI_SC_BREAKPOINT_STOP"], 0x00400000);
  EXPECT_EQ(values["HLI_SC_DEC_SYN_CHAN_EMPTY"], 0x10000000);
}

TEST(SignalCatalog, FehlerNrValues) {
  std::set<int64_t> numbers;
  for (const ValueName& v : SignalValues()) {
    if (v.pattern == "QMFB1A00.FEHLER_NR") numbers.insert(v.value);
  }
  const std::set<int64_t> expected = {1,  2,  3,  4,  5,  6,  7,  10, 11, 12, 13,
                                      20, 21, 22, 23, 24, 25, 26, 27, 28, 29, 30,
                                      31, 32, 33, 34, 35, 36, 37, 38, 40};
  EXPECT_EQ(numbers, expected);
}

}  // namespace
}  // namespace vmt::control::gateway
