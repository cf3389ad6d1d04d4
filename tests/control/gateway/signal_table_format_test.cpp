#include "control/gateway/signal_table_format.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "control/gateway/nc_status_block.hpp"
#include "tests/control/gateway/lathe_layout.hpp"

namespace vmt::control::gateway {
namespace {

using testing::LatheLayout;

// RFC 4180 reader, independent of FormatCsv's writer.
std::vector<std::vector<std::string>> ParseCsv(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> row;
  std::string field;
  bool quoted = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
        field += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        field += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      row.push_back(field);
      field.clear();
    } else if (c == '\n') {
      row.push_back(field);
      field.clear();
      rows.push_back(row);
      row.clear();
    } else {
      field += c;
    }
  }
  EXPECT_FALSE(quoted) << "unterminated quote";
  EXPECT_TRUE(field.empty() && row.empty()) << "last line without newline";
  return rows;
}

TEST(SignalTableFormat, CsvRoundTrip) {
  const auto table = BuildSignalTable(LatheLayout());
  const auto rows = ParseCsv(FormatCsv(table));
  const std::vector<NcStatusField> status = NcStatusLayoutOf(table).Fields();
  ASSERT_EQ(rows.size(), table.size() + 3 + status.size());
  EXPECT_EQ(rows[0],
            (std::vector<std::string>{"name", "type", "direction", "area", "address (0-based)",
                                      "count", "meaning", "source", "vmt", "written_by"}));
  for (size_t i = 0; i < table.size(); ++i) {
    const auto& r = rows[i + 1];
    const Signal& s = table[i];
    ASSERT_EQ(r.size(), 10u) << s.name;
    EXPECT_EQ(r[0], s.name);
    EXPECT_EQ(r[1], ToString(s.type));
    EXPECT_EQ(r[2], ToString(s.direction));
    EXPECT_EQ(r[3], ToString(s.modbus.area));
    EXPECT_EQ(r[4], std::to_string(s.modbus.address));
    EXPECT_EQ(r[5], std::to_string(s.modbus.count));
    EXPECT_EQ(r[6], s.meaning);
    EXPECT_EQ(r[7], s.source);
    EXPECT_EQ(r[8], VmtColumn(s));
    EXPECT_EQ(r[9], WrittenBy(s));
  }
  // vmt serve's registers that are not signals: the lockstep cycle, the AXD_WR block.
  const auto& cycle = rows[table.size() + 1];
  ASSERT_EQ(cycle.size(), 10u);
  EXPECT_EQ(cycle[0], "(lockstep cycle)");
  EXPECT_EQ(cycle[3], "holding_register");
  EXPECT_EQ(cycle[4], std::to_string(LockstepCycleRegister(table)));
  const auto& axd = rows[table.size() + 2];
  EXPECT_EQ(axd[0], "(AXD_WR block)");
  EXPECT_EQ(axd[4], std::to_string(AxdWrRegister(table)));
  EXPECT_EQ(axd[5], "6");
  // Then the NC status block's registers, read only, with their units.
  for (size_t i = 0; i < status.size(); ++i) {
    const auto& r = rows[table.size() + 3 + i];
    ASSERT_EQ(r.size(), 10u) << status[i].name;
    EXPECT_EQ(r[0], status[i].name);
    EXPECT_EQ(r[2], "NC->PLC");
    EXPECT_EQ(r[3], "input_register");
    EXPECT_EQ(r[4], std::to_string(status[i].address));
    EXPECT_EQ(r[9], "vmt (the NC)");
    if (!status[i].unit.empty()) {
      EXPECT_TRUE(r[6].ends_with(" [" + status[i].unit + "]")) << r[6];
    }
  }
  EXPECT_EQ(rows[table.size() + 3][0], "NC.VERSION");
  EXPECT_EQ(rows[table.size() + 3][4], "1000");
}

TEST(SignalTableFormat, WrittenBySaysWhoSetsEachSignal) {
  const auto table = BuildSignalTable(LatheLayout());
  auto who = [&](const char* name) {
    for (const Signal& s : table)
      if (s.name == name) return WrittenBy(s);
    return std::string("(missing)");
  };
  EXPECT_EQ(who("P00S.RUN"), "vmt (the NC)");
  EXPECT_EQ(who("P00C.START"), "the PLC");
}

TEST(SignalTableFormat, CsvQuotesCommasQuotesAndLineBreaks) {
  auto table = BuildSignalTable(LatheLayout());
  table.resize(1);
  table[0].meaning = "say \"hi\", then\nleave";
  const std::string csv = FormatCsv(table);
  EXPECT_NE(csv.find("\"say \"\"hi\"\", then\nleave\""), std::string::npos) << csv;
  const auto rows = ParseCsv(csv);
  // The header, the signal, vmt serve's two register blocks, the NC status block (no axes).
  ASSERT_EQ(rows.size(), 4u + NcStatusLayoutOf(table).Fields().size());
  EXPECT_EQ(rows[1][6], table[0].meaning);
  // The source of P00C.REPOS has "; " but no comma: left unquoted.
  EXPECT_EQ(rows[1][7], table[0].source);
}

TEST(SignalTableFormat, JsonParsesAndListsEverySignal) {
  const auto table = BuildSignalTable(LatheLayout());
  const auto doc = nlohmann::json::parse(FormatJson(table));
  EXPECT_EQ(doc["format"], "vmt-gateway-signals");
  EXPECT_EQ(doc["version"], 1);
  const auto& signals = doc["signals"];
  ASSERT_EQ(signals.size(), table.size());
  // The NC status block apart from the signals.
  const NcStatusLayout layout = NcStatusLayoutOf(table);
  EXPECT_EQ(doc["modbus"]["nc_status_register"], layout.address);
  ASSERT_EQ(doc["nc_status"].size(), layout.Fields().size());
  for (const auto& j : doc["nc_status"]) {
    EXPECT_EQ(j["modbus"]["area"], "input_register");
    EXPECT_EQ(j["written_by"], "vmt (the NC)");
    if (j["name"] == "A01.NC_POS") {
      EXPECT_EQ(j["unit"], "0.0001 mm");
      EXPECT_EQ(j["type"], "DINT");
      EXPECT_EQ(j["modbus"]["address"], layout.address + 32);
    }
  }
  for (size_t i = 0; i < table.size(); ++i) {
    const auto& j = signals[i];
    EXPECT_EQ(j["name"], table[i].name);
    EXPECT_EQ(j["type"], ToString(table[i].type));
    EXPECT_EQ(j["direction"], ToString(table[i].direction));
    EXPECT_EQ(j["modbus"]["area"], ToString(table[i].modbus.area));
    EXPECT_EQ(j["modbus"]["address"], table[i].modbus.address);
    EXPECT_EQ(j["modbus"]["count"], table[i].modbus.count);
    EXPECT_EQ(j["meaning"], table[i].meaning);
    EXPECT_EQ(j["source"], table[i].source);
    EXPECT_EQ(j["vmt"], table[i].not_evaluated.empty() ? "evaluated" : "not evaluated");
  }
  // Extra fields where they say something.
  for (const auto& j : signals) {
    if (j["name"] == "A04S.HOMED") {
      EXPECT_EQ(j["axis_name"], "C");
    }
    if (j["name"] == "QMFB1A00.Q_Nummer") {
      EXPECT_EQ(j["preset"], 9992);
    }
    if (j["name"] == "P00S.STOP") {
      EXPECT_EQ(j["aliases"][0], "P00SSTOP");
    }
    if (j["name"] == "P00.mc_cmd_bs_deviation_max_w") {
      EXPECT_EQ(j["unit"], "0.1 um");
    }
  }
}

TEST(SignalTableFormat, JsonValuesFollowTheTable) {
  const auto with_process = nlohmann::json::parse(FormatJson(BuildSignalTable(LatheLayout())));
  bool found_state = false;
  for (const auto& v : with_process["values"]) {
    if (v["name"] == "HLI_BS_WAIT_FOR_PLC_OFF") {
      found_state = true;
      EXPECT_EQ(v["value"], 3);
      EXPECT_EQ(v["signal_pattern"], "Pxx.bahn_state.block_search_state_r");
    }
  }
  EXPECT_TRUE(found_state);
  EXPECT_FALSE(with_process["unrepresented"].empty());

  // Without processes the process families' values are left out; the FB's stay.
  const auto global_only = nlohmann::json::parse(FormatJson(BuildSignalTable(GatewayLayout{})));
  for (const auto& v : global_only["values"]) {
    EXPECT_EQ(v["signal_pattern"], "QMFB1A00.FEHLER_NR") << v.dump();
  }
  EXPECT_FALSE(global_only["values"].empty());
}

}  // namespace
}  // namespace vmt::control::gateway
