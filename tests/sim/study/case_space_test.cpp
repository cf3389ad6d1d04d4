// The cases of a plan made from their index: the ids a study writes, found back from an id
// (names holding '/' included), and a folder's share of them as a bit per case.
#include <gtest/gtest.h>

#include <set>

#include "sim/study/study_cases.hpp"
#include "sim/study/study_source.hpp"

namespace vmt::sim::study {
namespace {

struct Plan {
  StudyPlan plan;
  std::vector<Interruption> interruptions;
  Plan() {
    plan.subroutines = {{"nc/99.mtc", "/x/nc/99.mtc", {}},
                        {"manual X,Z", "", {"X", "Z"}},
                        {"nc/a/b.mtc", "/x/nc/a/b.mtc", {}}};
    plan.retracts = {{"X+ then Z+", {}}, {"Z/X", {}}, {"up", {}}};
    plan.modes = {ReposMode::kRepositioning, ReposMode::kRestart};
    for (int i = 0; i < 7; ++i)
      interruptions.push_back({"N00" + std::to_string(10 * i + 10) + "@250", 1.0 + i, "", 250});
    interruptions.push_back({"N0010#2@250", 9.0, "", 250});
  }
};

TEST(study_case_space, EveryIndexRoundTripsThroughItsId) {
  const Plan p;
  const CaseSpace space(p.plan, p.interruptions);
  ASSERT_EQ(space.size(), 3u * 8 * 3 * 2);
  EXPECT_EQ(space.groups(), 3u * 8);
  EXPECT_EQ(space.cases_per_group(), 6u);
  std::set<std::string> ids;
  for (size_t k = 0; k < space.size(); ++k) {
    const StudyCase c = space.At(k);
    EXPECT_EQ(c.index, k);
    EXPECT_EQ(c.group, c.subroutine * p.interruptions.size() + c.interruption);
    EXPECT_EQ(space.Index(c.subroutine, c.interruption, c.retract, c.mode == ReposMode::kRestart),
              k);
    EXPECT_EQ(c.id, p.plan.subroutines[c.subroutine].name + "/" +
                        p.interruptions[c.interruption].label + "/" +
                        p.plan.retracts[c.retract].name + "/" + ToString(c.mode));
    ASSERT_EQ(space.IndexOf(c.id), k) << c.id;
    ids.insert(c.id);
  }
  EXPECT_EQ(ids.size(), space.size());  // no two cases share an id
  const std::vector<StudyCase> all = EnumerateCases(p.plan, p.interruptions);
  ASSERT_EQ(all.size(), space.size());
  EXPECT_EQ(all[17].id, space.At(17).id);
}

TEST(study_case_space, AnIdOfNoCaseIsNone) {
  const Plan p;
  const CaseSpace space(p.plan, p.interruptions);
  for (const std::string id :
       {"", "nc/99.mtc", "nc/99.mtc/N0010@250/up", "nc/99.mtc/N0010@250/up/restarted",
        "nc/99.mtc/N0015@250/up/restart", "nc/98.mtc/N0010@250/up/restart",
        "nc/99.mtc/N0010@250/down/restart", "nc/99.mtc//up/restart",
        "nc/99.mtc/N0010@250/up/restart/", "xnc/99.mtc/N0010@250/up/restart"})
    EXPECT_FALSE(space.IndexOf(id)) << id;
  EXPECT_EQ(space.IndexOf("nc/a/b.mtc/N0010#2@250/Z/X/restart"), space.Index(2, 7, 1, 1));
}

TEST(study_case_space, AShareIsWholeGroupsThenItsFirstCases) {
  const Plan p;
  const CaseSpace space(p.plan, p.interruptions);
  StudySource source;
  source.shard = 2, source.shards = 5;
  const std::vector<bool> share = ShareOf(space, source);
  ASSERT_EQ(share.size(), space.size());
  size_t n = 0;
  for (size_t k = 0; k < space.size(); ++k) {
    EXPECT_EQ(share[k], space.At(k).group % 5 == 1) << k;
    n += share[k];
  }
  EXPECT_EQ(n, 5u * 6);  // groups 1, 6, 11, 16, 21 of 24
  source.max_cases = 8;
  const std::vector<bool> first = ShareOf(space, source);
  size_t m = 0, last = 0;
  for (size_t k = 0; k < space.size(); ++k)
    if (first[k]) ++m, last = k;
  EXPECT_EQ(m, 8u);
  EXPECT_EQ(last, space.Index(0, 6, 0, 1));  // all of group 1, then two of group 6
  source.shards = source.shard = 1;
  source.max_cases.reset();
  const std::vector<bool> whole = ShareOf(space, source);
  EXPECT_EQ(std::count(whole.begin(), whole.end(), true), static_cast<long>(space.size()));
}

}  // namespace
}  // namespace vmt::sim::study
