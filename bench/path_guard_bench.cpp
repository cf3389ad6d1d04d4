// PathGuard straight-move checks per second on lathe-c1's real collision geometry (all its
// <collision> meshes and a 60 x 160 mm workpiece): 200 random approach moves of carriage and
// cross slide from poses where nothing touches, the kind a REPOS study asks by the thousand.
// Counters: checks_per_s (the measure), queries_per_check (FCL distance + collision calls),
// contact_fraction.

#include <benchmark/benchmark.h>

#include <random>

#include "sim/collision/straight_move_check.hpp"

namespace {

using namespace vmt;

void BM_StraightMoveCheckLatheC1(benchmark::State& state) {
  const sim::MachineModel model =
      sim::LoadMachineModel(std::string(VMT_SOURCE_DIR) + "/models/lathe-c1/machine.yaml");
  sim::CollisionWorld world(model, {{"workpiece", "spindle", 0.030, 0.160, 0.060}});
  const int z = model.JointIndex("z_carriage"), x = model.JointIndex("x_slide");
  const int w = model.JointIndex("tailstock");
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> zd(0.0, 0.65), xd(0.0, 0.3);
  std::vector<double> from(model.joints.size(), 0.0);
  from[w] = 0.45;
  // Moves from poses where nothing touches (a move out of a contact is no approach move).
  auto touches = [&](const std::vector<double>& q) {
    world.Pose(q);
    for (int i = 0; i < world.size(); ++i)
      for (int k = i + 1; k < world.size(); ++k)
        if (!world.MayTouch(i, k) && world.Collide(i, k)) return true;
    return false;
  };
  std::vector<std::pair<std::vector<double>, std::vector<double>>> moves;
  while (moves.size() < 200) {
    std::vector<double> a = from, b = from;
    a[z] = zd(rng), a[x] = xd(rng), b[z] = zd(rng), b[x] = xd(rng);
    if (!touches(a)) moves.emplace_back(a, b);
  }
  int64_t checks = 0, contacts = 0;
  const int64_t queries_before = world.queries();
  for (auto _ : state) {
    const auto& [a, b] = moves[checks % moves.size()];
    const sim::StraightMoveCheck c = sim::CheckStraightMove(world, a, b);
    contacts += !c.clear;
    ++checks;
  }
  state.counters["checks_per_s"] =
      benchmark::Counter(static_cast<double>(checks), benchmark::Counter::kIsRate);
  state.counters["queries_per_check"] =
      static_cast<double>(world.queries() - queries_before) / static_cast<double>(checks);
  state.counters["contact_fraction"] = static_cast<double>(contacts) / static_cast<double>(checks);
  state.counters["parts"] = world.size();
}

BENCHMARK(BM_StraightMoveCheckLatheC1)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
