#include "sim/runner/run_story.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sstream>

namespace vmt::sim {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

std::vector<std::string> Story(const std::string& events) {
  std::istringstream in(events);
  return RunStory(in);
}

TEST(RunStory, TellsTheProgramTheOperatorRepositioningAndPathGuard) {
  const auto lines = Story(R"({"t":0.0,"event":"step","text":"timeline[0]: press mAUTO"}
{"t":0.1,"event":"step","text":"timeline[1]: press mSTART"}
{"t":0.104,"event":"nc","state":"running"}
{"t":0.105,"event":"path_guard","move":"spindle start","clear":true,"min_clearance":211.661,"closest":["spindle_jaw1","turret_st01_holder"]}
{"t":10.004,"event":"nc","state":"hold"}
{"t":10.3,"event":"step","text":"timeline[3]: press mMANU"}
{"t":11.4,"event":"path_guard","move":"jog","clear":true,"min_clearance":0.019,"closest":["turret_st01_insert","workpiece"]}
{"t":12.0,"event":"snapshot","camera":"work","file":"work_12.0s.png"}
{"t":12.1,"event":"step","text":"timeline[9]: press mSTART"}
{"t":12.708,"event":"repos","subroutine":true}
{"t":12.708,"event":"nc","state":"running"}
{"t":15.036,"event":"repos","subroutine":false}
not json
{"t":20.898,"event":"nc","state":"ended"}
)");
  EXPECT_THAT(lines, ElementsAre("NC program: started at 0.10 s, held 1 time, ended at 20.90 s",
                                 "keys pressed: mAUTO, mSTART, mMANU",
                                 "repositioning: the REPOS subroutine ran 12.71 s to 15.04 s",
                                 "PathGuard: checked 2 moves, all clear; closest approach 0.019 mm "
                                 "(turret_st01_insert and workpiece)"));
}

TEST(RunStory, TellsRefusalsErrorsMessagesAndDriveTrips) {
  const auto lines = Story(R"({"t":0.1,"event":"nc","state":"running"}
{"t":2.5,"event":"drive","name":"C","overload":true,"overspeed":false,"parameter_set_error":false}
{"t":3.0,"event":"path_guard","move":"G77","clear":false,"parts":["turret_disc","spindle_jaw2"],"reaction":"stop"}
{"t":3.0,"event":"message","source":"nc","number":507,"text":"collision"}
{"t":3.1,"event":"message","source":"nc","number":507,"state":"cleared"}
{"t":3.2,"event":"message","source":"nc","number":507,"text":"collision"}
{"t":3.0,"event":"nc","state":"error","error":"PathGuard: contact"}
)");
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_EQ(lines[0],
            "NC program: started at 0.10 s, stopped in error at 3.00 s: PathGuard: contact");
  EXPECT_EQ(lines[1],
            "PathGuard: checked 1 move, refused 1: G77 at 3.00 s (turret_disc and spindle_jaw2)");
  EXPECT_EQ(lines[2], "messages: nc 507 at 3.00 s \"collision\"");
  EXPECT_THAT(lines[3], HasSubstr("C overload at 2.50 s"));
}

TEST(RunStory, NothingToTellForARunWithoutEvents) { EXPECT_TRUE(Story("").empty()); }

}  // namespace
}  // namespace vmt::sim
