// A case's verdict and severity from its events: a refused REPOS move's depth past the first
// contact (a graze within 0.1 mm of the move's end, a crash beyond), and PathGuard refusing the
// operator's own retract as "retract_refused", not as the subroutine's error.
#include "sim/study/case_observer.hpp"

#include <gtest/gtest.h>

namespace vmt::sim::study {
namespace {

using Json = nlohmann::ordered_json;

struct Fixture {
  StudyPlan plan;
  std::vector<Interruption> interruptions{{"N0030@250", 2.0, "N0030", 250}};
  StudyCase c;
  Fixture() {
    plan.subroutines.push_back({"nc/99.mtc", "nc/99.mtc", {}});
    plan.retracts.push_back({"X+ then Z-", {{"X", 20, std::nullopt}, {"Z", -20, std::nullopt}}});
    c.id = "nc/99.mtc/N0030@250/X+ then Z-/repositioning";
  }
  CaseResult Run(const std::vector<Json>& events) const {
    CaseObserver obs(5);
    for (const Json& e : events) obs.OnEvent(e);
    return obs.Result(plan, interruptions, c, 9.0);
  }
};

Json Step(size_t i, double t) {
  return {{"t", t}, {"event", "step"}, {"text", "timeline[" + std::to_string(i) + "]: x"}};
}

Json Refused(const std::string& move, Json from, Json to, Json at) {
  return {{"t", 3.0},
          {"event", "path_guard"},
          {"move", move},
          {"clear", false},
          {"from", from},
          {"to", to},
          {"parts", {"turret_st01_holder", "spindle_jaw2"}},
          {"point", {78.5, -17.1, 140.0}},
          {"position", at}};
}

Json NcError(double t) {
  return {{"t", t}, {"event", "nc"}, {"state", "error"}, {"error", "collision ahead"}};
}

TEST(study_observer, ACrashRecordsHowFarTheMoveWouldHaveGoneOn) {
  const Fixture f;
  const CaseResult r = f.Run({Step(5, 2.5),
                              {{"t", 2.6}, {"event", "repos"}, {"subroutine", true}},
                              Refused("G77", {{"X", 40.0}, {"Z", 120.0}},
                                      {{"X", 28.0}, {"Z", 100.0}}, {{"X", 34.0}, {"Z", 110.0}}),
                              NcError(3.0)});
  EXPECT_EQ(r["verdict"], "collision") << r.dump();
  EXPECT_EQ(r["contact_class"], "crash");
  EXPECT_DOUBLE_EQ(r["past_contact_mm"].get<double>(), 11.662);  // hypot(6, 10)
  EXPECT_EQ(r["contact_move"], "G77");
  EXPECT_EQ(r["contact_target"], (Json{{"X", 28.0}, {"Z", 100.0}}));
}

TEST(study_observer, AContactAtTheMovesEndIsAGraze) {
  const Fixture f;
  for (const double z : {100.1, 100.0}) {
    const CaseResult r = f.Run({Step(5, 2.5),
                                {{"t", 2.6}, {"event", "repos"}, {"subroutine", true}},
                                Refused("jog", {{"Z", 120.0}}, {{"Z", 100.0}}, {{"Z", z}}),
                                NcError(3.0)});
    EXPECT_EQ(r["contact_class"], "graze") << z;
  }
  const CaseResult r = f.Run({Step(5, 2.5),
                              {{"t", 2.6}, {"event", "repos"}, {"subroutine", true}},
                              Refused("jog", {{"Z", 120.0}}, {{"Z", 100.0}}, {{"Z", 100.102}}),
                              NcError(3.0)});
  EXPECT_EQ(r["contact_class"], "crash");
}

TEST(study_observer, ARefusedRetractIsTheOperatorsNotTheSubroutines) {
  const Fixture f;
  // PathGuard refuses the retract's second jog (toward the chuck): 507, the case ends before
  // the REPOS phase.
  const CaseResult r =
      f.Run({Refused("jog", {{"Z", 110.0}}, {{"Z", 90.0}}, {{"Z", 101.0}}), NcError(2.8)});
  EXPECT_EQ(r["verdict"], "retract_refused") << r.dump();
  EXPECT_TRUE(r["contact_class"].is_null());
  EXPECT_EQ(r["retract_contact"], (Json{"turret_st01_holder", "spindle_jaw2"}));
  // Another error without a refused retract stays an error.
  const CaseResult e = f.Run({Step(5, 2.5), NcError(2.8)});
  EXPECT_EQ(e["verdict"], "error");
}

TEST(study_observer, PastContactOverTheAxesTheMoveNames) {
  EXPECT_DOUBLE_EQ(PastContact(Json{{"X", 1.0}, {"Z", 2.0}}, Json{{"X", 4.0}, {"Z", 6.0}}), 5.0);
  EXPECT_DOUBLE_EQ(PastContact(Json{{"X", 1.0}}, Json{{"X", 1.0}}), 0.0);
  EXPECT_DOUBLE_EQ(PastContact(nullptr, Json{{"X", 1.0}}), 0.0);
}

}  // namespace
}  // namespace vmt::sim::study
