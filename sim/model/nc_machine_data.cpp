#include "sim/model/nc_machine_data.hpp"

#include <string>

#include "sim/model/machine_model.hpp"
#include "sim/model/yaml_reader.hpp"

namespace vmt::sim {
namespace {

// Largest zero offset (100 m) and tool length or nose radius (10 m): beyond any lathe's work
// space, small enough that positions computed of them stay exact to far below a micrometre.
constexpr double kMaxOffsetMm = 1e5;
constexpr double kMaxToolLengthMm = 1e4;

int AxisIndex(const std::vector<control::axes::AxisParameters>& axes, const std::string& name) {
  for (size_t a = 0; a < axes.size(); ++a)
    if (axes[a].name == name) return static_cast<int>(a);
  return -1;
}

// Manual units are per minute (Cxx.020 [mm/min | deg/min]); the channel works per second.
double PerMinute(const YamlNode& n, const char* key, double fallback_per_s) {
  if (!n.Has(key)) return fallback_per_s;
  const double v = n[key].Double();
  if (v <= 0) n[key].Fail("must be > 0");
  return v / 60;
}

// C-axis manual 2.3 / 3.3 Homing: the reference holds while
//   n_max [1/s] * impulses or oscillations per revolution <= limit frequency.
// Both or neither: one without the other monitors nothing.
void ReadEncoderLimit(const YamlNode& n, control::axes::AxisParameters& a) {
  const bool periods = n.Has("encoder_periods_per_rev"), limit = n.Has("encoder_limit_hz");
  if (periods != limit)
    n[periods ? "encoder_periods_per_rev" : "encoder_limit_hz"].Fail(
        "needs encoder_periods_per_rev and encoder_limit_hz together (C-axis manual 2.3: "
        "speed x periods per revolution <= limit frequency)");
  if (!periods) return;
  a.encoder_periods_per_rev = n["encoder_periods_per_rev"].Double();
  if (a.encoder_periods_per_rev <= 0) n["encoder_periods_per_rev"].Fail("must be > 0");
  a.encoder_limit_hz = n["encoder_limit_hz"].Double();
  if (a.encoder_limit_hz <= 0) n["encoder_limit_hz"].Fail("must be > 0");
}

// Cxx.025..Cxx.032, waypoints 0..7 (C-axis manual 2.2; AxxS.WP0..WP7, 4.2), in machine
// coordinates: mm, or deg within one turn for a rotary axis or spindle.
void ReadWaypoints(const YamlNode& n, bool rotary, control::axes::AxisParameters& a) {
  for (int k = 0; k < 8; ++k) {
    const std::string key = "Cxx.0" + std::to_string(25 + k);
    if (!n.Has(key)) continue;
    a.waypoints[k] = n[key].Double();
    if (rotary && !(a.waypoints[k] >= 0 && a.waypoints[k] < 360))
      n[key].Fail("must be in [0, 360) deg (a waypoint within one turn)");
  }
}

// The main spindle's own parameters (C-axis manual 2.2 / 3.2: "Jogging speed" and "Jogging
// spindle position" with new parameter numbers the manual does not print, Cxx.049), for
// AxxC.M3 / M4 / M19 in manual mode (4.2) and the status indication (2.3).
void ReadSpindleParameters(const MachineModel& m, const YamlNode& sp, NcMachineData& nc) {
  control::axes::AxisParameters& s = nc.spindle;
  const DriveParams& d = m.drives[nc.spindle_drive];
  const double limit_rpm = d.velocity_limit * kDegPerRad / 6;
  if (sp.Has("jogging_speed")) {
    const double rpm = sp["jogging_speed"].Double();
    if (rpm <= 0) sp["jogging_speed"].Fail("must be > 0 (rpm)");
    if (rpm > limit_rpm * (1 + 1e-9))
      sp["jogging_speed"].Fail("faster than drive " + d.info.name + "'s velocity_limit");
    s.jog_per_s = rpm * 6;
  }
  s.jog_spindle_position = sp.Double("jogging_spindle_position", 0);
  if (s.jog_spindle_position < 0 || s.jog_spindle_position >= 360)
    sp["jogging_spindle_position"].Fail("must be in [0, 360) deg");
  s.max_spindle_rpm = sp.Double("Cxx.049", limit_rpm);
  if (s.max_spindle_rpm <= 0) sp["Cxx.049"].Fail("must be > 0 (rpm)");
  if (s.max_spindle_rpm > limit_rpm * (1 + 1e-9))
    sp["Cxx.049"].Fail("faster than drive " + d.info.name + "'s velocity_limit");
  ReadEncoderLimit(sp, s);
  ReadWaypoints(sp, true, s);
}

control::axes::AxisParameters ReadAxis(const MachineModel& m, const YamlNode& n, size_t i) {
  n.AllowKeys({"name", "number", "drive", "rapid", "acceleration", "jerk", "Cxx.020", "Cxx.021",
               "Cxx.022", "Cxx.023", "Cxx.086", "reference", "homing", "needs_homing",
               "encoder_periods_per_rev", "encoder_limit_hz", "stations", "Cxx.025",
               "Cxx.026", "Cxx.027", "Cxx.028", "Cxx.029", "Cxx.030", "Cxx.031", "Cxx.032"});
  control::axes::AxisParameters a;
  a.name = n["name"].String();
  a.number = n.Int("number", static_cast<int>(i) + 1);
  if (a.number < 1 || a.number > 99) n["number"].Fail("must be in 1..99 (Axx, Cxx)");
  const std::string drive = n.String("drive", a.name);
  a.drive = m.DriveIndex(drive);
  if (a.drive < 0) (n.Has("drive") ? n["drive"] : n["name"]).Fail("no drive '" + drive + "'");
  const DriveParams& d = m.drives[a.drive];
  a.rotary = d.info.kind == control::AxisKind::kRotary;
  const double unit = a.rotary ? kDegPerRad : kMmPerM;
  a.rapid_per_s = PerMinute(n, "rapid", d.velocity_limit * unit);
  if (a.rapid_per_s > d.velocity_limit * unit * (1 + 1e-9))
    n["rapid"].Fail("faster than the drive's velocity_limit");
  a.acceleration = n.Double("acceleration", d.acceleration_limit * unit);
  if (a.acceleration <= 0) n["acceleration"].Fail("must be > 0");
  a.jerk = n.Double("jerk", 0);
  if (a.jerk < 0) n["jerk"].Fail("must be >= 0 (0: not limited)");
  a.jog_per_s = PerMinute(n, "Cxx.020", 0);
  a.jog_rapid_per_s = PerMinute(n, "Cxx.021", 0);
  a.jog_distance = n.Double("Cxx.022", 0);
  if (a.jog_distance < 0) n["Cxx.022"].Fail("must be >= 0");
  a.in_position_window = n.Double("Cxx.023", d.in_position_window * unit);
  a.repos_window = n.Double("Cxx.086", 0.2);
  // REPOS manual 6.1: 0 leaves the axis out of repositioning; any other window lies in the
  // value range 0.1 .. 200000.
  if (a.repos_window != 0 && !(a.repos_window >= 0.1 && a.repos_window <= 200000))
    n["Cxx.086"].Fail("must be 0 (the axis is not repositioned) or in 0.1..200000");
  a.reference_position = n.Double("reference", 0);
  a.homing_per_s = PerMinute(n, "homing", 0);
  a.homed_at_start = !n.Bool("needs_homing", false);
  ReadEncoderLimit(n, a);
  ReadWaypoints(n, a.rotary, a);
  // Software limits: the joint's travel (the axis position is the joint position).
  const Joint& joint = m.joints[d.motor_joint];
  if (joint.type == JointType::kPrismatic || joint.type == JointType::kRevolute) {
    a.travel_min = joint.lower * unit;
    a.travel_max = joint.upper * unit;
  }
  if (a.travel_max > a.travel_min &&
      (a.reference_position < a.travel_min || a.reference_position > a.travel_max))
    n["reference"].Fail("outside the axis' travel");
  return a;
}

// C-axis manual 2.2: a main spindle with rotary axis capability is one axis with one axis
// parameter record and two designations (S1 in main spindle mode, C in rotary axis mode), so
// the rotary axis has the spindle's axis number. Its speeds and windows are those of the drive
// parameter set used for rotary mode, not of the spindle's set 0.
void RotaryAxisOnTheSpindleDrive(const MachineModel& m, const YamlNode& axis, const YamlNode& sp,
                                 NcMachineData& nc) {
  control::axes::AxisParameters& a = nc.axes[nc.rotary_axis];
  if (!sp.Has("number")) nc.spindle_number = a.number;
  if (a.number != nc.spindle_number)
    axis["number"].Fail("must be the spindle's number " + std::to_string(nc.spindle_number) +
                        ": the rotary axis of a spindle with rotary axis capability is the same "
                        "axis (C-axis manual 2.2)");
  const DriveParams& d = m.drives[nc.spindle_drive];
  if (nc.rotary_parameter_set >= static_cast<int>(d.parameter_sets.size()))
    sp["rotary_parameter_set"].Fail("drive " + d.info.name + " has no parameter set " +
                                    std::to_string(nc.rotary_parameter_set));
  const DriveParameterSet& set = d.parameter_sets[nc.rotary_parameter_set];
  const std::string which =
      "drive " + d.info.name + "'s parameter set " + std::to_string(nc.rotary_parameter_set);
  if (!axis.Has("rapid"))
    a.rapid_per_s = set.velocity_limit * kDegPerRad;
  else if (a.rapid_per_s > set.velocity_limit * kDegPerRad * (1 + 1e-9))
    axis["rapid"].Fail("faster than the velocity_limit of " + which);
  if (!axis.Has("acceleration"))
    a.acceleration = set.acceleration_limit * kDegPerRad;
  else if (a.acceleration > set.acceleration_limit * kDegPerRad * (1 + 1e-9))
    axis["acceleration"].Fail("above the acceleration_limit of " + which);
  if (!axis.Has("Cxx.023")) a.in_position_window = set.in_position_window * kDegPerRad;
  // One drive, one encoder, one reference (2.3 Homing): the spindle's encoder data is the
  // axis'. Given twice it could disagree.
  if (sp.Has("encoder_periods_per_rev")) {
    if (axis.Has("encoder_periods_per_rev"))
      axis["encoder_periods_per_rev"].Fail(
          "the spindle's encoder is given already: spindle and rotary axis on one drive have one "
          "encoder (C-axis manual 2.3)");
    a.encoder_periods_per_rev = nc.spindle.encoder_periods_per_rev;
    a.encoder_limit_hz = nc.spindle.encoder_limit_hz;
  }
}

}  // namespace

control::axes::ZeroOffsetTable ReadZeroOffsets(
    const std::vector<control::axes::AxisParameters>& axes, const YamlNode& node) {
  control::axes::ZeroOffsetTable t;
  for (const std::string& key : node.Keys()) {
    const YamlNode table = node[key];
    int g = -1;
    if (key.size() == 3 && key[0] == 'G' && key[1] == '5' && key[2] >= '4' && key[2] <= '9')
      g = 50 + (key[2] - '0');
    if (g < 0) table.Fail("expected G54 .. G59");
    std::vector<double>& row = t.g54_to_g59[g - 54];
    row.assign(axes.size(), 0.0);
    for (const std::string& axis : table.Keys()) {
      const int a = AxisIndex(axes, axis);
      if (a < 0) table[axis].Fail("no NC axis '" + axis + "'");
      row[a] = table[axis].Double(-kMaxOffsetMm, kMaxOffsetMm);
    }
  }
  return t;
}

control::axes::ToolTable ReadToolTable(const std::vector<control::axes::AxisParameters>& axes,
                                       const YamlNode& node) {
  control::axes::ToolTable t;
  for (size_t i = 0; i < node.size(); ++i) {
    const YamlNode e = node[i];
    control::axes::ToolEdge edge;
    edge.tool = e["T"].Int(0, 99999999);
    edge.edge = e.Int("D", 1, 1, 99);
    if (edge.tool < 0) e["T"].Fail("must be >= 0");
    if (edge.edge < 1) e["D"].Fail("must be >= 1 (D0 is no correction)");
    if (t.Find(edge.tool, edge.edge))
      e.Fail("T" + std::to_string(edge.tool) + " D" + std::to_string(edge.edge) + " listed twice");
    edge.length.assign(axes.size(), 0.0);
    for (const std::string& key : e.Keys()) {
      if (key == "T" || key == "D") continue;
      if (key == "radius") {
        edge.nose_radius = e[key].Double(0, kMaxToolLengthMm);
        if (edge.nose_radius < 0) e[key].Fail("must be >= 0");
      } else if (key == "edge") {
        edge.edge_position = e[key].Int(0, 9);
        if (edge.edge_position < 0 || edge.edge_position > 9) e[key].Fail("must be in 0..9");
      } else {
        const int a = AxisIndex(axes, key);
        if (a < 0) e[key].Fail("expected T, D, radius, edge or an NC axis name");
        edge.length[a] = e[key].Double(-kMaxToolLengthMm, kMaxToolLengthMm);
      }
    }
    t.edges.push_back(edge);
  }
  return t;
}

NcMachineData ReadNcMachineData(const MachineModel& m, const YamlNode& node) {
  node.AllowKeys(
      {"process", "axes", "spindle", "zero_offsets", "tools", "path_guard", "tool_storage"});
  NcMachineData nc;
  nc.present = true;
  if (node.Has("path_guard")) {
    const std::string r = node["path_guard"].String();
    if (r == "stop") {
      nc.path_guard = control::GuardReaction::kStop;
    } else if (r == "warn") {
      nc.path_guard = control::GuardReaction::kWarn;
    } else if (r == "off") {
      nc.path_guard = control::GuardReaction::kOff;
    } else {
      node["path_guard"].Fail("expected stop, warn or off");
    }
  }
  if (node.Has("process")) {
    const YamlNode p = node["process"];
    p.AllowKeys({"number", "Bxx.032", "Bxx.036", "Bxx.045"});
    nc.process.number = p.Int("number", 0);
    if (nc.process.number < 0 || nc.process.number > 99) p["number"].Fail("must be in 0..99");
    nc.process.reverse_program_required = p.Bool("Bxx.032", false);
    nc.process.jogging_causes_reset = p.Bool("Bxx.036", false);
    nc.process.reposition_tool_storage = p.Bool("Bxx.045", false);
  }
  const YamlNode axes = node["axes"];
  for (size_t i = 0; i < axes.size(); ++i) {
    control::axes::AxisParameters a = ReadAxis(m, axes[i], i);
    if (axes[i].Has("stations")) axes[i]["stations"].Fail("only the tool storage axis has stations");
    if (AxisIndex(nc.axes, a.name) >= 0) axes[i]["name"].Fail("duplicate NC axis");
    for (const auto& other : nc.axes)
      if (other.number == a.number) axes[i]["number"].Fail("axis number used twice");
    nc.axes.push_back(a);
  }
  if (node.Has("tool_storage")) {
    // The tool storage axis (turret): repositioning compares its position with the one at the
    // interruption when Bxx.045 is yes (REPOS manual 6.2). `tool_storage: T` names its drive;
    // the map form gives its axis parameters too, which an NC-controlled one is jogged and
    // returned with (3.4, 4.2): `{name: T, Cxx.020: ..., Cxx.021: ..., Cxx.022: ...}`, and
    // its `stations`, evenly spaced over a turn, which an NC-controlled one's T words index.
    const YamlNode t = node["tool_storage"];
    if (t.IsMap()) {
      nc.tool_storage = ReadAxis(m, t, nc.axes.size());
      nc.tool_storage_stations = t.Int("stations", 0);
      if (nc.tool_storage_stations < 0) t["stations"].Fail("must be >= 0 (0: not known)");
      if (nc.tool_storage_stations > 0 && !nc.tool_storage.rotary)
        t["stations"].Fail("stations are spaced over a turn: the axis must be rotary");
      if (AxisIndex(nc.axes, nc.tool_storage.name) >= 0) t["name"].Fail("already an NC axis");
      for (const auto& other : nc.axes)
        if (other.number == nc.tool_storage.number) t["number"].Fail("axis number used twice");
    } else {
      nc.tool_storage.name = t.String();
      nc.tool_storage.drive = m.DriveIndex(t.String());
      if (nc.tool_storage.drive < 0) t.Fail("no drive '" + t.String() + "'");
    }
    nc.tool_storage_drive = nc.tool_storage.drive;
  }
  if (node.Has("spindle")) {
    // `spindle: S1`, or `spindle: {drive: S1, number: 3, rotary_axis: C,
    // rotary_parameter_set: 1}` for a spindle with a rotary axis mode.
    const YamlNode sp = node["spindle"];
    const YamlNode s = sp.IsMap() ? sp["drive"] : sp;
    nc.spindle_drive = m.DriveIndex(s.String());
    if (nc.spindle_drive < 0) s.Fail("no drive '" + s.String() + "'");
    if (!m.drives[nc.spindle_drive].spindle) s.Fail("not a spindle drive");
    nc.spindle.max_spindle_rpm = m.drives[nc.spindle_drive].velocity_limit * kDegPerRad / 6;
    if (sp.IsMap()) {
      sp.AllowKeys({"drive", "number", "rotary_axis", "rotary_parameter_set",
                    "changeover_message_s", "jogging_speed", "jogging_spindle_position", "Cxx.049",
                    "encoder_periods_per_rev", "encoder_limit_hz", "Cxx.025", "Cxx.026", "Cxx.027",
                    "Cxx.028", "Cxx.029", "Cxx.030", "Cxx.031", "Cxx.032"});
      ReadSpindleParameters(m, sp, nc);
      nc.spindle_number = sp.Int("number", -1);
      if (sp.Has("number") && (nc.spindle_number < 1 || nc.spindle_number > 99))
        sp["number"].Fail("must be in 1..99 (Axx)");
      if (sp.Has("rotary_axis")) {
        nc.rotary_axis = AxisIndex(nc.axes, sp["rotary_axis"].String());
        if (nc.rotary_axis < 0)
          sp["rotary_axis"].Fail("no NC axis '" + sp["rotary_axis"].String() + "'");
        if (!nc.axes[nc.rotary_axis].rotary) sp["rotary_axis"].Fail("not a rotary axis");
      }
      nc.rotary_parameter_set = sp.Int("rotary_parameter_set", 0);
      nc.changeover_message_s = sp.Double("changeover_message_s", 5);
      if (!(nc.changeover_message_s > 0 && nc.changeover_message_s <= 3600))
        sp["changeover_message_s"].Fail("expected seconds, > 0 and at most 3600");
      if (nc.rotary_parameter_set < 0 || nc.rotary_parameter_set > 7)
        sp["rotary_parameter_set"].Fail("must be in 0..7");
      for (const auto& a : nc.axes)
        if (a.number == nc.spindle_number && a.drive != nc.spindle_drive)
          sp["number"].Fail("axis number used twice");
      if (nc.rotary_axis >= 0 && nc.axes[nc.rotary_axis].drive == nc.spindle_drive)
        RotaryAxisOnTheSpindleDrive(m, axes[nc.rotary_axis], sp, nc);
    }
  }
  if (node.Has("zero_offsets")) nc.zero_offsets = ReadZeroOffsets(nc.axes, node["zero_offsets"]);
  if (node.Has("tools")) nc.tools = ReadToolTable(nc.axes, node["tools"]);
  return nc;
}

}  // namespace vmt::sim
