// The station's JSON of a run: the model's links with their meshes and the workpiece, the
// machine keys and axes, a state with one pose per link, and the signals with what a page may
// write; where the tool in work cuts; PathGuard's refusal and a probe latch (with where the
// stylus touched the part) become marks.

#include "sim/station/station_frames.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "../sim_test_support.hpp"

namespace vmt::sim::station {
namespace {

using Json = nlohmann::json;
using testing::SourcePath;

TEST(StationFramesTest, ModelStateAndSignalsOfARun) {
  const Scene scene = LoadScene(SourcePath("scenes/machine-panel.yaml"));
  RunOptions options;
  options.until_s = 0.2;
  SceneRun run(scene, options);
  while (!run.done()) run.Step();

  const Json model = Json::parse(ModelJson(run, "lockstep"));
  EXPECT_EQ(model["scene"], "machine-panel");
  ASSERT_EQ(model["links"].size(), scene.model->links.size());
  size_t triangles = 0;
  bool workpiece = false;
  for (const Json& link : model["links"])
    for (const Json& v : link["visuals"]) {
      ASSERT_EQ(v["positions"].size() % 3, 0u);
      ASSERT_EQ(v["indices"].size() % 3, 0u);
      triangles += v["indices"].size() / 3;
      workpiece = workpiece || v["name"] == "workpiece";
    }
  EXPECT_GT(triangles, 1000u);
  EXPECT_TRUE(workpiece);
  EXPECT_NE(std::find(model["keys"].begin(), model["keys"].end(), "mJGPOS_X"), model["keys"].end());
  EXPECT_EQ(model["axes"][0]["name"], "X");
  EXPECT_FALSE(model["program"]["lines"].empty());
  EXPECT_FALSE(model["cameras"].empty());

  const Json state = Json::parse(StateJson(run, 12, "paused", 7, StationMarks{}));
  EXPECT_EQ(state["run"], "paused");
  EXPECT_EQ(state["cycle"], 12);
  EXPECT_EQ(state["events"], 7);
  EXPECT_EQ(state["poses"].size(), scene.model->links.size());
  EXPECT_EQ(state["poses"][0].size(), 7u);
  EXPECT_EQ(state["nc"]["mode"], "automatic");
  EXPECT_TRUE(state["guard"].is_null());
  ASSERT_EQ(state["axes"].size(), model["axes"].size());
  EXPECT_EQ(state["repos"]["function"], "none");  // the REPOS screen, nothing called
  EXPECT_EQ(state["headstock"]["mode"], "spindle");
  EXPECT_TRUE(state["headstock"]["signals"].contains("A03.ROTMOD_Q"));
  EXPECT_EQ(state["block_search"]["state"], "HLI_BS_INACTIVE");

  // The workpiece as turned: not cut yet at 0.2 s, the stock cylinder whole.
  const Json stock = Json::parse(StockJson(run));
  EXPECT_EQ(stock["link"], "spindle");
  ASSERT_EQ(stock["cylinders"].size(), 1u);
  EXPECT_NEAR(stock["cylinders"][0][2].get<double>(), 0.030, 1e-9);  // 60 mm diameter
  EXPECT_EQ(state["stock"], stock["version"]);

  const Json signals = Json::parse(SignalsJson(run));
  bool key_writable = false, status_writable = true;
  for (const Json& s : signals["signals"]) {
    if (s["name"] == "mSTART") key_writable = s["writable"];
    if (s["name"] == "P00S.RUN") status_writable = s["writable"];
  }
  EXPECT_TRUE(key_writable);
  EXPECT_FALSE(status_writable);
}

// lathe-c1 holds every tool's tip on the turret's tool-tip plane, 60 mm ahead of the Z
// carriage, and X is the tip's radius (models/lathe-c1/README.md, turret stations).
TEST(StationFramesTest, ToolTipIsTheCuttingCornerOfTheToolInWork) {
  const Scene scene = LoadScene(SourcePath("scenes/machine-panel.yaml"));
  RunOptions options;
  options.until_s = 0.1;
  SceneRun run(scene, options);
  while (!run.done()) run.Step();
  const Json state = Json::parse(StateJson(run, 0, "paused", 0, StationMarks{}));
  ASSERT_TRUE(state["tool_tip"].is_array());
  const double x_mm = state["axes"][0]["machine"], z_mm = state["axes"][1]["machine"];
  EXPECT_NEAR(state["tool_tip"][0].get<double>(), x_mm / 1000, 1e-6);
  EXPECT_NEAR(state["tool_tip"][1].get<double>(), 0.0, 1e-6);
  EXPECT_NEAR(state["tool_tip"][2].get<double>(), (z_mm + 60) / 1000, 1e-6);
}

TEST(StationFramesTest, NoToolTipWhileTheProbeFacesTheSpindle) {
  const Scene scene = LoadScene(SourcePath("scenes/measure-shaft.yaml"));  // turret at T3
  RunOptions options;
  options.until_s = 0.01;
  SceneRun run(scene, options);
  while (!run.done()) run.Step();
  EXPECT_TRUE(Json::parse(StateJson(run, 0, "paused", 0, StationMarks{}))["tool_tip"].is_null());
}

// The first contact of measure-shaft: the ruby meets the d60 master, and both measuring axes
// latch at that edge.
TEST(StationFramesTest, ProbeLatchCarriesWhereTheStylusTouched) {
  const Scene scene = LoadScene(SourcePath("scenes/measure-shaft.yaml"));
  StationMarks marks;
  RunOptions options;
  options.until_s = 1.2;
  options.on_event = [&marks](const nlohmann::ordered_json& e) { marks.Note(e); };
  SceneRun run(scene, options);
  while (!run.done()) run.Step();
  const Json probe = Json::parse(StateJson(run, 0, "paused", 0, marks))["probe"];
  ASSERT_TRUE(probe.is_object());
  ASSERT_TRUE(probe["point"].is_array());
  const double r = std::hypot(probe["point"][0].get<double>(), probe["point"][1].get<double>());
  EXPECT_NEAR(r, 0.030, 1e-6);  // on the master's surface
  const double z = probe["point"][2];
  EXPECT_TRUE(z > 0.060 && z < 0.190) << z;  // on the d60, between the chuck and the shoulder
  ASSERT_EQ(probe["latches"].size(), 2u);
  EXPECT_EQ(probe["latches"][0]["t"], probe["latches"][1]["t"]);
}

// The probe card's switches and the measuring pages as MTD( ) reads them: SETTING and the
// stylus page set by the program, the basis page's page numbers as installed.
TEST(StationFramesTest, ProbeSwitchesAndMeasuringPages) {
  const Scene scene = LoadScene(SourcePath("scenes/measure-shaft.yaml"));
  RunOptions options;
  options.until_s = 1.2;
  SceneRun run(scene, options);
  while (!run.done()) run.Step();
  const Json state = Json::parse(StateJson(run, 0, "paused", 0, StationMarks{}));
  const Json& switches = state["probe_switches"];
  ASSERT_EQ(switches.size(), 2u);
  EXPECT_EQ(switches[0]["pin"], "PIN4");
  EXPECT_EQ(switches[0]["contact"], "IPROBE_CONTACT");
  EXPECT_EQ(switches[0]["ready_input"], "IPROBE_READY");
  EXPECT_TRUE(switches[0]["ready"].is_boolean());
  const Json& pages = state["measuring_pages"];
  ASSERT_EQ(pages.size(), 6u);
  EXPECT_EQ(pages[0]["name"], "BASISMESSPAGE");
  EXPECT_EQ(pages[0]["number"], 90);
  ASSERT_EQ(pages[0]["rows"].size(), 1u);  // process 0
  ASSERT_EQ(pages[0]["elements"].size(), 10u);
  EXPECT_EQ(pages[0]["rows"][0]["values"][0], 101);  // ZWISCHENSPEICHERPAGE's number
  EXPECT_EQ(pages[2]["name"], "TASTWERKZEUGPAGE");
  EXPECT_FALSE(pages[2]["rows"].empty());  // the styluses the scene sets up
  EXPECT_EQ(pages[4]["name"], "POINTPAGE");
}

TEST(StationFramesTest, MarksFollowTheEvents) {
  StationMarks marks;
  marks.Note({{"event", "path_guard"}, {"clear", true}});
  EXPECT_TRUE(marks.guard.empty());
  marks.Note({{"event", "path_guard"},
              {"clear", false},
              {"move", "G77"},
              {"parts", {"turret_st01_insert", "spindle_jaw1"}},
              {"point", {85.9, 0, 137.7}}});
  const Json guard = Json::parse(marks.guard);
  EXPECT_EQ(guard["parts"][1], "spindle_jaw1");
  EXPECT_DOUBLE_EQ(guard["point"][0].get<double>(), 0.0859);  // metres
  marks.Note({{"event", "probe_latch"}, {"drive", "X"}, {"measured_value", 29.99}, {"t", 1.2}});
  EXPECT_EQ(Json::parse(marks.probe)["drive"], "X");
  for (int i = 0; i < 20; ++i)
    marks.Note({{"event", "probe_latch"}, {"drive", "Z"}, {"measured_value", i}, {"t", 2.0 + i}});
  ASSERT_EQ(marks.latches.size(), StationMarks::kLatchesKept);  // the last few
  EXPECT_EQ(Json::parse(marks.latches.back())["value"], 19);
  marks.Note({{"event", "clutch"}, {"name", "K"}, {"state", "blocked"}});
  EXPECT_EQ(marks.clutches.at("K"), "blocked");
  marks.Note({{"event", "nc"}, {"state", "idle"}});  // Control-Reset
  EXPECT_TRUE(marks.guard.empty());
}

}  // namespace
}  // namespace vmt::sim::station
