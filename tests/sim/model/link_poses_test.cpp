// The poses of a few links (a stylus' and the part's, every drive tick) come out as the same
// bits as the poses of the whole machine, and only the links on their chains to the root are
// posed.

#include <gtest/gtest.h>

#include <random>

#include "../sim_test_support.hpp"
#include "sim/model/machine_model.hpp"

namespace vmt::sim {
namespace {

using testing::Lathe;

// The link itself and its ancestors, found the slow way: parent after parent.
std::vector<bool> Ancestry(const MachineModel& m, int link) {
  std::vector<bool> on(m.links.size(), false);
  for (bool moved = true; moved;) {
    on[link] = true;
    moved = false;
    for (const Joint& j : m.joints)
      if (j.child_link == link) link = j.parent_link, moved = true;
  }
  return on;
}

TEST(LinkPoses, AFewLinksArePosedAsTheWholeMachinePosesThem) {
  const MachineModel& m = Lathe();
  ASSERT_GT(m.links.size(), 5u);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> joint(-2, 2);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<double> q(m.joints.size());
    for (double& v : q) v = joint(random);
    const std::vector<Eigen::Isometry3d> whole = LinkPoses(m, q);
    for (int link = 0; link < static_cast<int>(m.links.size()); ++link) {
      const std::vector<bool> needed = LinkChains(m, {link});
      EXPECT_EQ(needed, Ancestry(m, link)) << m.links[link].name;
      std::vector<Eigen::Isometry3d> some;
      LinkPoses(m, q, needed, some);
      ASSERT_EQ(some.size(), m.links.size());
      for (size_t l = 0; l < m.links.size(); ++l) {
        if (needed[l])
          EXPECT_TRUE(some[l].matrix() == whole[l].matrix()) << m.links[l].name;
        else
          EXPECT_TRUE(some[l].matrix() == Eigen::Matrix4d::Identity()) << m.links[l].name;
      }
    }
  }
  // Two links: the union of their chains.
  const int spindle = m.LinkIndex("spindle"), turret = m.LinkIndex("turret");
  ASSERT_GE(spindle, 0);
  ASSERT_GE(turret, 0);
  std::vector<bool> both = Ancestry(m, spindle), turret_chain = Ancestry(m, turret);
  for (size_t l = 0; l < both.size(); ++l) both[l] = both[l] || turret_chain[l];
  EXPECT_EQ(LinkChains(m, {spindle, turret}), both);
}

}  // namespace
}  // namespace vmt::sim
