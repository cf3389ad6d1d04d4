// Block search's skipped blocks on their own, handed a narrow fake of the channel: the blocks
// from an interpreter, offsets that take effect at once, the path memory, the turret and the
// errors recorded. The search follows the path on paper from where the program has the axes,
// stops at the continue block, sends technology to the PLC and waits for its acknowledgement,
// keeps the main spindle as the program left it, and refuses what it cannot carry to the
// continue position (further spindles, G77, a breakpoint it passes); the program's end without
// the continue block is the manual's P-ERR-20704 warning.

#include "control/channel/block_search_simulation.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "control/channel/channel_messages.hpp"
#include "control/nc/parser.hpp"

namespace vmt::control::channel {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

ChannelConfig LatheConfig() {
  ChannelConfig c;
  axes::AxisParameters x;
  x.name = "X";
  x.drive = 0;
  x.rapid_per_s = 200;
  x.acceleration = 2000;
  x.travel_min = -300;
  x.travel_max = 300;
  axes::AxisParameters z = x;
  z.name = "Z";
  z.drive = 1;
  c.axes = {x, z};
  c.spindle_drive = 2;
  c.aux_handshake = true;
  return c;
}

struct Error {
  int32_t block;
  std::string text;
  int number;
};

/// The channel as the skipped blocks see it: X at 50 and Z at 5, no offsets.
struct Rig {
  explicit Rig(const std::string& text, uint32_t block_number)
      : parsed(nc::ParseProgram(text, "p.mtc", nc::Dialect::kMtc200)) {
    EXPECT_TRUE(parsed.ok()) << nc::Format(parsed.errors[0], parsed.program.files);
    nc::InterpreterConfig ic;
    ic.axes = {"X", "Z"};
    interpreter.emplace(std::vector<const nc::Program*>{&parsed.program}, ic);
    interpreter->SetPosition(commanded);
    interpreter->SetEveryBlock(true);
    data.started.type = BlockSearchType::kBlockNumber;
    data.started.block_number = block_number;
    data.state = BlockSearchState::kActive;
    frames.translation = {0, 0};
    frames.shift = {0, 0};
    frames.homed = {true, true};
    search.Begin(data.started, commanded, DriveSetpoint{DriveMode::kVelocity, 0, 0});
  }

  SearchLink Link() {
    return SearchLink{
        .config = config,
        .data = data,
        .interpreter = *interpreter,
        .state = state,
        .frames = frames,
        .events = events,
        .aux = aux,
        .headstock = headstock,
        .cax = cax,
        .backward = backward,
        .commanded = commanded,
        .program_of = [this](uint32_t) -> const nc::Program& { return parsed.program; },
        .fail = [this](const nc::Program&, int32_t b, const std::string& text,
                       int number) { Fail(b, text, number); },
        .fail_message = [this](const std::string& text, int number) { Fail(-1, text, number); },
        .take_offsets = [this](const nc::ModalState&, const nc::Program&,
                               int32_t) { return ++offsets_taken > 0; },
        .index_tool_storage =
            [this](const nc::PreparedBlock& b, const nc::Program&) {
              return tools.push_back(b.modal.tool), true;
            },
        .simulate_measuring = [](const nc::PreparedBlock&, std::vector<double>&) { return true; },
        .cax_instruction = [](const nc::Program&, const nc::Statement&, nc::PreparedBlock&,
                              double) -> std::optional<bool> { return std::nullopt; },
        .track_c = [](nc::PreparedBlock&, const std::vector<double>&, double,
                      std::optional<double>&) { return true; },
    };
  }

  /// The interpreter's next block; at the text's end a block that says so.
  bool NextBlock() {
    if (interpreter->Next(block)) return true;
    block = nc::PreparedBlock{};
    block.end = true;
    block.block = -1;
    return true;
  }

  void Fail(int32_t b, const std::string& text, int number) {
    errors.push_back({b, text, number});
    state = ChannelState::kError;
  }

  /// One NC cycle of the search; the PLC acknowledges what it was sent before the next.
  bool Cycle() {
    const bool ok = search.SimulateBlocks(Link(), block, [this] { return NextBlock(); });
    for (const nc::AuxFunction& f : aux.functions)
      sent.push_back(std::string(1, f.letter) + std::to_string(static_cast<int>(f.value)));
    return ok;
  }

  int32_t Number() const { return parsed.program.blocks[static_cast<size_t>(block.block)].number; }

  nc::ParseResult parsed;
  ChannelConfig config = LatheConfig();
  std::optional<nc::Interpreter> interpreter;
  BlockSearchData data;
  ChannelState state = ChannelState::kRunning;
  ProgramFrames frames;
  ProgramEvents events;
  AuxOutput aux;
  HeadstockControl headstock{std::nullopt};
  CaxTrackState cax;
  BackwardTravel backward;
  std::vector<double> commanded{50, 5};
  nc::PreparedBlock block;
  BlockSearchSimulation search;

  int offsets_taken = 0;
  std::vector<int> tools;
  std::vector<std::string> sent;
  std::vector<Error> errors;
};

constexpr const char* kTurning =
    "N10 G01 X40 Z0 F500\n"
    "N20 X30 Z-20\n"
    "N30 X20 Z-40\n"
    "N40 X10\n"
    "N50 M30\n";

TEST(BlockSearchSimulation, FollowsThePathOnPaperUpToTheContinueBlock) {
  Rig r(kTurning, 30);
  ASSERT_TRUE(r.Cycle());
  EXPECT_TRUE(r.errors.empty());
  EXPECT_EQ(r.data.state, BlockSearchState::kWaitForPlcOff);
  EXPECT_EQ(r.Number(), 30);
  const BlockSearchRun& s = r.search.run();
  EXPECT_EQ(s.blocks, 3);
  // No per mille: machining goes on at the continue block's start, where N20 left the axes.
  EXPECT_THAT(s.restart, ElementsAre(30, -20));
  EXPECT_THAT(s.position, ElementsAre(30, -20));
  EXPECT_FALSE(s.ends_program);
  // The decoded path up to the continue block, for backward travel from there.
  EXPECT_FALSE(r.backward.empty());
  EXPECT_TRUE(r.backward.LastStepIs(s.restart_motion));
  // The distance from program start counts the skipped paths (X, Z are main axes).
  EXPECT_NEAR(r.data.program_distance.distance(), std::hypot(10, 5) + std::hypot(10, 20), 1e-9);
  EXPECT_EQ(r.offsets_taken, 3);
  EXPECT_THAT(r.commanded, ElementsAre(50, 5)) << "the search moves no axis";
}

TEST(BlockSearchSimulation, TechnologyWaitsForThePlcAndTheSpindleKeepsTheProgramsSpeed) {
  Rig r(
      "N10 G01 X40 Z0 F500 S1000 M03\n"
      "N20 X30 M08\n"
      "N30 X20 S500\n"
      "N40 X10\n"
      "N50 M05\n"
      "N60 M30\n",
      40);
  ASSERT_TRUE(r.Cycle());
  // M03 goes to the PLC as in a run: the search stops at its block until acknowledged.
  EXPECT_EQ(r.data.state, BlockSearchState::kActive);
  EXPECT_EQ(r.Number(), 10);
  EXPECT_THAT(r.sent, ElementsAre("M3"));
  EXPECT_EQ(r.aux.strobe, 1u);
  r.aux.functions.clear();
  ASSERT_TRUE(r.Cycle());
  EXPECT_EQ(r.Number(), 20);
  EXPECT_THAT(r.sent, ElementsAre("M3", "M8"));
  r.aux.functions.clear();
  ASSERT_TRUE(r.Cycle());
  // N30's S alone changes the running spindle's speed; the search stops at N40, so N50's M05
  // is the run's.
  EXPECT_EQ(r.data.state, BlockSearchState::kWaitForPlcOff);
  EXPECT_EQ(r.Number(), 40);
  EXPECT_EQ(r.search.run().spindle.mode, DriveMode::kVelocity);
  EXPECT_NEAR(r.search.run().spindle.value, 500 * 6, 1e-9);  // deg/s
  EXPECT_THAT(r.sent, ElementsAre("M3", "M8"));
  EXPECT_TRUE(r.errors.empty());
}

TEST(BlockSearchSimulation, TheProgramEndWithoutTheContinueBlockEndsItInSearchMode) {
  Rig r(kTurning, 99);
  ASSERT_TRUE(r.Cycle());
  EXPECT_TRUE(r.search.run().ends_program);
  EXPECT_EQ(r.data.state, BlockSearchState::kWaitForPlcOff);
  ASSERT_EQ(r.data.warnings.size(), 1u);
  EXPECT_THAT(r.data.warnings[0], HasSubstr("P-ERR-20704"));
  EXPECT_THAT(r.search.run().position, ElementsAre(10, -40));
}

TEST(BlockSearchSimulation, RefusesWhatItCannotCarryToTheContinuePosition) {
  // A further spindle's words would be lost at the continue position.
  Rig further("N10 G01 X40 Z0 F500\nN20 S2=800 M2=3\nN30 X20\nN40 M30\n", 30);
  EXPECT_FALSE(further.Cycle());
  ASSERT_EQ(further.errors.size(), 1u);
  EXPECT_EQ(further.errors[0].number, kMsgBlockSearch);
  EXPECT_THAT(further.errors[0].text, HasSubstr("further spindles"));

  // A breakpoint the search passes (3.5: it must lie after the continue position).
  Rig breakpoint(kTurning, 30);
  breakpoint.data.program_distance.SetBreakpoint(5);
  EXPECT_FALSE(breakpoint.Cycle());
  ASSERT_EQ(breakpoint.errors.size(), 1u);
  EXPECT_THAT(breakpoint.errors[0].text, HasSubstr("mc_cmd_bs_breakpoint_position_w"));
  EXPECT_EQ(breakpoint.search.run().blocks, 1);
}

TEST(BlockSearchSimulation, StopsAfterItsBlocksPerCycleForAProgramThatLoopsForEver) {
  Rig r(
      "N10 G01 X40 Z0 F500\n"
      "N20 .LOOP\n"
      "N30 X30\n"
      "N40 X40 BRA .LOOP\n",
      99);
  ASSERT_TRUE(r.Cycle());
  EXPECT_EQ(r.data.state, BlockSearchState::kActive);
  EXPECT_EQ(r.search.run().blocks, BlockSearchSimulation::kBlocksPerCycle);
  ASSERT_TRUE(r.Cycle());
  EXPECT_EQ(r.search.run().blocks, 2 * BlockSearchSimulation::kBlocksPerCycle);
}

}  // namespace
}  // namespace vmt::control::channel
