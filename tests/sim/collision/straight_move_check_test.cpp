// PathGuard's straight-move check on lathe-c1's real geometry against brute force: on random
// moves of the carriage, cross slide, turret and tailstock, it never misses a contact that
// sampling finds, places the first contact within the resolution (1 µm of the fastest point),
// reports only real contacts, and its smallest clearance is within its stated tolerance.

#include "sim/collision/straight_move_check.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>

#include "sim/model/machine_model.hpp"

namespace vmt::sim {
namespace {

const char* kModel = VMT_SOURCE_DIR "/models/lathe-c1/machine.yaml";

struct Lathe {
  Lathe()
      : model(LoadMachineModel(kModel)),
        world(model, {{"workpiece", "spindle", 0.030, 0.160, 0.060}}) {}
  std::vector<double> Zero() const { return std::vector<double>(model.joints.size(), 0.0); }
  int J(const char* name) const { return model.JointIndex(name); }
  MachineModel model;
  CollisionWorld world;
};

/// Any pair that is not the machine's own contact touching at the current pose.
bool AnyContact(const CollisionWorld& w, int* a = nullptr, int* b = nullptr) {
  for (int i = 0; i < w.size(); ++i)
    for (int k = i + 1; k < w.size(); ++k)
      if (!w.MayTouch(i, k) && w.Collide(i, k)) {
        if (a) *a = i, *b = k;
        return true;
      }
  return false;
}

/// Whether the move changes the pair's relative pose (the pairs whose clearance it can change).
std::vector<std::pair<int, int>> MovingPairs(CollisionWorld& w, const std::vector<double>& from,
                                             const std::vector<double>& to);

std::vector<double> Lerp(const std::vector<double>& a, const std::vector<double>& b, double u) {
  std::vector<double> q(a.size());
  for (size_t i = 0; i < a.size(); ++i) q[i] = a[i] + (b[i] - a[i]) * u;
  return q;
}

std::vector<std::pair<int, int>> MovingPairs(CollisionWorld& w, const std::vector<double>& from,
                                             const std::vector<double>& to) {
  std::vector<std::vector<Eigen::Isometry3d>> poses;
  for (double u : {0.0, 0.37, 1.0}) {
    w.Pose(Lerp(from, to, u));
    poses.emplace_back();
    for (int p = 0; p < w.size(); ++p)
      poses.back().push_back(w.X_WorldLink(w.part(p).link) * w.part(p).X_LinkPart);
  }
  std::vector<std::pair<int, int>> pairs;
  for (int i = 0; i < w.size(); ++i)
    for (int j = i + 1; j < w.size(); ++j) {
      if (w.MayTouch(i, j)) continue;
      const Eigen::Isometry3d r0 = poses[0][i].inverse() * poses[0][j];
      bool moves = false;
      for (int k = 1; k < 3; ++k)
        moves = moves || !(poses[k][i].inverse() * poses[k][j]).isApprox(r0, 1e-12);
      if (moves) pairs.emplace_back(i, j);
    }
  return pairs;
}

TEST(StraightMoveCheck, TheMachinesOwnContactsAreNotReported) {
  Lathe l;
  ASSERT_GT(l.world.size(), 20);
  // The default scene's start (Z500 X200 W300): saddle on its rail, turret in its housing,
  // workpiece in the jaws, pinion at the gear touch, and none of it counts.
  std::vector<double> home = l.Zero();
  home[l.J("z_carriage")] = 0.5, home[l.J("x_slide")] = 0.2, home[l.J("tailstock")] = 0.3;
  l.world.Pose(home);
  EXPECT_FALSE(AnyContact(l.world));
  // In the zero pose the turning tool stands in the workpiece: a contact, though it is there
  // from the start (a slide lies between them).
  l.world.Pose(l.Zero());
  int insert = -1, workpiece = -1;
  for (int p = 0; p < l.world.size(); ++p) {
    if (l.world.part(p).name == "turret_st01_insert") insert = p;
    if (l.world.part(p).name == "workpiece") workpiece = p;
  }
  ASSERT_GE(insert, 0);
  ASSERT_GE(workpiece, 0);
  EXPECT_TRUE(l.world.Collide(insert, workpiece));
  EXPECT_FALSE(l.world.MayTouch(insert, workpiece));
}

TEST(StraightMoveCheck, ToolIntoTheWorkpieceStopsAtItsSurface) {
  Lathe l;
  std::vector<double> from = l.Zero(), to = l.Zero();
  // Carriage over the workpiece, cross slide from far out straight in to the axis.
  from[l.J("z_carriage")] = to[l.J("z_carriage")] = 0.10;
  from[l.J("x_slide")] = 0.25;
  to[l.J("x_slide")] = 0.0;
  from[l.J("tailstock")] = to[l.J("tailstock")] = 0.45;
  StraightMoveCheck c = CheckStraightMove(l.world, from, to);
  ASSERT_FALSE(c.clear);
  // Something touched something, at a pose that really touches, and just before it nothing.
  l.world.Pose(c.q);
  EXPECT_TRUE(l.world.Collide(c.part_a, c.part_b));
  const double bound = std::abs(to[l.J("x_slide")] - from[l.J("x_slide")]);
  l.world.Pose(Lerp(from, to, c.u - 1e-6 / bound));
  EXPECT_FALSE(AnyContact(l.world));
  EXPECT_EQ(c.min_clearance_m, 0);
}

// Brute force: samples every 1/400 of the move, then the first touching interval every 0.5 µm
// of the fastest point; only the pairs the move can bring into contact within the interval
// (their boxes closer than twice the fastest point's travel) are asked.
struct BruteForce {
  bool contact = false;
  double u = 1;
};
BruteForce Sample(CollisionWorld& w, const std::vector<double>& from, const std::vector<double>& to,
                  double bound, const std::vector<std::pair<int, int>>& pairs) {
  BruteForce r;
  const int n = 400;
  for (int k = 1; k <= n; ++k) {
    const double u0 = static_cast<double>(k - 1) / n;
    w.Pose(Lerp(from, to, u0));
    std::vector<std::pair<int, int>> near;
    for (const auto& [i, j] : pairs)
      if (w.BoxDistance(i, j) <= 2 * bound / n) near.emplace_back(i, j);
    if (near.empty()) continue;
    const double fine = 0.5e-6 / bound;
    for (double u = u0; u <= u0 + 1.0 / n + fine; u += fine) {
      w.Pose(Lerp(from, to, std::min(u, 1.0)));
      for (const auto& [i, j] : near)
        if (w.Collide(i, j)) {
          r.contact = true, r.u = std::min(u, 1.0);
          return r;
        }
    }
  }
  return r;
}

// Brute force is 96 % of this test's time; under AddressSanitizer (about 90 s for all 60 trials)
// it was the longest test of the sanitizer run. The Release build checks all 60 trials. The
// sanitizer build, there to check memory, checks trials 20-39 of the same random sequence: they
// have every kind of move (turret turns, tailstock moves) and both outcomes (19 moves, 4
// contacts), at a tenth of the brute force's time (a few clear moves near a slide take most of
// it, and they lie outside). The counts asked for scale with the trials checked.
#if defined(__SANITIZE_ADDRESS__)
constexpr int kFirstTrial = 20, kEndTrial = 40;
#else
constexpr int kFirstTrial = 0, kEndTrial = 60;
#endif

TEST(StraightMoveCheck, AgreesWithBruteForceOnRandomMoves) {
  Lathe l;
  std::mt19937_64 rng(20261123);
  std::uniform_real_distribution<double> z(0.0, 0.65), x(0.0, 0.3), w(0.2, 0.7), unit(0, 1);
  int moves = 0, contacts = 0, clear = 0;
  std::uniform_real_distribution<double> x_in(0.0, 0.06);  // towards the workpiece and chuck
  for (int trial = 0; trial < 60; ++trial) {
    std::vector<double> from = l.Zero(), to = l.Zero();
    from[l.J("z_carriage")] = z(rng), to[l.J("z_carriage")] = z(rng);
    from[l.J("x_slide")] = x(rng), to[l.J("x_slide")] = trial % 2 ? x_in(rng) : x(rng);
    from[l.J("tailstock")] = to[l.J("tailstock")] = w(rng);
    if (trial % 3 == 0) to[l.J("turret")] = from[l.J("turret")] + (unit(rng) - 0.5) * 2;
    if (trial % 4 == 0) to[l.J("tailstock")] = w(rng);
    if (trial < kFirstTrial || trial >= kEndTrial) continue;  // drawn all the same: same moves
    l.world.Pose(from);
    if (AnyContact(l.world)) continue;  // starts inside: not a move to check
    ++moves;
    double bound = 0;
    for (int p = 0; p < l.world.size(); ++p)
      bound = std::max(bound, MotionBound(l.world, p, from, to));
    const auto t0 = std::chrono::steady_clock::now();
    const StraightMoveCheck c = CheckStraightMove(l.world, from, to);
    const auto t1 = std::chrono::steady_clock::now();
    const auto pairs = MovingPairs(l.world, from, to);
    const BruteForce bf = Sample(l.world, from, to, bound, pairs);
    const auto t2 = std::chrono::steady_clock::now();
    SCOPED_TRACE("trial " + std::to_string(trial));
    if (getenv("VMT_TIMING"))
      printf("trial %d guard %.1f ms brute %.1f ms pairs %zu contact %d\n", trial,
             std::chrono::duration<double, std::milli>(t1 - t0).count(),
             std::chrono::duration<double, std::milli>(t2 - t1).count(), pairs.size(), !c.clear);
    if (bf.contact) {
      // Never missed, never later than sampling finds it.
      ASSERT_FALSE(c.clear);
      EXPECT_LE(c.u, bf.u + 1e-6 / bound);
    }
    if (!c.clear) {
      ++contacts;
      // A real contact, and the first: clear 1 µm (of the fastest point) before it.
      l.world.Pose(c.q);
      EXPECT_TRUE(l.world.Collide(c.part_a, c.part_b));
      l.world.Pose(Lerp(from, to, std::max(0.0, c.u - 1.01e-6 / bound)));
      EXPECT_FALSE(AnyContact(l.world));
    } else {
      ++clear;
      // The smallest clearance: a real distance (so no smaller than the true minimum) and no
      // more than its tolerance above what sampling sees anywhere on the way.
      double sampled = 1e30;
      for (int k = 0; k <= 20; ++k) {
        l.world.Pose(Lerp(from, to, k / 20.0));
        for (const auto& [i, j] : pairs)
          if (l.world.BoxDistance(i, j) < sampled)  // a lower bound: farther pairs cannot win
            sampled = std::min(sampled, l.world.Distance(i, j));
      }
      const double tol = std::max(10e-6, 0.1 * c.min_clearance_m);
      EXPECT_GE(sampled, c.min_clearance_m - tol - 1e-12);
      l.world.Pose(Lerp(from, to, c.closest_u));
      EXPECT_NEAR(l.world.Distance(c.closest_a, c.closest_b), c.min_clearance_m, 1e-9);
    }
  }
  // The random moves exercise both outcomes (of 60 trials: 30 moves, 10 contacts, 5 clear).
  const int trials = kEndTrial - kFirstTrial;
  EXPECT_GE(moves, trials / 2);
  EXPECT_GE(contacts, trials / 6);
  EXPECT_GE(clear, trials / 12);
}

}  // namespace
}  // namespace vmt::sim
