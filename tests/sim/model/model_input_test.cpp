// Bad machine, URDF and scene files give an error naming the file and the YAML path (or URDF
// element) -- never a crash.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "../sim_test_support.hpp"
#include "sim/model/model_error.hpp"
#include "sim/scene/scene.hpp"

namespace vmt::sim {
namespace {

using ::testing::HasSubstr;
using testing::OutputDir;
using testing::SourcePath;

std::string Write(const std::string& dir, const std::string& name, const std::string& text) {
  const std::string path = dir + "/" + name;
  std::ofstream(path) << text;
  return path;
}

// lathe-c1's machine.yaml with `edit` applied, in a scratch folder; with `urdf_edit`, a copy of
// machine.urdf (and its meshes) with that edit beside it. Returns the error message of loading
// it ("" if it loads).
std::string LoadEdited(const std::string& name, const std::function<std::string(std::string)>& edit,
                       const std::function<std::string(std::string)>& urdf_edit = {}) {
  const std::string dir = OutputDir("bad_models/" + name);
  std::string yaml_text = testing::ReadBytes(SourcePath("models/lathe-c1/machine.yaml"));
  if (urdf_edit) {
    std::filesystem::remove_all(dir + "/meshes");
    std::filesystem::copy(SourcePath("models/lathe-c1/meshes"), dir + "/meshes");
    Write(dir, "machine.urdf",
          urdf_edit(testing::ReadBytes(SourcePath("models/lathe-c1/machine.urdf"))));
  } else {
    // A machine.yaml edit leaves the URDF and meshes where they are: their paths are the
    // process' mesh cache keys, so the cases after the first do not parse the meshes again
    // (under the sanitizers that took most of a minute per test). Same line, so line numbers in
    // the messages are those of the edited file.
    yaml_text = testing::ReplaceOnce(yaml_text, "urdf: machine.urdf",
                                     "urdf: " + SourcePath("models/lathe-c1/machine.urdf"));
  }
  const std::string yaml = Write(dir, "machine.yaml", edit(yaml_text));
  try {
    LoadMachineModel(yaml);
  } catch (const ModelError& e) {
    return e.what();
  }
  return "";
}

std::string Replace(std::string s, const std::string& from, const std::string& to) {
  const size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << "fixture text not found: " << from;
  if (at != std::string::npos) s.replace(at, from.size(), to);
  return s;
}

TEST(ModelInputTest, TheLatheLoads) {
  const MachineModel& m = testing::Lathe();
  EXPECT_EQ(m.name, "lathe-c1");
  EXPECT_EQ(m.drives.size(), 7u);
  EXPECT_GE(m.links.size(), 10u);
  EXPECT_EQ(m.clutches.size(), 1u);
  for (const Link& l : m.links)
    for (const Visual& v : l.visuals) EXPECT_FALSE(v.mesh->indices.empty()) << v.mesh_file;
}

TEST(ModelInputTest, WrongTypeNamesFileLineAndPath) {
  const std::string e = LoadEdited("wrong_type", [](std::string s) {
    return Replace(s, "    kv: 40                  # position loop gain, 1/s (2.4 (m/min)/mm)",
                   "    kv: fast");
  });
  EXPECT_THAT(e, HasSubstr("machine.yaml:"));
  EXPECT_THAT(e, HasSubstr("drives[0].kv"));
  EXPECT_THAT(e, HasSubstr("expected a number, got \"fast\""));
}

TEST(ModelInputTest, MissingKey) {
  const std::string e = LoadEdited(
      "missing_key", [](std::string s) { return Replace(s, "    torque_limit: 7000\n", ""); });
  EXPECT_THAT(e, HasSubstr("drives[1]"));
  EXPECT_THAT(e, HasSubstr("missing required key 'torque_limit'"));
}

TEST(ModelInputTest, ActuatorErrorsNameTheirPath) {
  struct Case {
    const char* name;
    const char* from;
    const char* to;
    const char* path;
    const char* message;
  };
  const Case cases[] = {
      {"actuator_valve_is_input", "valve: QTAILSTOCK,", "valve: ITAILSTOCK_FWD,",
       "actuators[0].valve", "must be an output"},
      {"actuator_unknown_switch", "on_switch: ICOOLANT_PRESSURE", "on_switch: IPUMP",
       "actuators[2].on_switch", "no I/O point 'IPUMP'"},
      {"actuator_zero_time", "time_on: 0.4", "time_on: 0", "actuators[2].time_on", "must be > 0"},
      {"actuator_unknown_drive", "holds: T,", "holds: Q,", "actuators[1].holds",
       "no drive named 'Q'"},
      {"actuator_shared_switch", "on_switch: IPROBE_READY", "on_switch: IDOOR_OPEN", "io",
       "'IDOOR_OPEN' is the switch of more than one device"},
      {"position_switch_window", "pitch: 30, window: 0.05", "pitch: 30, window: 15",
       "position_switches[0].window", "must be in (0, pitch/2)"},
      {"position_switch_drive", "drive: T, pitch", "drive: TT, pitch", "position_switches[0].drive",
       "no drive named 'TT'"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string e =
        LoadEdited(c.name, [&](std::string s) { return Replace(s, c.from, c.to); });
    EXPECT_THAT(e, HasSubstr(c.path));
    EXPECT_THAT(e, HasSubstr(c.message));
  }
}

// Drive keys of parameter sets, the load-side encoder and the overload time.
TEST(ModelInputTest, DriveKeyErrorsNameTheirPath) {
  struct Case {
    const char* name;
    const char* insert;  // after Z's following_error_limit
    const char* path;
    const char* message;
  };
  const Case cases[] = {
      {"set_unknown_key", "    parameter_sets:\n      - {kv: 10, kvv: 3}\n",
       "drives[0].parameter_sets[0].kvv", "unknown key 'kvv'"},
      {"set_negative", "    parameter_sets:\n      - {kv: -1}\n", "drives[0].parameter_sets[0].kv",
       "must be > 0"},
      {"set_type", "    parameter_sets:\n      - {type: stepper}\n",
       "drives[0].parameter_sets[0].type", "expected servo or spindle"},
      {"set_too_many", "    parameter_sets: [{}, {}, {}, {}, {}, {}, {}, {}]\n",
       "drives[0].parameter_sets", "at most 7 entries"},
      {"set_not_a_map", "    parameter_sets: [10]\n", "drives[0].parameter_sets[0]",
       "expected a map"},
      {"sets_not_a_list", "    parameter_sets: {kv: 10}\n", "drives[0].parameter_sets",
       "expected a list"},
      {"encoder_kind", "    encoder: rotor\n", "drives[0].encoder", "expected motor or load"},
      {"encoder_no_joint", "    encoder: load\n", "drives[0]", "missing required key 'load_joint'"},
      {"encoder_unknown_joint", "    encoder: load\n    load_joint: spindel\n",
       "drives[0].load_joint", "no joint 'spindel'"},
      {"encoder_joint_kind", "    encoder: load\n    load_joint: spindle\n", "drives[0].load_joint",
       "joint type does not match the drive's kind"},
      {"encoder_motor_joint", "    encoder: load\n    load_joint: z_carriage\n",
       "drives[0].load_joint", "is the motor joint"},
      {"load_joint_alone", "    load_joint: tailstock\n", "drives[0].load_joint",
       "only a drive with encoder: load has a load_joint"},
      {"overload_time", "    overload_time: 0\n", "drives[0].overload_time", "must be > 0"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string at = "    following_error_limit: 20  # mm\n";
    const std::string e =
        LoadEdited(c.name, [&](std::string s) { return Replace(s, at, at + c.insert); });
    EXPECT_THAT(e, HasSubstr("machine.yaml:"));
    EXPECT_THAT(e, HasSubstr(c.path));
    EXPECT_THAT(e, HasSubstr(c.message));
  }
}

// The main spindle's parameters of manual mode and status indication, and the encoders' limit
// frequency (C-axis manual 2.2, 2.3, 3.3, 4.2) in `nc: spindle:` and on an axis.
TEST(ModelInputTest, SpindleAndEncoderParametersAreRead) {
  const MachineModel& m = testing::Lathe();
  EXPECT_DOUBLE_EQ(m.nc.spindle.jog_per_s, 600);  // jogging_speed 100 rpm, in deg/s
  EXPECT_EQ(m.nc.path_guard, control::GuardReaction::kStop);
  EXPECT_DOUBLE_EQ(m.nc.spindle.jog_spindle_position, 45);
  EXPECT_DOUBLE_EQ(m.nc.spindle.max_spindle_rpm, 4000);  // Cxx.049
  EXPECT_DOUBLE_EQ(m.nc.spindle.encoder_periods_per_rev, 375);
  EXPECT_DOUBLE_EQ(m.nc.spindle.encoder_limit_hz, 150000);
  // 150 kHz / 375 = 400 rev/s: the gear-type encoder's 24000 rpm (3.3).
  EXPECT_DOUBLE_EQ(m.nc.spindle.encoder_limit_hz / m.nc.spindle.encoder_periods_per_rev * 60,
                   24000);
  const control::axes::AxisParameters& c = m.nc.axes[m.nc.rotary_axis];
  EXPECT_DOUBLE_EQ(c.encoder_periods_per_rev, 2048);
  EXPECT_DOUBLE_EQ(c.encoder_limit_hz, 150000);
  // C's encoder outruns S1 (4000 rpm) as 3.3's note asks: 150 kHz / 2048 = 4394 rpm.
  EXPECT_GT(c.encoder_limit_hz / c.encoder_periods_per_rev * 60, 4000);
}

TEST(ModelInputTest, SpindleAndEncoderParameterErrorsNameTheirPath) {
  struct Case {
    const char* name;
    const char* from;
    const char* to;
    const char* path;
    const char* message;
  };
  const Case cases[] = {
      {"jog_speed_negative", "jogging_speed: 100,", "jogging_speed: -5,",
       "nc.spindle.jogging_speed", "must be > 0 (rpm)"},
      {"jog_speed_too_fast", "jogging_speed: 100,", "jogging_speed: 5000,",
       "nc.spindle.jogging_speed", "faster than drive S1's velocity_limit"},
      {"jog_speed_misspelt", "jogging_speed: 100,", "jog_speed: 100,", "nc.spindle.jog_speed",
       "unknown key 'jog_speed'"},
      {"jog_position", "jogging_spindle_position: 45,", "jogging_spindle_position: 360,",
       "nc.spindle.jogging_spindle_position", "must be in [0, 360) deg"},
      {"max_speed", "Cxx.049: 4000,", "Cxx.049: 4500,", "nc.spindle.Cxx.049",
       "faster than drive S1's velocity_limit"},
      {"encoder_half", "encoder_periods_per_rev: 375, encoder_limit_hz: 150000}",
       "encoder_periods_per_rev: 375}", "nc.spindle.encoder_periods_per_rev",
       "needs encoder_periods_per_rev and encoder_limit_hz together"},
      {"encoder_limit_zero", "encoder_limit_hz: 150000}", "encoder_limit_hz: 0}",
       "nc.spindle.encoder_limit_hz", "must be > 0"},
      {"axis_encoder", "      encoder_limit_hz: 150000\n  zero_offsets",
       "      encoder_limit_hz: -1\n  zero_offsets", "nc.axes[2].encoder_limit_hz", "must be > 0"},
      {"axis_encoder_half", "      encoder_periods_per_rev: 2048\n", "",
       "nc.axes[2].encoder_limit_hz", "needs encoder_periods_per_rev and encoder_limit_hz"},
      {"path_guard", "path_guard: stop", "path_guard: maybe", "nc.path_guard",
       "expected stop, warn or off"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string e =
        LoadEdited(c.name, [&](std::string s) { return Replace(s, c.from, c.to); });
    EXPECT_THAT(e, HasSubstr("machine.yaml:"));
    EXPECT_THAT(e, HasSubstr(c.path));
    EXPECT_THAT(e, HasSubstr(c.message));
  }
}

TEST(ModelInputTest, UnknownKeyIsNotIgnored) {
  const std::string e = LoadEdited("unknown_key", [](std::string s) {
    return Replace(s, "    teeth: 24", "    teeth: 24\n    teath: 25");
  });
  EXPECT_THAT(e, HasSubstr("couplings[1].teath"));
  EXPECT_THAT(e, HasSubstr("unknown key 'teath'"));
}

TEST(ModelInputTest, UnknownJointAndIo) {
  EXPECT_THAT(
      LoadEdited("unknown_joint",
                 [](std::string s) { return Replace(s, "joint: x_slide", "joint: y_slide"); }),
      HasSubstr("drives[1].joint: no joint 'y_slide'"));
  EXPECT_THAT(LoadEdited("unknown_io",
                         [](std::string s) {
                           return Replace(s, "valve_engage: QROTMODE", "valve_engage: QROTMOD");
                         }),
              HasSubstr("couplings[1].valve_engage: no I/O point 'QROTMOD'"));
  EXPECT_THAT(LoadEdited("io_direction",
                         [](std::string s) {
                           return Replace(s, "sensor_engaged: IROTMODE", "sensor_engaged: QSPMODE");
                         }),
              HasSubstr("must be an input"));
}

// A selector (an override switch of the panel) is an operator's input with positions.
TEST(ModelInputTest, SelectorsAreReadAndChecked) {
  const MachineModel m = LoadMachineModel(SourcePath("models/lathe-c1/machine.yaml"));
  const int fovr = control::IndexOf(m.io, "mFOVR");
  ASSERT_GE(fovr, 0);
  EXPECT_TRUE(m.io[fovr].key);
  EXPECT_TRUE(m.io[fovr].selector());
  EXPECT_EQ(m.io[fovr].initial, 100);
  EXPECT_EQ(m.io[fovr].positions.front(), 0);
  EXPECT_EQ(m.io[fovr].positions.back(), 120);
  EXPECT_TRUE(m.io[fovr].PositionOk(75));
  EXPECT_FALSE(m.io[fovr].PositionOk(77));
  const std::string fovr_line = "  - {name: mFOVR, dir: selector, initial: 100,";
  EXPECT_THAT(LoadEdited("selector_initial",
                         [&](std::string s) {
                           return Replace(s, fovr_line,
                                          "  - {name: mFOVR, dir: selector, initial: 77,");
                         }),
              HasSubstr("initial: expected one of the positions"));
  EXPECT_THAT(LoadEdited("selector_order",
                         [](std::string s) {
                           return Replace(s, "positions: [0, 1, 2,", "positions: [0, 2, 1,");
                         }),
              HasSubstr("expected the positions in increasing order"));
  EXPECT_THAT(LoadEdited("selector_no_positions",
                         [&](std::string s) {
                           return Replace(s, fovr_line,
                                          "  - {name: mFOVRX, dir: selector}\n" + fovr_line);
                         }),
              HasSubstr("io[47]: missing required key 'positions'"));
  EXPECT_THAT(LoadEdited("key_with_positions",
                         [](std::string s) {
                           return Replace(s, "{name: mSBL, dir: key}",
                                          "{name: mSBL, dir: key, positions: [0, 1]}");
                         }),
              HasSubstr("only a selector (dir: selector) has it"));
}

TEST(ModelInputTest, YamlSyntaxErrorHasLineAndColumn) {
  const std::string e = LoadEdited("syntax", [](std::string s) {
    return Replace(s, "machine: lathe-c1", "machine: [lathe-c1");
  });
  EXPECT_THAT(e, ::testing::ContainsRegex("machine\\.yaml:[0-9]+:[0-9]+: .*YAML syntax error"));
}

TEST(ModelInputTest, BrokenUrdf) {
  const std::string e = LoadEdited(
      "broken_urdf", [](std::string s) { return s; },
      [](std::string u) { return u.substr(0, u.size() / 2); });
  EXPECT_THAT(e, HasSubstr("machine.urdf"));
  EXPECT_THAT(e, HasSubstr("invalid URDF"));
}

TEST(ModelInputTest, MissingMeshNamesTheLink) {
  const std::string e = LoadEdited(
      "missing_mesh", [](std::string s) { return s; },
      [](std::string u) {
        return Replace(u, "meshes/spindle_chuck_body.ply", "meshes/no_such_mesh.ply");
      });
  EXPECT_THAT(e, HasSubstr("machine.urdf"));
  EXPECT_THAT(e, HasSubstr("<link name=\"spindle\">"));
  EXPECT_THAT(e, HasSubstr("no_such_mesh.ply"));
}

TEST(ModelInputTest, MissingFile) {
  try {
    LoadMachineModel("/nonexistent/machine.yaml");
    FAIL();
  } catch (const ModelError& e) {
    EXPECT_THAT(e.what(), HasSubstr("/nonexistent/machine.yaml: cannot open file"));
  }
}

std::string SceneError(const std::string& name, const std::string& body) {
  return testing::SceneLoadError(testing::WriteLatheScene("bad_scenes", name, body));
}

TEST(SceneInputTest, GoodSceneLoads) {
  EXPECT_EQ(SceneError("good", "duration: 1\ntimeline:\n  - move: {axis: Z, to: 10, feed: 1000}\n"),
            "");
}

TEST(SceneInputTest, Errors) {
  EXPECT_THAT(SceneError("no_duration", "timeline: []\n"),
              HasSubstr("missing required key 'duration'"));
  EXPECT_THAT(
      SceneError("bad_axis", "duration: 1\ntimeline:\n  - move: {axis: Q, to: 1, feed: 10}\n"),
      HasSubstr("timeline[0].move.axis: no axis 'Q'"));
  EXPECT_THAT(SceneError("two_actions", "duration: 1\ntimeline:\n  - {wait: 1, off: {axis: Z}}\n"),
              HasSubstr("timeline[0]: a step needs exactly one of"));
  EXPECT_THAT(
      SceneError("bad_feed", "duration: 1\ntimeline:\n  - move: {axis: Z, to: 1, feed: -5}\n"),
      HasSubstr("timeline[0].move.feed: must be > 0"));
  EXPECT_THAT(
      SceneError("bad_parameter_set",
                 "duration: 1\ntimeline:\n  - speed: {axis: S1, rpm: 10, parameter_set: 8}\n"),
      HasSubstr("timeline[0].speed.parameter_set: expected 0..7"));
  EXPECT_THAT(SceneError("bad_camera", "duration: 1\nsnapshots:\n  - {at: 0, camera: nope}\n"),
              HasSubstr("snapshots[0].camera: no camera 'nope'"));
  EXPECT_THAT(SceneError("bad_backend", "duration: 1\nbackend: quantum\n"),
              HasSubstr("backend: expected physics or kinematic"));
  EXPECT_THAT(SceneError("bad_expect", "duration: 1\nexpect:\n  - {axis: Z, position: 1}\n"),
              HasSubstr("expect[0]: missing required key 'tol'"));
  EXPECT_THAT(
      SceneError("bad_file", "duration: 1\nsnapshots:\n  - {at: 0, camera: iso, file: ../x.png}\n"),
      HasSubstr("snapshots[0].file"));
  EXPECT_THAT(SceneError("not_a_map", "duration: [1, 2]\n"),
              HasSubstr("duration: expected a number"));
  EXPECT_THAT(SceneError("bad_initial", "duration: 1\ninitial: {Q: 3}\n"),
              HasSubstr("initial.Q: no axis 'Q'"));
  EXPECT_THAT(SceneError("beyond_travel",
                         "duration: 1\ntimeline:\n  - move: {axis: X, to: 400, feed: 10}\n"),
              HasSubstr("timeline[0].move.to: 400 is beyond the travel of X (0 .. 300)"));
  EXPECT_THAT(SceneError("initial_travel", "duration: 1\ninitial: {Z: -5}\n"),
              HasSubstr("initial.Z: -5 is beyond the travel of Z (0 .. 650)"));
  EXPECT_THAT(
      SceneError("fault_valve_is_sensor",
                 "duration: 1\ntimeline:\n  - fault: {valve: IROTMODE, stuck: true}\n"),
      HasSubstr("timeline[0].fault.valve: no machine valve (io dir: out) called 'IROTMODE'"));
  EXPECT_THAT(SceneError("fault_plc", "duration: 1\ntimeline:\n  - fault: {plc: crash}\n"),
              HasSubstr("timeline[0].fault.plc: expected overrun or client_gone"));
  EXPECT_THAT(SceneError("fault_client_gone_cycles",
                         "duration: 1\ntimeline:\n  - fault: {plc: client_gone, cycles: 3}\n"),
              HasSubstr("timeline[0].fault.cycles: unknown key 'cycles' (expected one of: plc)"));
  EXPECT_THAT(SceneError("fault_empty", "duration: 1\ntimeline:\n  - fault: {stuck: true}\n"),
              HasSubstr("timeline[0].fault: expected sensor, valve, drive, plc or clear"));
  EXPECT_THAT(SceneError("plc_without_nc", "duration: 1\nplc: {program: repos_machine_keys}\n"),
              HasSubstr("plc: a PLC program needs the nc: section"));
  EXPECT_THAT(SceneError("plc_unknown",
                         "duration: 1\nnc: {program: " + SourcePath("scenes/nc/stepped_shaft.mtc") +
                             "}\nplc: {program: nope}\n"),
              HasSubstr("plc.program: no PLC program 'nope' (there are: repos_machine_keys"));
  EXPECT_THAT(SceneError("plc_period",
                         "duration: 1\nnc: {program: " + SourcePath("scenes/nc/stepped_shaft.mtc") +
                             "}\nplc: {program: repos_machine_keys, period_ms: 0.3}\n"),
              HasSubstr("plc.period_ms: must be a multiple of the 0.25 ms drive tick"));
  const std::string two_programs =
      "duration: 1\nnc: {program: " + SourcePath("scenes/nc/stepped_shaft.mtc") +
      ", subprograms: [" + SourcePath("scenes/nc/99.mtc") + "]}\n";
  EXPECT_EQ(SceneError("select", two_programs + "timeline:\n  - nc: {select: 99}\n"), "");
  EXPECT_EQ(SceneError("select_file", two_programs + "timeline:\n  - nc: {select: 99.mtc}\n"), "");
  EXPECT_THAT(SceneError("program_is_a_directory",
                         "duration: 1\nnc: {program: " + SourcePath("scenes/nc") + "}\n"),
              HasSubstr("nc.program: cannot open NC program"));
  EXPECT_THAT(SceneError("select_none", two_programs + "timeline:\n  - nc: {select: 98}\n"),
              HasSubstr("timeline[0].nc.select: is none of the scene's NC programs"));
}

TEST(SceneInputTest, GarbageNeverCrashes) {
  // Arbitrary byte soup and YAML of the wrong shape: always a ModelError, never anything else.
  const char* inputs[] = {"",
                          "- 1\n- 2\n",
                          "scene: [",
                          "\x01\x02\xff\xfe",
                          "scene: x\nmodel: {a: 1}\n",
                          "{{{{",
                          "scene: x\nmodel: 42\nduration: 1\n"};
  int i = 0;
  for (const char* text : inputs) {
    const std::string path = Write(OutputDir("garbage"), "g" + std::to_string(i++) + ".yaml", text);
    EXPECT_THROW(LoadScene(path), ModelError) << text;
  }
}

}  // namespace
}  // namespace vmt::sim
