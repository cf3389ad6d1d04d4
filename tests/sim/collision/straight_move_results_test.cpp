// The straight-move check's answers pinned bit for bit: how the check gets to them (which pairs
// it asks FCL about, how it poses the parts on the way) may be made faster, what it answers may
// not change. Random moves on lathe-c1 of carriage, cross slide, turret, tailstock and spindle,
// with a solid workpiece, a bored one, the chuck as its sweep and the probe on its measuring
// path; every field of every answer goes into one digest. A change of lathe-c1's geometry or
// of what the check answers (its tolerances, its bisection) changes the digest on purpose: pin
// the new one then, and say why in the commit.

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <random>
#include <string>

#include "sim/collision/spindle_sweep.hpp"
#include "sim/collision/straight_move_check.hpp"

namespace vmt::sim {
namespace {

/// FNV-1a over the text of every value, doubles as hexadecimal floats (every bit).
struct Digest {
  uint64_t h = 1469598103934665603ull;
  void Add(const std::string& s) {
    for (const char c : s) h = (h ^ static_cast<unsigned char>(c)) * 1099511628211ull;
  }
  void Add(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%a;", v);
    Add(std::string(buf));
  }
  void Add(int v) { Add(std::to_string(v) + ";"); }
  std::string Hex() const {
    char buf[20];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
    return buf;
  }
};

void AddCheck(Digest& d, const StraightMoveCheck& c) {
  d.Add(static_cast<int>(c.clear));
  d.Add(c.part_a), d.Add(c.part_b), d.Add(c.u);
  for (int i = 0; i < 3; ++i) d.Add(c.point[i]);
  for (const double q : c.q) d.Add(q);
  d.Add(c.min_clearance_m), d.Add(c.closest_a), d.Add(c.closest_b), d.Add(c.closest_u);
}

/// `moves` random moves on `world`; the number that ended in a contact in `contacts`.
void RandomMoves(CollisionWorld& world, uint64_t seed, int moves, Digest& d, int& contacts) {
  const MachineModel& m = world.model();
  const int z = m.JointIndex("z_carriage"), x = m.JointIndex("x_slide");
  const int t = m.JointIndex("turret"), w = m.JointIndex("tailstock");
  const int s = m.JointIndex("spindle");
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> zd(0.0, 0.65), xd(0.0, 0.3), xin(0.0, 0.06), wd(0.2, 0.7),
      unit(0, 1);
  for (int k = 0; k < moves; ++k) {
    std::vector<double> from(m.joints.size(), 0.0), to;
    from[w] = wd(rng), from[z] = zd(rng), from[x] = xd(rng);
    from[t] = (unit(rng) - 0.5) * 6, from[s] = (unit(rng) - 0.5) * 6;
    to = from;
    to[z] = zd(rng), to[x] = k % 2 ? xin(rng) : xd(rng);
    if (k % 3 == 0) to[t] = from[t] + (unit(rng) - 0.5) * 2;
    if (k % 5 == 0) to[w] = wd(rng);
    if (k % 7 == 0) to[s] = from[s] + (unit(rng) - 0.5) * 2;
    const StraightMoveCheck c = CheckStraightMove(world, from, to);
    contacts += !c.clear;
    AddCheck(d, c);
  }
}

TEST(StraightMoveResults, AreTheSameBitForBit) {
  const MachineModel model = LoadMachineModel(VMT_SOURCE_DIR "/models/lathe-c1/machine.yaml");
  Digest d;
  int contacts = 0;
  CollisionWorld world(model, {{"workpiece", "spindle", 0.030, 0.160, 0.060}});
  RandomMoves(world, 1, 120, d, contacts);
  // A bored workpiece (a mesh) and the chuck as the solid its jaws sweep.
  const SpindleSweep sweep = SweepOf(world, "spindle");
  std::vector<CylinderPart> added = {{"workpiece", "spindle", 0.040, 0.120, 0.060, 0.015}};
  added.insert(added.end(), sweep.swept.begin(), sweep.swept.end());
  world.SetAdded(added);
  for (const int p : sweep.parts) world.SetAside(p, true);
  RandomMoves(world, 2, 80, d, contacts);
  // The probe on its measuring path: its ruby may touch the workpiece.
  world.SetMeasuring(true);
  RandomMoves(world, 3, 60, d, contacts);
  const StraightMoveCheck start =
      CheckSpindleStart(world, std::vector<double>(model.joints.size(), 0.0), sweep.joint,
                        world.size() - static_cast<int>(sweep.swept.size()));
  AddCheck(d, start);
  // Both outcomes, many times over.
  EXPECT_GE(contacts, 40);
  EXPECT_LE(contacts, 220);
  EXPECT_EQ(d.Hex(), "7c4ebb2227660e4e");
}

}  // namespace
}  // namespace vmt::sim
