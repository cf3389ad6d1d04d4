// What block search (TwinCAT block search manual, "Satzvorlauf") needs from the interpreter:
// the block counter (3.2, 9.2.1), every block handed out, #BLOCKSEARCH LOCKED / RELEASED (6),
// #DISTANCE PROG START (4.1.2) and the entry point by file offset (3.6).

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <tuple>

#include "control/nc/interpreter.hpp"
#include "control/nc/parser.hpp"

namespace vmt::control::nc {
namespace {

using ::testing::ElementsAre;
using ::testing::ElementsAreArray;
using ::testing::HasSubstr;
using ::testing::Pair;

InterpreterConfig Axes() {
  InterpreterConfig c;
  c.axes = {"X", "Y", "Z", "C"};
  return c;
}

// A seed program as the manual prints it: the file's `;` header (up to its line that is only
// ";") stripped, so that the `%` line is line 1 as in the manual's counts.
std::string Seed(const std::string& name, int* header_lines = nullptr) {
  std::ifstream in(std::filesystem::path(VMT_SOURCE_DIR) / "tests/control/nc/seed_programs" / name);
  std::stringstream text;
  text << in.rdbuf();
  const std::string all = text.str();
  const size_t end = all.find("\n;\n");
  EXPECT_NE(end, std::string::npos) << name;
  if (header_lines)
    *header_lines = static_cast<int>(std::count(all.begin(), all.begin() + end, '\n')) + 2;
  return all.substr(end + 3);
}

struct Run {
  std::vector<ParseResult> parsed;
  std::unique_ptr<Interpreter> interpreter;
  std::vector<PreparedBlock> blocks;
  std::string error;

  const Program& ProgramOf(const PreparedBlock& b) const { return parsed[b.program].program; }
  uint32_t Line(const PreparedBlock& b) const {
    return ProgramOf(b).blocks[static_cast<size_t>(b.block)].pos.line;
  }
  int32_t Number(const PreparedBlock& b) const {
    return ProgramOf(b).blocks[static_cast<size_t>(b.block)].number;
  }
  /// (line, block count) of every block handed out, the end block without a line left out.
  std::vector<std::pair<uint32_t, uint32_t>> Counts() const {
    std::vector<std::pair<uint32_t, uint32_t>> counts;
    for (const PreparedBlock& b : blocks)
      if (b.block >= 0) counts.emplace_back(Line(b), b.block_count);
    return counts;
  }
};

// Parses the programs (first = main) and runs the main one to its end or first error.
std::unique_ptr<Run> Execute(std::vector<std::pair<std::string, std::string>> files,
                             bool every_block, std::optional<uint32_t> start_at = {},
                             InterpreterConfig config = Axes()) {
  auto run = std::make_unique<Run>();
  std::vector<const Program*> programs;
  for (const auto& [name, text] : files) {
    run->parsed.push_back(ParseProgram(text, name, DetectDialect(text, name)));
    EXPECT_TRUE(run->parsed.back().ok())
        << name << ": " << Format(run->parsed.back().errors[0], run->parsed.back().program.files);
  }
  for (const ParseResult& r : run->parsed) programs.push_back(&r.program);
  run->interpreter = std::make_unique<Interpreter>(programs, config);
  run->interpreter->SetEveryBlock(every_block);
  if (start_at) {
    EXPECT_TRUE(run->interpreter->StartAt(*start_at));
  }
  PreparedBlock b;
  while (run->interpreter->Next(b)) {
    run->blocks.push_back(b);
    if (b.end) break;
  }
  if (run->interpreter->error())
    run->error = Format(*run->interpreter->error(), {run->interpreter->ErrorFile()});
  return run;
}

// ---- Block counter --------------------------------------------------------------------------

TEST(InterpreterBlockCountTest, ManualExampleTypeThreeEveryLine) {
  // 9.2.1: %=1, N00=2, P1=3, N80=4, N095=5, blank=6, $FOR=7,9,11,13,15, N100=8,10,12,14,16,
  // $ENDFOR=17, blank=18, N120=19, N130=20. The $ENDFOR that loops back is not counted; the
  // $FOR line it re-reads is.
  const auto r = Execute({{"t_sv_count.isg", Seed("blocksearch_type3_block_counter.isg")}}, true);
  ASSERT_EQ(r->error, "");
  EXPECT_THAT(r->Counts(), ElementsAre(Pair(1, 1), Pair(2, 2), Pair(3, 3), Pair(4, 4), Pair(5, 5),
                                       Pair(7, 7), Pair(8, 8), Pair(7, 9), Pair(8, 10), Pair(7, 11),
                                       Pair(8, 12), Pair(7, 13), Pair(8, 14), Pair(7, 15),
                                       Pair(8, 16), Pair(9, 17), Pair(11, 19), Pair(12, 20)));
  EXPECT_TRUE(r->blocks.back().end);
  EXPECT_EQ(r->interpreter->block_count(), 20u);
  // The program still does what it did: five passes of X-2 from X12.
  EXPECT_EQ(r->blocks.back().target[0], 2);
  EXPECT_EQ(r->interpreter->Variable("P1"), 6);
}

TEST(InterpreterBlockCountTest, ManualExampleTypeThreeBlocksWithEffect) {
  // Without SetEveryBlock the moves carry the same counts; the header of the seed file (before
  // its % line) is read as well and shifts every count by its lines.
  int header = 0;
  const std::string program = Seed("blocksearch_type3_block_counter.isg", &header);
  const auto r = Execute({{"t_sv_count.isg", program}}, false);
  ASSERT_EQ(r->error, "");
  EXPECT_THAT(r->Counts(),
              ElementsAre(Pair(2, 2), Pair(4, 4), Pair(5, 5), Pair(8, 8), Pair(8, 10), Pair(8, 12),
                          Pair(8, 14), Pair(8, 16), Pair(11, 19), Pair(12, 20)));
  std::ifstream in(std::filesystem::path(VMT_SOURCE_DIR) /
                   "tests/control/nc/seed_programs/blocksearch_type3_block_counter.isg");
  std::stringstream whole;
  whole << in.rdbuf();
  const auto h = Execute({{"t_sv_count.isg", whole.str()}}, false);
  ASSERT_EQ(h->blocks.size(), r->blocks.size());
  for (size_t i = 0; i < r->blocks.size(); ++i)
    EXPECT_EQ(h->blocks[i].block_count, r->blocks[i].block_count + static_cast<uint32_t>(header));
}

TEST(InterpreterBlockCountTest, ManualFigureThreeWhileLoop) {
  // 3.2, figure 3: $WHILE=4,10, body 5..8 and 11..14, $ENDWHILE=9,15, N100=16. The $WHILE that
  // fails after the loop-back is not counted: N100 follows its $ENDWHILE.
  const auto r = Execute({{"while.isg",
                           "%while\n"
                           "N10 G00 G90 X0 Y0\n"
                           "N20 P1 = 0\n"
                           "N30 $WHILE P1 < 2\n"
                           "N40 P1 = P1 + 1\n"
                           "N60 G91 X10\n"
                           "N70 Y10\n"
                           "N80 G90\n"
                           "N90 $ENDWHILE\n"
                           "N100 X0\n"
                           "N110 Y0\n"
                           "N120 M05\n"
                           "N130 M30\n"}},
                         true);
  ASSERT_EQ(r->error, "");
  EXPECT_THAT(r->Counts(),
              ElementsAre(Pair(1, 1), Pair(2, 2), Pair(3, 3), Pair(4, 4), Pair(5, 5), Pair(6, 6),
                          Pair(7, 7), Pair(8, 8), Pair(9, 9), Pair(4, 10), Pair(5, 11), Pair(6, 12),
                          Pair(7, 13), Pair(8, 14), Pair(9, 15), Pair(10, 16), Pair(11, 17),
                          Pair(12, 18), Pair(13, 19)));
}

TEST(InterpreterBlockCountTest, WhileThatNeverRunsJumpsPastItsEnd) {
  // A $WHILE that fails at once is read (counted); its jump past $ENDWHILE counts the target.
  const auto r = Execute({{"w.isg",
                           "%w\n"
                           "N10 $WHILE 0\n"
                           "N20 X1\n"
                           "N30 $ENDWHILE\n"
                           "\n"
                           "N40 X2\n"
                           "N50 M30\n"}},
                         true);
  ASSERT_EQ(r->error, "");
  EXPECT_THAT(r->Counts(), ElementsAre(Pair(1, 1), Pair(2, 2), Pair(6, 3), Pair(7, 4)));
}

TEST(InterpreterBlockCountTest, IfElseJumpsCountTheirTarget) {
  const std::string text =
      "%if\n"
      "N10 P1 = %d\n"
      "$IF P1 == 2\n"
      "N20 X1\n"
      "$ELSE\n"
      "N30 X2\n"
      "$ENDIF\n"
      "N40 M30\n";
  auto with = [&](int p1) {
    std::string t = text;
    t.replace(t.find("%d"), 2, std::to_string(p1));
    return t;
  };
  // False: $IF jumps to $ELSE (+1), then in sequence.
  const auto no = Execute({{"if.isg", with(1)}}, true);
  EXPECT_THAT(no->Counts(), ElementsAre(Pair(1, 1), Pair(2, 2), Pair(3, 3), Pair(5, 4), Pair(6, 5),
                                        Pair(7, 6), Pair(8, 7)));
  // True: the branch runs, $ELSE jumps to $ENDIF (+1).
  const auto yes = Execute({{"if.isg", with(2)}}, true);
  EXPECT_THAT(yes->Counts(), ElementsAre(Pair(1, 1), Pair(2, 2), Pair(3, 3), Pair(4, 4), Pair(5, 5),
                                         Pair(7, 6), Pair(8, 7)));
}

TEST(InterpreterBlockCountTest, SubprogramCountsItsFileAndTheReturnCountsOne) {
  // The called file counts its lines up to its first block (comment line and % line); the
  // return counts the caller's next line. Blank and comment lines in sequence count.
  const auto r = Execute({{"main.isg",
                           "%main\n"
                           "; comment\n"
                           "N10 G01 X1 F100\n"
                           "\n"
                           "N20 L sub\n"
                           "N30 X2\n"
                           "N40 M30\n"},
                          {"sub.isg",
                           "; sub comment\n"
                           "%sub\n"
                           "N10 Z1\n"
                           "N20 Z2\n"
                           "M17\n"}},
                         true);
  ASSERT_EQ(r->error, "");
  std::vector<std::tuple<uint32_t, uint32_t, uint32_t>> seen;  // program, line, count
  for (const PreparedBlock& b : r->blocks) seen.emplace_back(b.program, r->Line(b), b.block_count);
  EXPECT_THAT(seen,
              ElementsAreArray(std::vector<std::tuple<uint32_t, uint32_t, uint32_t>>{{0, 1, 1},
                                                                                     {0, 3, 3},
                                                                                     {0, 5, 5},
                                                                                     {1, 2, 7},
                                                                                     {1, 3, 8},
                                                                                     {1, 4, 9},
                                                                                     {1, 5, 10},
                                                                                     {0, 6, 11},
                                                                                     {0, 7, 12}}));
  // The same program twice: a second call counts the file's lines again.
  const auto twice = Execute(
      {{"main.isg", "%main\nN10 L sub\nN20 L sub\nN30 M30\n"}, {"sub.isg", "\n%sub\nN10 Z1\n"}},
      false);
  ASSERT_EQ(twice->error, "");
  ASSERT_EQ(twice->blocks.size(), 3u);
  EXPECT_EQ(twice->blocks[0].block_count, 2u + 3u);       // N10 L sub = 2, sub N10 = 2 + 3
  EXPECT_EQ(twice->blocks[1].block_count, 5u + 1u + 3u);  // return: N20 = 6, sub N10 = 6 + 3
  EXPECT_EQ(twice->blocks[2].block_count, 9u + 1u);       // return: N30 = 10
}

TEST(InterpreterBlockCountTest, Mtc200JsrRtsAndBranchLoopCountLikeJumps) {
  const auto r = Execute({{"a.mtc",
                           "N0001 @100=2\n"
                           "; comment\n"
                           "N0002 .LOOP\n"
                           "N0003 JSR .MOVE\n"
                           "N0004 @100=@100-1 BGT .LOOP\n"
                           "N0005 RET\n"
                           "\n"
                           "N0006 .MOVE\n"
                           "N0007 G01 X@100 F100 RTS\n"}},
                         true);
  ASSERT_EQ(r->error, "");
  EXPECT_THAT(r->Counts(), ElementsAre(Pair(1, 1), Pair(3, 3), Pair(4, 4), Pair(8, 5), Pair(9, 6),
                                       Pair(5, 7), Pair(3, 8), Pair(4, 9), Pair(8, 10), Pair(9, 11),
                                       Pair(5, 12), Pair(6, 13)));
  // Off: only the moves and the end, with the same counts.
  const auto off = Execute({{"a.mtc",
                             "N0001 @100=2\n"
                             "; comment\n"
                             "N0002 .LOOP\n"
                             "N0003 JSR .MOVE\n"
                             "N0004 @100=@100-1 BGT .LOOP\n"
                             "N0005 RET\n"
                             "\n"
                             "N0006 .MOVE\n"
                             "N0007 G01 X@100 F100 RTS\n"}},
                           false);
  EXPECT_THAT(off->Counts(), ElementsAre(Pair(9, 6), Pair(9, 11), Pair(6, 13)));
}

TEST(InterpreterBlockCountTest, BlankAndCommentLinesBetweenBlocksCount) {
  const auto r = Execute({{"c.isg",
                           "%c\n"
                           "\n"
                           "; one\n"
                           "(two)\n"
                           "\n"
                           "N10 X1\n"
                           "   \n"
                           "N20 X2 ; three\n"
                           "M30\n"}},
                         false);
  ASSERT_EQ(r->error, "");
  EXPECT_THAT(r->Counts(), ElementsAre(Pair(6, 6), Pair(8, 8), Pair(9, 9)));
}

// ---- SetEveryBlock --------------------------------------------------------------------------

TEST(InterpreterEveryBlockTest, BlocksWithoutEffectAreHandedOutOnlyWhenOn) {
  // Manual 10: block search to N100 P100 = 1, a block without motion.
  const std::string text = Seed("blocksearch_block_without_motion.isg");
  const auto off = Execute({{"t_sv_p.isg", text}}, false);
  const auto on = Execute({{"t_sv_p.isg", text}}, true);
  ASSERT_EQ(off->error, "");
  ASSERT_EQ(on->error, "");
  std::vector<int32_t> off_numbers, on_numbers;
  for (const PreparedBlock& b : off->blocks) off_numbers.push_back(off->Number(b));
  for (const PreparedBlock& b : on->blocks) on_numbers.push_back(on->Number(b));
  EXPECT_THAT(off_numbers, ElementsAre(907090, 70, 95, 110, 120, 907091));
  EXPECT_THAT(on_numbers, ElementsAre(-1, 907090, 70, 95, 100, 110, 120, 907091));
  const PreparedBlock& n100 = on->blocks[4];
  EXPECT_EQ(n100.motion, Motion::kNone);
  EXPECT_EQ(n100.block_count, 5u);
  // The blocks both hand out are the same.
  for (size_t i = 0, j = 0; i < off->blocks.size(); ++i, ++j) {
    while (on->Number(on->blocks[j]) != off->Number(off->blocks[i])) ++j;
    EXPECT_EQ(on->blocks[j].target, off->blocks[i].target);
    EXPECT_EQ(on->blocks[j].block_count, off->blocks[i].block_count);
  }
}

TEST(InterpreterEveryBlockTest, StructuresAndBareBlockNumbersAreHandedOut) {
  const auto r = Execute({{"s.isg",
                           "%s\n"
                           "N10\n"
                           "N20 $FOR P1 = 1, 2, 1\n"
                           "N30 P2 = P2 + P1\n"
                           "N40 $ENDFOR\n"
                           "N50 #BLOCKSEARCH LOCKED\n"
                           "N60 #BLOCKSEARCH RELEASED\n"
                           "N70 M30\n"}},
                         true);
  ASSERT_EQ(r->error, "");
  std::vector<int32_t> numbers;
  for (const PreparedBlock& b : r->blocks) numbers.push_back(r->Number(b));
  EXPECT_THAT(numbers, ElementsAre(-1, 10, 20, 30, 20, 30, 40, 50, 60, 70));
  EXPECT_EQ(r->interpreter->Variable("P2"), 3);
}

TEST(InterpreterEveryBlockTest, AnEndlessLoopIsStillAnError) {
  InterpreterConfig tight = Axes();
  tight.max_steps_per_block = 100;
  const auto r =
      Execute({{"e.isg", "%e\nN10 $WHILE 1\nN20 P1 = P1 + 1\nN30 $ENDWHILE\n"}}, true, {}, tight);
  EXPECT_THAT(r->error, HasSubstr("endless loop"));
  EXPECT_LE(r->blocks.size(), 101u);
  // A block with an effect starts the count of blocks without one again.
  const auto moving = Execute(
      {{"m.isg", "%m\nN10 $FOR P1 = 1, 500, 1\nN20 P2 = P1\nN30 X[P1]\nN40 $ENDFOR\nN50 M30\n"}},
      true, {}, tight);
  EXPECT_EQ(moving->error, "");
  EXPECT_TRUE(moving->blocks.back().end);
}

TEST(InterpreterEveryBlockTest, EndforWithAMoveHandsOutTheForLineAfterIt) {
  // A $ENDFOR line that also moves is handed out (not counted), then the $FOR line it re-reads.
  const auto r = Execute({{"f.isg", "%f\n$FOR P1 = 1, 2, 1\nN10 X[P1]\n$ENDFOR Z1\nM30\n"}}, true);
  ASSERT_EQ(r->error, "");
  EXPECT_THAT(r->Counts(), ElementsAre(Pair(1, 1), Pair(2, 2), Pair(3, 3), Pair(4, 3), Pair(2, 4),
                                       Pair(3, 5), Pair(4, 6), Pair(5, 7)));
  EXPECT_EQ(r->blocks[3].motion, Motion::kRapid);
  EXPECT_EQ(r->blocks[4].motion, Motion::kNone);
}

// ---- #BLOCKSEARCH LOCKED / RELEASED ---------------------------------------------------------

// (program name, N number) of every locked block.
std::vector<std::pair<std::string, int32_t>> Locked(const Run& r) {
  std::vector<std::pair<std::string, int32_t>> locked;
  for (const PreparedBlock& b : r.blocks)
    if (b.search_locked && b.block >= 0) locked.emplace_back(r.ProgramOf(b).name, r.Number(b));
  return locked;
}

constexpr const char* kGsp = "%GSP\nN10 X5\nN20 M17\n";

TEST(InterpreterSearchLockTest, ManualExampleOneLocksN40ToN100AndTheSubprogram) {
  // Manual 6, example 1: "Im Bereich der NC-Sätze N40-N100 einschließlich der darin
  // aufgerufenen Unterprogramme darf ... keine Fortsetzposition angewählt werden".
  for (bool every : {true, false}) {
    SCOPED_TRACE(every);
    const auto r = Execute(
        {{"blocksearch.isg", Seed("blocksearch_locked_example1.isg")}, {"GSP.nc", kGsp}}, every);
    ASSERT_EQ(r->error, "");
    using P = std::pair<std::string, int32_t>;
    std::vector<P> want = {{"BLOCKSEARCH", 40}, {"BLOCKSEARCH", 50}, {"BLOCKSEARCH", 60},
                           {"BLOCKSEARCH", 65}, {"GSP", -1},         {"GSP", 10},
                           {"GSP", 20},         {"BLOCKSEARCH", 70}, {"BLOCKSEARCH", 80},
                           {"BLOCKSEARCH", 90}, {"BLOCKSEARCH", 100}};
    if (!every)  // the % line and the call have no effect
      std::erase_if(want, [](const P& p) { return p.second == -1 || p.second == 65; });
    EXPECT_THAT(Locked(*r), ElementsAreArray(want));
  }
}

TEST(InterpreterSearchLockTest, ManualExampleTwoNestedLocksEndAtTheFirstRelease) {
  // Manual 6, example 2: "Bereich der Satzvorlaufsperre bei Schachtelung umfasst N40-N75".
  const auto r =
      Execute({{"blocksearch.isg", Seed("blocksearch_locked_nested.isg")}, {"GSP.nc", kGsp}}, true);
  ASSERT_EQ(r->error, "");
  std::vector<std::pair<std::string, int32_t>> want = {
      {"BLOCKSEARCH", 40}, {"BLOCKSEARCH", 50}, {"BLOCKSEARCH", 55}, {"BLOCKSEARCH", 60},
      {"BLOCKSEARCH", 65}, {"GSP", -1},         {"GSP", 10},         {"GSP", 20},
      {"BLOCKSEARCH", 70}, {"BLOCKSEARCH", 75}};
  EXPECT_THAT(Locked(*r), ElementsAreArray(want));
}

TEST(InterpreterSearchLockTest, ReleaseInsideASubprogramEndsTheLockAndCaseDoesNotMatter) {
  const auto r =
      Execute({{"m.isg",
                "%m\n"
                "N10 #blocksearch   Locked\n"
                "N20 L sub\n"
                "N30 X1\n"
                "N40 M30\n"},
               {"sub.isg", "%sub\nN10 Z1\nN20 #BlockSearch released ; comment\nN30 Z2\n"}},
              true);
  ASSERT_EQ(r->error, "");
  EXPECT_THAT(Locked(*r), ElementsAre(Pair("M", 10), Pair("M", 20), Pair("SUB", -1),
                                      Pair("SUB", 10), Pair("SUB", 20)));
}

std::string ParseError(const std::string& text) {
  const ParseResult r = ParseProgram(text, "p.isg", Dialect::kIsg);
  return r.ok() ? "" : Format(r.errors[0], r.program.files);
}

TEST(InterpreterSearchLockTest, UnknownKeywordIsAnErrorAtItsPosition) {
  EXPECT_EQ(ParseError("%p\nN10 #BLOCKSEARCH LOCKD\n"),
            "p.isg:2:18: error: unknown #BLOCKSEARCH keyword 'LOCKD': expected LOCKED or RELEASED");
  EXPECT_EQ(ParseError("%p\nN10 #BLOCKSEARCH   locked  now ; x\n"),
            "p.isg:2:28: error: unexpected 'NOW' after #BLOCKSEARCH LOCKED");
  EXPECT_EQ(ParseError("%p\nN10 #BLOCKSEARCH ; x\n"),
            "p.isg:2:17: error: expected LOCKED or RELEASED after #BLOCKSEARCH");
  EXPECT_EQ(ParseError("%p\nN10 #BLOCKSEARCH LOCKED\nN20 #BLOCKSEARCH RELEASED\n"), "");
  // Another #-command is not block search's to judge.
  EXPECT_EQ(ParseError("%p\nN10 #BLOCKSEARCHES X\n"), "");
}

TEST(InterpreterSearchLockTest, TheInterpreterRejectsAWrongTextOfAProgramBuiltByHand) {
  // Programs reach the interpreter parsed; one changed afterwards still stops at the command.
  ParseResult parsed =
      ParseProgram("%p\nN10 X1\nN20 #BLOCKSEARCH LOCKED\nN30 X2\n", "p.isg", Dialect::kIsg);
  ASSERT_TRUE(parsed.ok());
  parsed.program.texts[0] = "BLOCKSEARCH XYZ";
  Interpreter in({&parsed.program}, Axes());
  PreparedBlock b;
  EXPECT_TRUE(in.Next(b));
  EXPECT_FALSE(in.Next(b));
  ASSERT_TRUE(in.error());
  EXPECT_EQ(Format(*in.error(), {in.ErrorFile()}),
            "p.isg:3:5: error: unknown #BLOCKSEARCH keyword 'XYZ': expected LOCKED or RELEASED");
}

// ---- #DISTANCE PROG START -------------------------------------------------------------------

TEST(InterpreterDistanceCommandTest, OnOffClearOfTheManual) {
  // 4.1.2, figure 14.
  const auto r = Execute({{"example.isg", Seed("blocksearch_distance_prog_start_cmds.isg")}}, true);
  ASSERT_EQ(r->error, "");
  std::vector<std::pair<int32_t, DistanceCommand>> seen;
  for (const PreparedBlock& b : r->blocks) seen.emplace_back(r->Number(b), b.distance_command);
  using D = DistanceCommand;
  EXPECT_THAT(seen, ElementsAre(Pair(-1, D::kNone), Pair(5, D::kOff), Pair(10, D::kNone),
                                Pair(15, D::kClear), Pair(16, D::kOn), Pair(20, D::kNone),
                                Pair(30, D::kNone), Pair(40, D::kNone), Pair(-1, D::kNone)));
  // Without SetEveryBlock the commands are handed out too (the channel keeps the distance).
  const auto off =
      Execute({{"example.isg", Seed("blocksearch_distance_prog_start_cmds.isg")}}, false);
  int commands = 0;
  for (const PreparedBlock& b : off->blocks) commands += b.distance_command != D::kNone;
  EXPECT_EQ(commands, 3);
}

TEST(InterpreterDistanceCommandTest, OtherTextAfterDistanceProgStartIsAnError) {
  EXPECT_EQ(ParseError("%p\nN10 #DISTANCE PROG START MAYBE\n"),
            "p.isg:2:26: error: unknown #DISTANCE PROG START keyword 'MAYBE': expected ON, OFF "
            "or CLEAR");
  EXPECT_EQ(ParseError("%p\nN10 #DISTANCE PROG START\n"),
            "p.isg:2:25: error: expected ON, OFF or CLEAR after #DISTANCE PROG START");
  EXPECT_EQ(ParseError("%p\nN10 #DISTANCE PROG START ON OFF\n"),
            "p.isg:2:29: error: unexpected 'OFF' after #DISTANCE PROG START ON");
  EXPECT_EQ(ParseError("%p\nN10 #distance prog start clear\n"), "");
  // The seed programs of 4.1.2 all parse (two spellings of the manual's example).
  for (const char* seed :
       {"blocksearch_distance_prog_start.isg", "blocksearch_distance_prog_start_cmds.isg"})
    EXPECT_EQ(ParseError(Seed(seed)), "") << seed;
}

// ---- StartAt (entry point, manual 3.6) ------------------------------------------------------

constexpr const char* kEntry =
    "%entry\n"
    "N10 P1 = 1\n"
    "N20 G01 X10 F100\n"
    "\n"
    "N30 P2 = 2\n"
    "N40 X20\n"
    "M30\n";

uint32_t OffsetOf(const std::string& text, const std::string& what) {
  return static_cast<uint32_t>(text.find(what));
}

TEST(InterpreterStartAtTest, BlocksBeforeTheOffsetDoNotRun) {
  const std::string text = kEntry;
  const auto r = Execute({{"entry.isg", text}}, true, OffsetOf(text, "N30"));
  ASSERT_EQ(r->error, "");
  EXPECT_EQ(r->interpreter->Variable("P1"), 0);  // N10 did not run
  EXPECT_EQ(r->interpreter->Variable("P2"), 2);
  // Counted as the program shortened to start at N30's line: N30 is line 1.
  EXPECT_THAT(r->Counts(), ElementsAre(Pair(5, 1), Pair(6, 2), Pair(7, 3)));
  EXPECT_EQ(r->blocks[1].target[0], 20);
}

TEST(InterpreterStartAtTest, AnOffsetInsideALineStartsAtTheNextLine) {
  const std::string text = kEntry;
  // Inside N20's line: the blank line after it is the shortened program's first line.
  const auto r = Execute({{"entry.isg", text}}, false, OffsetOf(text, "X10"));
  ASSERT_EQ(r->error, "");
  EXPECT_EQ(r->interpreter->Variable("P1"), 0);
  ASSERT_EQ(r->blocks.size(), 2u);  // N40 X20, M30
  EXPECT_EQ(r->blocks[0].block_count, 3u);
  // Offset 0 is the whole program, counted as without StartAt.
  const auto whole = Execute({{"entry.isg", text}}, false, 0u);
  const auto plain = Execute({{"entry.isg", text}}, false);
  ASSERT_EQ(whole->blocks.size(), plain->blocks.size());
  for (size_t i = 0; i < whole->blocks.size(); ++i)
    EXPECT_EQ(whole->blocks[i].block_count, plain->blocks[i].block_count);
  EXPECT_EQ(whole->interpreter->Variable("P1"), 1);
}

TEST(InterpreterStartAtTest, AnOffsetPastTheLastBlockIsRefused) {
  const std::string text = kEntry;
  const ParseResult parsed = ParseProgram(text, "entry.isg", Dialect::kIsg);
  Interpreter past({&parsed.program}, Axes());
  EXPECT_FALSE(past.StartAt(static_cast<uint32_t>(text.size())));
  EXPECT_FALSE(past.StartAt(OffsetOf(text, "M30") + 1));
  EXPECT_FALSE(past.StartAt(0xFFFFFFFFu));
  // Refused changes nothing: the program runs from its start.
  PreparedBlock b;
  ASSERT_TRUE(past.Next(b));
  EXPECT_EQ(b.block_count, 3u);  // N20 G01 X10
  // Too late once the program runs.
  EXPECT_FALSE(past.StartAt(0));
  Interpreter last({&parsed.program}, Axes());
  EXPECT_TRUE(last.StartAt(OffsetOf(text, "M30")));
  ASSERT_TRUE(last.Next(b));
  EXPECT_TRUE(b.end);
  EXPECT_EQ(b.block_count, 1u);
}

}  // namespace
}  // namespace vmt::control::nc
