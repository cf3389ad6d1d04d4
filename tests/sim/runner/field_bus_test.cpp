// The field bus on its own: every I/O point with a signal is on it except the operator's keys;
// the sensors go into their signals, the valve signals out to the machine's outputs.
#include "sim/runner/field_bus.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "../sim_test_support.hpp"

namespace vmt::sim {
namespace {

TEST(FieldBus, SensorsInValvesOutKeysStayThePanels) {
  const Scene scene = LoadScene(testing::SourcePath("scenes/default.yaml"));
  const MachineModel& m = *scene.model;
  ASSERT_TRUE(scene.nc.signals);
  control::gateway::SignalImage image(*scene.nc.signals);
  FieldBus bus;
  EXPECT_FALSE(bus.connected());
  bus.ConnectAll(m, image);
  EXPECT_TRUE(bus.connected());

  std::vector<double> before(m.io.size());
  for (size_t i = 0; i < m.io.size(); ++i)
    if (const int id = image.Find(m.io[i].name); id >= 0) before[i] = image.Number(id);
  control::AmplifierTelegram at;
  at.inputs.assign(m.io.size(), 1);
  bus.ReadInputs(at, image);
  control::MasterTelegram mdt;
  mdt.outputs.assign(m.io.size(), 0);
  int sensors = 0, valves = 0, keys = 0;
  for (size_t i = 0; i < m.io.size(); ++i) {
    const int id = image.Find(m.io[i].name);
    if (id < 0) continue;
    if (m.io[i].key) {
      EXPECT_EQ(image.Number(id), before[i]) << m.io[i].name;  // not the bus's
      ++keys;
    } else if (!m.io[i].is_output) {
      EXPECT_TRUE(image.Bool(id)) << m.io[i].name;
      ++sensors;
    } else {
      image.SetBool(id, true);
      ++valves;
    }
  }
  bus.WriteOutputs(image, mdt);
  for (size_t i = 0; i < m.io.size(); ++i) {
    if (m.io[i].is_output && !m.io[i].key && image.Find(m.io[i].name) >= 0) {
      EXPECT_EQ(mdt.outputs[i], 1) << m.io[i].name;
    }
  }
  EXPECT_GT(sensors, 0);
  EXPECT_GT(valves, 0);
  EXPECT_GT(keys, 0);
}

}  // namespace
}  // namespace vmt::sim
