// LoadScene: a scene file (docs/scene-format.md) with its model, workpiece, initial state, NC,
// PLC, cameras and snapshots; timeline steps and expectations are scene_steps.cpp's.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/input_file.hpp"
#include "common/mapped_file.hpp"
#include "control/nc/modal_g_codes.hpp"
#include "control/nc/parser.hpp"
#include "control/plc/plc_programs.hpp"
#include "sim/model/gateway_layout.hpp"
#include "sim/model/model_error.hpp"
#include "sim/model/nc_machine_data.hpp"
#include "sim/model/yaml_reader.hpp"
#include "sim/scene/measuring_pages_loader.hpp"
#include "sim/scene/nc_channel_config.hpp"
#include "sim/scene/scene.hpp"
#include "sim/scene/scene_steps.hpp"
#include "sim/scene/snapshot_loader.hpp"
#include "sim/scene/workpiece_loader.hpp"

namespace vmt::sim {

const NamedCamera* Scene::Camera(const std::string& name) const {
  for (const NamedCamera& c : cameras)
    if (c.name == name) return &c;
  return nullptr;
}

namespace {

ProbeSamplingPhase ReadProbeSampling(const YamlNode& probe) {
  ProbeSamplingPhase sampling;
  if (!probe.IsMap()) probe.Fail("expected a map: {sampling_phase: fixed | seeded, seed: N}");
  probe.AllowKeys({"sampling_phase", "seed"});
  const std::string phase = probe.String("sampling_phase", "fixed");
  if (phase == "seeded")
    sampling.seeded = true;
  else if (phase != "fixed")
    probe["sampling_phase"].Fail("expected fixed or seeded, got \"" + phase + "\"");
  if (probe.Has("seed")) {
    if (!sampling.seeded) probe["seed"].Fail("a seed needs sampling_phase: seeded");
    const double seed = probe["seed"].Double(0, 4294967295.0);
    if (seed < 0 || seed > 4294967295.0 || seed != std::floor(seed))
      probe["seed"].Fail("expected a whole number 0..4294967295");
    sampling.seed = static_cast<uint64_t>(seed);
  }
  return sampling;
}

InitialState ReadInitialState(const YamlNode& init, const MachineModel& m) {
  InitialState initial;
  for (const std::string& key : init.Keys()) {
    if (key == "clutch") {
      const YamlNode cl = init["clutch"];
      for (const std::string& name : cl.Keys()) {
        bool found = false;
        for (const DogClutch& k : m.clutches) found = found || k.name == name;
        if (!found) cl[name].Fail("no clutch '" + name + "'");
        const std::string state = cl[name].String();
        if (state != "engaged" && state != "released")
          cl[name].Fail("expected engaged or released");
        initial.clutch_engaged[name] = state == "engaged";
      }
    } else {
      const int d = RequireDrive(m, init.KeyNode(key));
      initial.drive_positions[key] = init[key].Double();
      RequireWithinTravel(m, d, init[key].Double(), init[key]);
    }
  }
  return initial;
}

/// The model's cameras, each one the scene names replaced or added.
std::vector<NamedCamera> ReadCameras(const YamlNode& cams, const MachineModel& m) {
  std::vector<NamedCamera> cameras = m.cameras;
  for (const std::string& name : cams.Keys()) {
    NamedCamera cam = ReadCamera(name, cams[name]);
    bool replaced = false;
    for (NamedCamera& c : cameras)
      if (c.name == name) c = cam, replaced = true;
    if (!replaced) cameras.push_back(cam);
  }
  return cameras;
}

/// The embedded PLC: a program of the manuals, scanned against the gateway signals of `nc`.
PlcSetup ReadPlc(const YamlNode& plc, const NcSetup& nc) {
  PlcSetup plc_setup;
  plc.AllowKeys({"program", "period_ms", "constants"});
  if (!nc.present) plc.Fail("a PLC program needs the nc: section (the gateway signals)");
  plc_setup.present = true;
  plc_setup.program = plc["program"].String();
  const auto names = control::plc::PlcProgramNames();
  if (std::find(names.begin(), names.end(), plc_setup.program) == names.end()) {
    std::string list;
    for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
    plc["program"].Fail("no PLC program '" + plc_setup.program + "' (there are: " + list + ")");
  }
  if (plc.Has("constants")) {
    const YamlNode constants = plc["constants"];
    for (const std::string& name : constants.Keys()) {
      int id = -1;
      for (size_t i = 0; i < nc.signals->size(); ++i)
        if ((*nc.signals)[i].name == name) id = static_cast<int>(i);
      if (id < 0) constants[name].Fail("no gateway signal '" + name + "' (vmt signals MODEL)");
      if ((*nc.signals)[id].direction != control::gateway::Direction::kPlcToNc)
        constants[name].Fail("'" + name + "' is not written by the PLC: no constant of it");
      plc_setup.constants.emplace_back(id, SignalValue(nc, id, constants[name]));
    }
  }
  const double period_ms = plc.Double("period_ms", 4, 0, 1000);
  const double ticks = period_ms * 1e-3 / kDriveTickS;
  if (!(ticks >= 1) || std::abs(ticks - std::round(ticks)) > 1e-9 || ticks > 4000)
    plc["period_ms"].Fail("must be a multiple of the 0.25 ms drive tick, at most 1000 ms");
  plc_setup.period_s = std::round(ticks) * kDriveTickS;
  return plc_setup;
}

/// `nc: axes:`: the channel's axes among the machine's NC axes (or made from its drives), with
/// the zero offsets, tool lengths and the headstock's rotary axis following them.
void ChooseAxes(const YamlNode& axes, const MachineModel& m, NcSetup& setup) {
  std::vector<control::axes::AxisParameters> chosen;
  for (size_t i = 0; i < axes.size(); ++i) {
    const std::string name = axes[i].String();
    auto it = std::find_if(m.nc.axes.begin(), m.nc.axes.end(),
                           [&](const auto& a) { return a.name == name; });
    if (it != m.nc.axes.end()) {
      chosen.push_back(*it);
      continue;
    }
    const int d = RequireDrive(m, axes[i]);
    control::axes::AxisParameters a;
    const DriveParams& p = m.drives[d];
    a.name = name;
    a.number = static_cast<int>(i) + 1;
    a.drive = d;
    a.rotary = p.info.kind == control::AxisKind::kRotary;
    const double unit = a.rotary ? kDegPerRad : kMmPerM;
    a.rapid_per_s = p.velocity_limit * unit;
    a.acceleration = p.acceleration_limit * unit;
    const Joint& joint = m.joints[p.motor_joint];
    if (joint.type == JointType::kPrismatic || joint.type == JointType::kRevolute)
      a.travel_min = joint.lower * unit, a.travel_max = joint.upper * unit;
    chosen.push_back(a);
  }
  // Zero offsets and tool lengths follow the axes they were given for.
  auto column = [&](const std::vector<double>& row) {
    std::vector<double> out(chosen.size(), 0.0);
    for (size_t k = 0; k < chosen.size(); ++k)
      for (size_t j = 0; j < m.nc.axes.size() && j < row.size(); ++j)
        if (m.nc.axes[j].name == chosen[k].name) out[k] = row[j];
    return out;
  };
  for (auto& row : setup.data.zero_offsets.g54_to_g59) row = column(row);
  for (auto& edge : setup.data.tools.edges) edge.length = column(edge.length);
  // The headstock's rotary axis mode only if its rotary axis is among the chosen ones.
  const int ra = setup.data.rotary_axis;
  setup.data.rotary_axis = -1;
  for (size_t k = 0; k < chosen.size() && ra >= 0; ++k)
    if (chosen[k].name == m.nc.axes[ra].name) setup.data.rotary_axis = static_cast<int>(k);
  setup.data.axes = chosen;
}

/// `nc: block_search:`: the CNC objects of block search as the PLC or the HMI writes them before
/// the start, named without the channel's prefix (mc_cmd_bs_type_w: 4).
void ReadBlockSearchObjects(const YamlNode& bs, NcSetup& setup) {
  const std::string prefix = "P" + std::string(setup.data.process.number < 10 ? "0" : "") +
                             std::to_string(setup.data.process.number) + ".";
  for (const std::string& key : bs.Keys()) {
    const bool object = key.rfind("mc_cmd_bs_", 0) == 0 || key == "mc_command_file_offset_w" ||
                        key.rfind("bahn_lc_control.block_search.", 0) == 0;
    if (!object)
      bs[key].Fail(
          "not a block search object (mc_cmd_bs_*_w, mc_command_file_offset_w, "
          "bahn_lc_control.block_search.enable_w)");
    const std::string error = AddSignalPreset(setup, prefix + key, bs[key].String());
    if (!error.empty()) bs[key].Fail(error);
  }
}

/// The `nc:` section: the programs parsed, the channel's axes, spindle, tables, start-up state
/// and gateway signals.
NcSetup ReadNc(const YamlNode& nc, const MachineModel& m, const std::string& path) {
  NcSetup setup;
  nc.AllowKeys({"program", "subprograms", "dialect", "axes", "spindle", "override", "zero_offsets",
                "tools", "initial", "aux_handshake", "block_search", "tool_storage_nc",
                "jog_of_path"});
  setup.present = true;
  std::vector<YamlNode> files{nc["program"]};
  if (nc.Has("subprograms"))
    for (size_t i = 0; i < nc["subprograms"].size(); ++i) files.push_back(nc["subprograms"][i]);
  const std::string dialect = nc.String("dialect", "");
  if (!dialect.empty() && dialect != "mtc200" && dialect != "isg")
    nc["dialect"].Fail("expected mtc200 or isg");
  const auto parse = [&](const YamlNode& f) {
    const std::string file =
        (std::filesystem::path(path).parent_path() / f.String()).lexically_normal().string();
    std::string why;
    const std::optional<common::MappedFile> read = common::MappedFile::Read(file, &why);
    if (!read) f.Fail("cannot open NC program " + file + ": " + why);
    const std::string_view text = *read;
    namespace cnc = control::nc;
    const cnc::Dialect d = dialect.empty()    ? cnc::DetectDialect(text, file)
                           : dialect == "isg" ? cnc::Dialect::kIsg
                                              : cnc::Dialect::kMtc200;
    auto parsed = std::make_shared<cnc::ParseResult>(cnc::ParseProgram(text, file, d));
    // NC errors read like a compiler's, the first one names the scene entry that loaded it.
    if (!parsed->ok()) f.Fail(cnc::Format(parsed->errors[0], parsed->program.files));
    return parsed;
  };
  for (const YamlNode& f : files) setup.programs.push_back(parse(f));
  // Block search 4.2.1: the manual return's program, for a JogOfPath channel of its own.
  if (nc.Has("jog_of_path")) setup.jog_of_path = parse(nc["jog_of_path"]);
  // The channel's axes: the machine's NC axes, or the scene's choice among them. A machine
  // without an `nc:` section gets axes from its drives with the drives' limits.
  setup.data = m.nc;
  if (nc.Has("axes"))
    ChooseAxes(nc["axes"], m, setup);
  else if (!m.nc.present)
    nc.Fail("the machine has no nc: section: list the channel's axes (axes: [X, Z])");
  if (nc.Has("spindle")) {
    setup.data.spindle_drive = RequireDrive(m, nc["spindle"]);
    if (!m.drives[setup.data.spindle_drive].spindle) nc["spindle"].Fail("not a spindle drive");
    // The model's spindle parameters (jogging speed, Cxx.049, ...) are its spindle's.
    if (setup.data.spindle_drive != m.nc.spindle_drive) {
      setup.data.spindle = {};
      setup.data.spindle.max_spindle_rpm =
          m.drives[setup.data.spindle_drive].velocity_limit * kDegPerRad / 6;
    }
  }
  for (const auto& a : setup.data.axes) setup.axis_drives.push_back(a.drive);
  if (nc.Has("zero_offsets"))
    setup.data.zero_offsets = ReadZeroOffsets(setup.data.axes, nc["zero_offsets"]);
  if (nc.Has("tools")) setup.data.tools = ReadToolTable(setup.data.axes, nc["tools"]);
  if (nc.Has("initial")) {
    // Start-up G codes of the channel: the zero offset and tool length a program expects.
    const YamlNode init = nc["initial"];
    for (size_t i = 0; i < init.size(); ++i) {
      const std::string error = control::nc::ApplyInitialWord(init[i].String(), setup.initial);
      if (!error.empty()) init[i].Fail(error);
    }
  }
  setup.aux_handshake = nc.Bool("aux_handshake", false);
  setup.tool_storage_nc = nc.Bool("tool_storage_nc", false);
  if (setup.tool_storage_nc && setup.data.tool_storage_drive < 0)
    nc["tool_storage_nc"].Fail("the machine has no tool storage axis (nc: tool_storage:)");
  // Its T words index it to their stations (REPOS manual 4.2): the NC must know them.
  if (setup.tool_storage_nc && setup.data.tool_storage_stations <= 0)
    nc["tool_storage_nc"].Fail(
        "the machine's tool storage axis has no stations (nc: tool_storage: {stations: ...})");
  setup.signals = std::make_shared<const std::vector<control::gateway::Signal>>(
      control::gateway::BuildSignalTable(GatewayLayoutOf(m)));
  // Feed override in percent, as the operator panel sets it (0..200 %).
  setup.override = nc.Double("override", 100, 0, 200) / 100;
  PresetStylusPages(m, setup.measuring_pages);
  if (nc.Has("block_search")) ReadBlockSearchObjects(nc["block_search"], setup);
  return setup;
}

// The block search objects whose values the TwinCAT manual bounds (4.1.1: the covered distance
// in per mille of the block; distances and offsets are not negative), checked as they are set
// rather than when the search starts.
std::string BlockSearchRangeError(const std::string& name, double value) {
  const auto ends_with = [&](const char* suffix) {
    const std::string s = suffix;
    return name.size() >= s.size() && name.compare(name.size() - s.size(), s.size(), s) == 0;
  };
  if (ends_with("mc_cmd_bs_covered_distance_w") && !(value >= 0 && value <= 1000))
    return "must be in 0..1000 (per mille of the block's path)";
  for (const char* key : {"mc_cmd_bs_deviation_max_w", "mc_command_file_offset_w",
                          "mc_cmd_bs_distance_prog_start_w", "mc_cmd_bs_breakpoint_position_w"})
    if (ends_with(key) && value < 0) return "must not be negative";
  return "";
}

}  // namespace

Scene LoadScene(const std::string& path) {
  const YamlNode root = YamlNode::LoadFile(path);
  if (!root.IsMap()) root.Fail("a scene file is a map");
  root.AllowKeys({"scene", "model", "backend", "duration", "trace_period", "workpiece", "initial",
                  "plc", "nc", "timeline", "expect", "snapshots", "cameras", "measuring_pages",
                  "probe", "study"});  // study: read by vmt study (sim/study), not by a run
  Scene s;
  s.file = path;
  s.name = root["scene"].String();
  const YamlNode model = root["model"];
  const std::string model_path =
      (std::filesystem::path(path).parent_path() / model.String()).lexically_normal().string();
  if (const std::string why = common::InputFileProblem(model_path); !why.empty())
    model.Fail("cannot open model " + model_path + ": " + why);
  s.model = std::make_shared<MachineModel>(LoadMachineModel(model_path));
  const MachineModel& m = *s.model;

  const std::string backend = root.String("backend", "physics");
  if (backend == "physics")
    s.backend = BackendKind::kPhysics;
  else if (backend == "kinematic")
    s.backend = BackendKind::kKinematic;
  else
    root["backend"].Fail("expected physics or kinematic, got \"" + backend + "\"");
  s.duration_s = root["duration"].Double(0, kMaxSceneSeconds);
  if (s.duration_s <= 0 || s.duration_s > 86400) root["duration"].Fail("must be in (0, 86400] s");
  s.trace_period_s = root.Double("trace_period", 0.001, kDriveTickS, kMaxSceneSeconds);
  if (s.trace_period_s < kDriveTickS) root["trace_period"].Fail("must be >= 0.00025 s");

  if (root.Has("workpiece")) s.workpiece = LoadWorkpiece(root["workpiece"], m);

  if (root.Has("probe")) s.probe_sampling = ReadProbeSampling(root["probe"]);
  if (root.Has("initial")) s.initial = ReadInitialState(root["initial"], m);
  s.cameras = root.Has("cameras") ? ReadCameras(root["cameras"], m) : m.cameras;
  if (root.Has("nc")) s.nc = ReadNc(root["nc"], m, path);
  if (root.Has("measuring_pages")) {
    if (!s.nc.present)
      root["measuring_pages"].Fail("the machine data pages are the NC's: the scene needs nc:");
    LoadMeasuringPages(root["measuring_pages"], s.nc.data.tools, s.nc.measuring_pages);
  }
  if (root.Has("plc")) s.plc = ReadPlc(root["plc"], s.nc);
  if (root.Has("timeline")) {
    const YamlNode t = root["timeline"];
    for (size_t i = 0; i < t.size(); ++i) {
      if (t[i].Has("press")) {
        for (TimelineStep& step : ReadPress(m, t[i], i, s.nc)) s.timeline.push_back(step);
        continue;
      }
      s.timeline.push_back(ReadStep(m, t[i], i, s.nc, s.plc.present));
    }
  }
  if (root.Has("expect")) {
    const YamlNode e = root["expect"];
    for (size_t i = 0; i < e.size(); ++i)
      s.expectations.push_back(ReadExpectation(m, e[i], i, s.nc));
  }
  if (root.Has("snapshots")) ReadSnapshots(root["snapshots"], s);
  if (s.nc.present) s.nc.channel = ChannelConfigOf(m, s.nc);
  return s;
}

std::string AddSignalPreset(NcSetup& nc, const std::string& name, const std::string& value) {
  using control::gateway::Direction;
  using control::gateway::SignalType;
  if (!nc.present || !nc.signals) return "the scene has no nc: section (no gateway signals)";
  int id = -1;
  for (size_t i = 0; i < nc.signals->size(); ++i)
    if ((*nc.signals)[i].name == name) id = static_cast<int>(i);
  if (id < 0) return "no gateway signal '" + name + "' (vmt signals MODEL lists them)";
  const control::gateway::Signal& sig = (*nc.signals)[id];
  if (sig.direction != Direction::kPlcToNc)
    return "'" + name + "' is not written by the PLC: it cannot be preset";
  NcSetup::SignalPreset preset{id, 0, ""};
  if (sig.type == SignalType::kString) {
    if (value.size() > 83) return "'" + name + "' holds at most 83 characters";
    preset.text = value;
  } else if (sig.type == SignalType::kBool) {
    if (value == "true" || value == "TRUE" || value == "1")
      preset.number = 1;
    else if (value != "false" && value != "FALSE" && value != "0")
      return "'" + name + "' is BOOL: expected true or false, not '" + value + "'";
  } else {
    char* end = nullptr;
    preset.number = std::strtod(value.c_str(), &end);
    if (value.empty() || *end != '\0' || !std::isfinite(preset.number))
      return "'" + name + "' expects a number, not '" + value + "'";
    const std::string error = control::gateway::ValueError(sig.type, preset.number);
    if (!error.empty()) return "'" + name + "': " + error;
    const std::string range = BlockSearchRangeError(name, preset.number);
    if (!range.empty()) return "'" + name + "': " + range;
  }
  for (NcSetup::SignalPreset& p : nc.presets)
    if (p.id == id) {
      p = preset;
      return "";
    }
  nc.presets.push_back(preset);
  return "";
}

}  // namespace vmt::sim
