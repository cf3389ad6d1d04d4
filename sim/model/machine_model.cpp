#include "sim/model/machine_model.hpp"

#include <algorithm>
#include <filesystem>

#include "control/gateway/signal_table.hpp"
#include "sim/model/gateway_layout.hpp"
#include "sim/model/model_error.hpp"
#include "sim/model/urdf_loader.hpp"
#include "sim/model/yaml_reader.hpp"

namespace vmt::sim {
namespace {

// Longest switching time of a valve, clutch or settling drive (10 min): any longer is a typo.
constexpr double kMaxActionSeconds = 600;

constexpr double kRadPerDeg = 1.0 / kDegPerRad;

// Machine units (mm | deg) -> SI (m | rad).
double ToSi(control::AxisKind kind) {
  return kind == control::AxisKind::kLinear ? 1.0 / kMmPerM : kRadPerDeg;
}

int RequireJoint(const MachineModel& m, const YamlNode& node) {
  const int j = m.JointIndex(node.String());
  if (j < 0) node.Fail("no joint '" + node.String() + "' in " + m.urdf_path);
  return j;
}

int RequireIo(const MachineModel& m, const YamlNode& node, bool output) {
  const int i = control::IndexOf(m.io, node.String());
  if (i < 0) node.Fail("no I/O point '" + node.String() + "' in io:");
  if (m.io[i].is_output != output)
    node.Fail("'" + node.String() + "' must be an " + (output ? "output" : "input"));
  return i;
}

int OptionalIo(const MachineModel& m, const YamlNode& map, const char* key, bool output) {
  return map.Has(key) ? RequireIo(m, map[key], output) : -1;
}

void ReadActuators(MachineModel& m, const YamlNode& list) {
  for (size_t i = 0; i < list.size(); ++i) {
    const YamlNode a = list[i];
    a.AllowKeys({"name", "valve", "on_switch", "off_switch", "time_on", "time_off", "holds",
                 "hold_torque"});
    Actuator d;
    d.name = a["name"].String();
    for (const Actuator& other : m.actuators)
      if (other.name == d.name) a["name"].Fail("duplicate actuator name");
    d.valve = RequireIo(m, a["valve"], true);
    d.on_switch = OptionalIo(m, a, "on_switch", false);
    d.off_switch = OptionalIo(m, a, "off_switch", false);
    d.time_on_s = a["time_on"].Double(0, kMaxActionSeconds);
    d.time_off_s = a["time_off"].Double(0, kMaxActionSeconds);
    if (d.time_on_s <= 0) a["time_on"].Fail("must be > 0");
    if (d.time_off_s <= 0) a["time_off"].Fail("must be > 0");
    if (a.Has("holds")) {
      d.holds_drive = m.DriveIndex(a["holds"].String());
      if (d.holds_drive < 0) a["holds"].Fail("no drive named '" + a["holds"].String() + "'");
      d.hold_torque = a["hold_torque"].Double();
      if (d.hold_torque <= 0) a["hold_torque"].Fail("must be > 0");
    } else if (a.Has("hold_torque")) {
      a["hold_torque"].Fail("only a device that holds a drive (holds:) has a hold torque");
    }
    m.actuators.push_back(d);
  }
}

void ReadPositionSwitches(MachineModel& m, const YamlNode& list) {
  for (size_t i = 0; i < list.size(); ++i) {
    const YamlNode p = list[i];
    p.AllowKeys({"name", "drive", "pitch", "window"});
    PositionSwitch ps;
    ps.input = RequireIo(m, p["name"], false);
    ps.drive = m.DriveIndex(p["drive"].String());
    if (ps.drive < 0) p["drive"].Fail("no drive named '" + p["drive"].String() + "'");
    ps.pitch = p["pitch"].Double();
    ps.window = p["window"].Double();
    if (ps.pitch <= 0) p["pitch"].Fail("must be > 0");
    if (ps.window <= 0 || ps.window >= ps.pitch / 2) p["window"].Fail("must be in (0, pitch/2)");
    m.position_switches.push_back(ps);
  }
}

// An input shows one thing: two devices on one switch would overwrite each other silently.
void CheckSwitchesDrivenOnce(const MachineModel& m, const YamlNode& root) {
  std::vector<int> driven(m.io.size(), 0);
  for (const DogClutch& k : m.clutches) ++driven[k.sensor_engaged], ++driven[k.sensor_released];
  for (const Actuator& a : m.actuators) {
    if (a.on_switch >= 0) ++driven[a.on_switch];
    if (a.off_switch >= 0) ++driven[a.off_switch];
  }
  for (const PositionSwitch& p : m.position_switches) ++driven[p.input];
  for (const ProbeStylus& p : m.probes) ++driven[p.contact_input];
  for (size_t i = 0; i < driven.size(); ++i)
    if (driven[i] > 1)
      root["io"].Fail("input '" + m.io[i].name + "' is the switch of more than one device");
}

// The gains and limits of a parameter set. Set 0 (`base` null) is the drive's own keys and needs
// them all; an entry of parameter_sets takes set 0's value for every key it does not name.
DriveParameterSet ReadParameterSet(const YamlNode& n, control::AxisKind kind,
                                   const DriveParameterSet* base) {
  DriveParameterSet g = base ? *base : DriveParameterSet{};
  if (!base || n.Has("type")) {
    const std::string type = n.String("type", "servo");
    if (type != "servo" && type != "spindle") n["type"].Fail("expected servo or spindle");
    g.spindle = type == "spindle";
  }
  const double s = ToSi(kind);
  // `scale` takes machine units to SI (a gain per unit divides by it); every gain and limit is a
  // positive number.
  auto read = [&](const char* key, double& field, double scale, bool per_unit = false) {
    if (base && !n.Has(key)) return;
    const double v = n[key].Double();
    if (v <= 0) n[key].Fail("must be > 0");
    field = per_unit ? v / scale : v * scale;
  };
  read("kv", g.kv_per_s, 1);
  read("velocity_kp", g.velocity_kp, s, true);  // N per (mm/s) -> N per (m/s)
  read("velocity_ti", g.velocity_ti_s, 1);
  read("torque_limit", g.torque_limit, 1);
  read("velocity_limit", g.velocity_limit, s);
  read("acceleration_limit", g.acceleration_limit, s);
  read("in_position_window", g.in_position_window, s);
  read("standstill_window", g.standstill_window, s);
  read("following_error_limit", g.following_error_limit, s);
  if (!base && !n.Has("positioning_speed"))
    g.positioning_speed = 360 * s;
  else
    read("positioning_speed", g.positioning_speed, s);
  return g;
}

// `encoder: load` closes the position loop on another joint's encoder (C-axis manual 3.1: the
// external spindle encoder of a separate servo); the motor's own encoder is the default.
void ReadEncoder(const MachineModel& m, const YamlNode& d, DriveParams& p) {
  const std::string encoder = d.String("encoder", "motor");
  if (encoder != "motor" && encoder != "load") d["encoder"].Fail("expected motor or load");
  if (encoder == "motor") {
    if (d.Has("load_joint"))
      d["load_joint"].Fail("only a drive with encoder: load has a load_joint");
    return;
  }
  const YamlNode j = d["load_joint"];
  p.load_joint = RequireJoint(m, j);
  if (p.load_joint == p.motor_joint)
    j.Fail("is the motor joint: a load-side encoder sits on the load, another joint");
  const JointType jt = m.joints[p.load_joint].type;
  if (jt == JointType::kFixed ||
      (jt == JointType::kPrismatic) != (p.info.kind == control::AxisKind::kLinear))
    j.Fail("joint type does not match the drive's kind");
}

// The drive's probe inputs E4/E5 (fast-measurement manual 7.3), named PIN4/PIN5 as in
// TASTWERKZEUGPAGE; each is wired to a switch of the machine's I/O map.
void ReadProbeInputs(const MachineModel& m, const YamlNode& n, DriveParams& p) {
  if (!n.IsMap()) n.Fail("expected a map {PIN4: <input>, PIN5: <input>}");
  n.AllowKeys({"PIN4", "PIN5"});
  const char* pins[2] = {"PIN4", "PIN5"};
  for (int k = 0; k < 2; ++k) {
    if (!n.Has(pins[k])) continue;
    const YamlNode pin = n[pins[k]];
    p.probe_inputs[k] = RequireIo(m, pin, false);
    if (m.io[p.probe_inputs[k]].key)
      pin.Fail("'" + pin.String() + "' is an operator's key, not a switch of the machine");
  }
}

DriveParams ReadDrive(const MachineModel& m, const YamlNode& d) {
  // clang-format off
  d.AllowKeys({"name", "kind", "type", "joint", "ratio", "kv", "velocity_kp", "velocity_ti",
               "torque_limit", "velocity_limit", "acceleration_limit", "encoder_resolution",
               "in_position_window", "standstill_window", "following_error_limit",
               "positioning_speed", "encoder", "load_joint", "modulo", "overload_time",
               "torque_threshold", "power_threshold", "parameter_sets", "probe_inputs",
               "spec"});
  // clang-format on
  DriveParams p;
  p.info.name = d["name"].String();
  const std::string kind = d["kind"].String();
  if (kind == "linear")
    p.info.kind = control::AxisKind::kLinear;
  else if (kind == "rotary")
    p.info.kind = control::AxisKind::kRotary;
  else
    d["kind"].Fail("expected linear or rotary, got \"" + kind + "\"");
  static_cast<DriveParameterSet&>(p) = ReadParameterSet(d, p.info.kind, nullptr);
  p.motor_joint = RequireJoint(m, d["joint"]);
  const JointType jt = m.joints[p.motor_joint].type;
  const bool joint_linear = jt == JointType::kPrismatic;
  if (jt == JointType::kFixed || joint_linear != (p.info.kind == control::AxisKind::kLinear))
    d["joint"].Fail("joint type does not match kind " + kind);
  ReadEncoder(m, d, p);

  const double s = ToSi(p.info.kind);
  p.ratio = d.Double("ratio", 1.0);
  if (p.ratio == 0) d["ratio"].Fail("must not be 0");
  p.encoder_resolution = d["encoder_resolution"].Double() * s;
  if (p.encoder_resolution <= 0) d["encoder_resolution"].Fail("must be > 0");
  p.overload_time_s = d.Double("overload_time", 1.0, 0, 3600);
  if (p.overload_time_s <= 0) d["overload_time"].Fail("must be > 0");
  // The threshold status bits (C-axis manual 4.2 AxxS.MD_MDX, P_PX): N | N m and W, as the
  // torque limit, already SI.
  p.torque_threshold = d.Double("torque_threshold", 0);
  if (p.torque_threshold < 0) d["torque_threshold"].Fail("must be >= 0 (0: none)");
  p.power_threshold_w = d.Double("power_threshold", 0);
  if (p.power_threshold_w < 0) d["power_threshold"].Fail("must be >= 0 (0: none)");
  if (d.Has("modulo")) {
    if (p.info.kind != control::AxisKind::kRotary) d["modulo"].Fail("only a rotary drive has one");
    p.modulo = d["modulo"].Double() * s;
    if (!(p.modulo > 0)) d["modulo"].Fail("must be > 0 (degrees)");
  }

  p.parameter_sets.push_back(static_cast<const DriveParameterSet&>(p));
  if (d.Has("parameter_sets")) {
    const YamlNode sets = d["parameter_sets"];
    // SERCOS numbers sets 0..7 (C-axis manual 2.2: "Valid entries are figures between 0 and 7").
    if (sets.size() > 7) sets.Fail("at most 7 entries: sets 1..7 (set 0 is the drive's own keys)");
    for (size_t i = 0; i < sets.size(); ++i) {
      const YamlNode set = sets[i];
      if (!set.IsMap()) set.Fail("expected a map of overrides of set 0's keys");
      set.AllowKeys({"type", "kv", "velocity_kp", "velocity_ti", "torque_limit", "velocity_limit",
                     "acceleration_limit", "in_position_window", "standstill_window",
                     "following_error_limit", "positioning_speed"});
      p.parameter_sets.push_back(ReadParameterSet(set, p.info.kind, &p.parameter_sets[0]));
    }
  }
  if (d.Has("probe_inputs")) ReadProbeInputs(m, d["probe_inputs"], p);
  if (d.Has("spec")) {
    const YamlNode spec = d["spec"];
    spec.AllowKeys({"settle_time", "overshoot"});
    p.spec_settle_time_s = spec["settle_time"].Double(0, kMaxActionSeconds);
    p.spec_overshoot = spec["overshoot"].Double() * s;
  }
  return p;
}

}  // namespace

std::vector<control::DriveInfo> MachineModel::DriveInfos() const {
  std::vector<control::DriveInfo> infos;
  for (const DriveParams& d : drives) infos.push_back(d.info);
  return infos;
}

int MachineModel::LinkIndex(const std::string& n) const {
  for (size_t i = 0; i < links.size(); ++i)
    if (links[i].name == n) return static_cast<int>(i);
  return -1;
}
int MachineModel::JointIndex(const std::string& n) const {
  for (size_t i = 0; i < joints.size(); ++i)
    if (joints[i].name == n) return static_cast<int>(i);
  return -1;
}
int MachineModel::DriveIndex(const std::string& n) const {
  for (size_t i = 0; i < drives.size(); ++i)
    if (drives[i].info.name == n) return static_cast<int>(i);
  return -1;
}

namespace {

// The machine's inputs, outputs, keys and selectors (`io:`).
void ReadIo(MachineModel& m, const YamlNode& io) {
  for (size_t i = 0; i < io.size(); ++i) {
    io[i].AllowKeys({"name", "dir", "positions", "initial"});
    const std::string dir = io[i]["dir"].String();
    if (dir != "in" && dir != "out" && dir != "key" && dir != "selector")
      io[i]["dir"].Fail("expected in, out, key or selector");
    if (control::IndexOf(m.io, io[i]["name"].String()) >= 0) io[i]["name"].Fail("duplicate");
    control::IoInfo point;
    point.name = io[i]["name"].String();
    point.is_output = dir == "out";
    point.key = dir == "key" || dir == "selector";
    if (dir == "selector") {
      const YamlNode positions = io[i]["positions"];
      if (!positions.IsSequence() || positions.size() < 2 || positions.size() > 64)
        positions.Fail("expected a list of 2 to 64 positions (integers)");
      for (size_t k = 0; k < positions.size(); ++k) {
        const int v = positions[k].Int();
        if (v < 0 || v > 32767) positions[k].Fail("expected a position 0..32767");
        if (k > 0 && v <= point.positions.back())
          positions[k].Fail("expected the positions in increasing order");
        point.positions.push_back(v);
      }
      point.initial = io[i].Has("initial") ? io[i]["initial"].Int() : point.positions.front();
      if (std::find(point.positions.begin(), point.positions.end(), point.initial) ==
          point.positions.end())
        io[i]["initial"].Fail("expected one of the positions");
    } else {
      for (const char* only : {"positions", "initial"})
        if (io[i].Has(only)) io[i][only].Fail("only a selector (dir: selector) has it");
    }
    m.io.push_back(std::move(point));
  }
}

// The <collision> parts that cut the workpiece (`cutting_parts:`).
void ReadCuttingParts(MachineModel& m, const YamlNode& cs) {
  if (!cs.IsSequence()) cs.Fail("expected a list of <collision> names");
  for (size_t i = 0; i < cs.size(); ++i) {
    const std::string name = cs[i].String();
    CuttingPart found;
    for (size_t l = 0; l < m.links.size() && found.link < 0; ++l)
      for (size_t c = 0; c < m.links[l].collisions.size(); ++c)
        if (m.links[l].collisions[c].name == name)
          found = {static_cast<int>(l), static_cast<int>(c)};
    if (found.link < 0) cs[i].Fail("no <collision name=\"" + name + "\"> in the URDF");
    m.cutting_parts.push_back(found);
  }
}

// Gears and dog clutches between joints (`couplings:`).
void ReadCouplings(MachineModel& m, const YamlNode& cs) {
  for (size_t i = 0; i < cs.size(); ++i) {
    const YamlNode c = cs[i];
    const std::string type = c["type"].String();
    if (type == "gear") {
      c.AllowKeys({"name", "type", "motor", "load", "ratio"});
      GearCoupling g{c["name"].String(), RequireJoint(m, c["motor"]), RequireJoint(m, c["load"]),
                     c["ratio"].Double()};
      if (g.ratio == 0) c["ratio"].Fail("must not be 0");
      m.gears.push_back(g);
    } else if (type == "dog_clutch") {
      c.AllowKeys({"name", "type", "motor", "load", "ratio", "teeth", "phase_tolerance",
                   "max_relative_speed", "engage_time", "release_time", "valve_engage",
                   "valve_release", "sensor_engaged", "sensor_released"});
      DogClutch k;
      k.name = c["name"].String();
      k.motor_joint = RequireJoint(m, c["motor"]);
      k.load_joint = RequireJoint(m, c["load"]);
      k.ratio = c["ratio"].Double();
      if (k.ratio == 0) c["ratio"].Fail("must not be 0");
      k.teeth = c["teeth"].Int(1, 3600);
      if (k.teeth < 1) c["teeth"].Fail("must be >= 1");
      k.phase_tolerance_rad = c["phase_tolerance"].Double(0, 360) * kRadPerDeg;
      k.max_relative_speed_rad_s = c["max_relative_speed"].Double() * kRadPerDeg;
      k.engage_time_s = c["engage_time"].Double(0, kMaxActionSeconds);
      k.release_time_s = c["release_time"].Double(0, kMaxActionSeconds);
      k.valve_engage = RequireIo(m, c["valve_engage"], true);
      k.valve_release = RequireIo(m, c["valve_release"], true);
      k.sensor_engaged = RequireIo(m, c["sensor_engaged"], false);
      k.sensor_released = RequireIo(m, c["sensor_released"], false);
      m.clutches.push_back(k);
    } else {
      c["type"].Fail("expected gear or dog_clutch, got \"" + type + "\"");
    }
  }
}

}  // namespace

MachineModel LoadMachineModel(const std::string& machine_yaml_path) {
  const YamlNode root = YamlNode::LoadFile(machine_yaml_path);
  root.AllowKeys({"machine", "urdf", "io", "drives", "couplings", "actuators", "position_switches",
                  "cutting_parts", "cameras", "nc", "probe"});
  MachineModel m;
  m.yaml_path = machine_yaml_path;
  m.name = root["machine"].String();
  const YamlNode urdf = root["urdf"];
  m.urdf_path = (std::filesystem::path(machine_yaml_path).parent_path() / urdf.String()).string();
  if (!std::filesystem::exists(m.urdf_path)) urdf.Fail("URDF file not found: " + m.urdf_path);
  LoadUrdf(m.urdf_path, m);
  if (root.Has("io")) ReadIo(m, root["io"]);
  if (root.Has("cutting_parts")) ReadCuttingParts(m, root["cutting_parts"]);
  const YamlNode drives = root["drives"];
  for (size_t i = 0; i < drives.size(); ++i) {
    DriveParams p = ReadDrive(m, drives[i]);
    if (m.DriveIndex(p.info.name) >= 0) drives[i]["name"].Fail("duplicate drive name");
    m.drives.push_back(std::move(p));
  }

  if (root.Has("couplings")) ReadCouplings(m, root["couplings"]);
  if (root.Has("actuators")) ReadActuators(m, root["actuators"]);
  if (root.Has("position_switches")) ReadPositionSwitches(m, root["position_switches"]);
  CheckSwitchesDrivenOnce(m, root);

  if (root.Has("cameras")) {
    const YamlNode cams = root["cameras"];
    for (const std::string& name : cams.Keys()) {
      const NamedCamera cam = ReadCamera(name, cams[name]);
      m.cameras.push_back(cam);
    }
  }
  if (root.Has("nc")) m.nc = ReadNcMachineData(m, root["nc"]);
  if (root.Has("probe")) {
    m.probes = ReadProbeStyluses(m, root["probe"]);
    CheckSwitchesDrivenOnce(m, root);
  }
  // The NC-PLC signals the machine gives (its io names, axis numbers) must make a signal table;
  // said here, where the file is known, not when a scene first builds the table.
  try {
    (void)control::gateway::BuildSignalTable(GatewayLayoutOf(m));
  } catch (const std::invalid_argument& e) {
    std::string why = e.what();
    if (why.rfind("GatewayLayout.", 0) == 0) why.erase(0, std::string("GatewayLayout.").size());
    throw ModelError(machine_yaml_path, "", why);
  }
  return m;
}

std::vector<Eigen::Isometry3d> LinkPoses(const MachineModel& model, const std::vector<double>& q) {
  std::vector<Eigen::Isometry3d> X_W(model.links.size(), Eigen::Isometry3d::Identity());
  LinkPoses(model, q, std::vector<bool>(model.links.size(), true), X_W);
  return X_W;
}

std::vector<bool> LinkChains(const MachineModel& model, const std::vector<int>& links) {
  std::vector<bool> needed(model.links.size(), false);
  for (const int link : links) needed.at(static_cast<size_t>(link)) = true;
  // Children come after their parents: walking back carries a need up to the root.
  for (size_t j = model.joints.size(); j-- > 0;)
    if (needed[model.joints[j].child_link]) needed[model.joints[j].parent_link] = true;
  return needed;
}

void LinkPoses(const MachineModel& model, const std::vector<double>& q,
               const std::vector<bool>& needed, std::vector<Eigen::Isometry3d>& X_W) {
  if (X_W.size() != model.links.size())
    X_W.assign(model.links.size(), Eigen::Isometry3d::Identity());
  for (size_t j = 0; j < model.joints.size(); ++j) {
    const Joint& joint = model.joints[j];
    if (!needed[joint.child_link]) continue;
    // The joint's own motion is a pure translation or a pure rotation: only that half of the
    // product is formed. The other half is multiplied by an identity or adds zeros, which changes
    // no bit.
    Eigen::Isometry3d& X = X_W[joint.child_link];
    X = X_W[joint.parent_link] * joint.X_ParentJoint;
    if (joint.type == JointType::kPrismatic)
      X.translation() = X.linear() * (joint.axis * q[j]) + X.translation();
    else if (joint.type != JointType::kFixed)
      X.linear() = X.linear() * Eigen::AngleAxisd(q[j], joint.axis).toRotationMatrix();
  }
}

}  // namespace vmt::sim
