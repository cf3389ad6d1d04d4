// The parts a scene adds are replaced as the stock is turned; those that come again unchanged
// keep their solids and pairs. A world so updated must answer every query as one built afresh
// from the same parts, to the bit.

#include "sim/collision/collision_world.hpp"

#include <gtest/gtest.h>

#include "sim/model/model_error.hpp"

namespace vmt::sim {
namespace {

std::vector<double> Joints(const MachineModel& model, double step) {
  std::vector<double> q(model.joints.size(), 0.0);
  for (size_t j = 0; j < q.size(); ++j) q[j] = step * static_cast<double>(j % 5 + 1);
  return q;
}

// `machine`: how many parts the model has (the added ones follow them).
void ExpectSameAnswers(CollisionWorld& updated, CollisionWorld& fresh, const MachineModel& model,
                       int machine) {
  ASSERT_EQ(updated.size(), fresh.size());
  for (int i = 0; i < fresh.size(); ++i) {
    EXPECT_EQ(updated.part(i).name, fresh.part(i).name);
    EXPECT_EQ(updated.part(i).link, fresh.part(i).link);
    EXPECT_EQ(updated.part(i).radius, fresh.part(i).radius);
  }
  for (const double step : {0.0, 0.004, -0.013}) {
    updated.Pose(Joints(model, step));
    fresh.Pose(Joints(model, step));
    for (int a = 0; a < fresh.size(); ++a)
      for (int b = a + 1; b < fresh.size(); ++b) {
        ASSERT_EQ(updated.MayTouch(a, b), fresh.MayTouch(a, b))
            << fresh.part(a).name << " / " << fresh.part(b).name;
        if (b < machine) continue;  // the machine's own pairs are never rebuilt
        ASSERT_EQ(updated.Distance(a, b), fresh.Distance(a, b))
            << fresh.part(a).name << " / " << fresh.part(b).name << " at " << step;
        ASSERT_EQ(updated.Collide(a, b), fresh.Collide(a, b));
      }
  }
}

TEST(CollisionWorld, AddedPartsKeptOrBuiltAnewAnswerAsAFreshWorld) {
  const MachineModel model = LoadMachineModel(VMT_SOURCE_DIR "/models/lathe-c1/machine.yaml");
  const CylinderPart stock{"workpiece", "spindle", 0.03, 0.1, 0.06, 0};
  const CylinderPart step{"workpiece", "spindle", 0.025, 0.06, 0.16, 0};
  const CylinderPart bore{"workpiece", "spindle", 0.025, 0.02, 0.2, 0.01};
  const CylinderPart sweep{"chuck sweep", "spindle", 0.09, 0.04, 0.0, 0.035};
  const std::vector<std::vector<CylinderPart>> sequence = {
      {stock, step, sweep},
      {CylinderPart{"workpiece", "spindle", 0.029, 0.1, 0.06, 0}, step, sweep},  // one turned
      {sweep, step, bore, step},  // reordered, one gone, one new, one twice
      {},
      {stock, bore, sweep},
  };
  const int machine = CollisionWorld(model).size();
  CollisionWorld updated(model, sequence[0]);
  for (size_t k = 1; k < sequence.size(); ++k) {
    SCOPED_TRACE(k);
    updated.SetAdded(sequence[k]);
    CollisionWorld fresh(model, sequence[k]);
    ExpectSameAnswers(updated, fresh, model, machine);
  }
}

TEST(CollisionWorld, AnAddedPartOnAMissingLinkIsRefused) {
  const MachineModel model = LoadMachineModel(VMT_SOURCE_DIR "/models/lathe-c1/machine.yaml");
  CollisionWorld world(model, {{"workpiece", "spindle", 0.03, 0.1, 0.06, 0}});
  EXPECT_THROW(world.SetAdded({{"workpiece", "no such link", 0.03, 0.1, 0.06, 0}}), ModelError);
}

}  // namespace
}  // namespace vmt::sim
