// The names a scene's steps and expectations use, resolved against the machine and its NC
// with the YAML path of their faults, and the expectations (docs/scene-format.md). The step
// kinds are in steps/.
#include "sim/scene/scene_steps.hpp"

#include <algorithm>
#include <cctype>
#include <sstream>

#include "control/drive_bus.hpp"
#include "sim/model/model_error.hpp"
#include "sim/model/yaml_reader.hpp"

namespace vmt::sim {

// An axis by its drive's name, or by the name of an NC axis of the machine: on a main spindle
// with rotary axis capability (C-axis manual 2.2) C is the rotary axis designation of drive S1.
int RequireDrive(const MachineModel& m, const YamlNode& n) {
  int d = m.DriveIndex(n.String());
  for (const control::axes::AxisParameters& a : m.nc.axes)
    if (d < 0 && a.name == n.String()) d = a.drive;
  if (d < 0) n.Fail("no axis '" + n.String() + "' in the machine model");
  return d;
}

// The index of an NC channel axis named by its drive or NC axis name.
int RequireChannelAxis(const MachineModel& m, const NcSetup& nc, const YamlNode& n) {
  const int drive = RequireDrive(m, n);
  for (size_t k = 0; k < nc.axis_drives.size(); ++k)
    if (nc.axis_drives[k] == drive) return static_cast<int>(k);
  n.Fail("not an axis of the NC channel");
}

// The axis of a jog or handwheel step: a channel axis, or X1 / Y1, the fictive axes of the
// G31 face transformation (REPOS manual 5.2), which the channel moves only while G31 is active
// in rotary axis mode.
void RequireJogAxis(const MachineModel& m, const NcSetup& nc, const YamlNode& n,
                    TimelineStep& s) {
  const std::string name = n.String();
  if (name == "X1" || name == "Y1") {
    s.fictive = name == "X1" ? 0 : 1;
    return;
  }
  s.axis = RequireChannelAxis(m, nc, n);
  s.drive = nc.axis_drives[s.axis];
}

std::string Fmt(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// A load-side position of a drive (mm | deg) must lie within its joint's travel.
void RequireWithinTravel(const MachineModel& m, int drive, double value, const YamlNode& where) {
  const DriveParams& p = m.drives[drive];
  const Joint& j = m.joints[p.motor_joint];
  if (j.type == JointType::kContinuous || j.type == JointType::kFixed) return;
  const double unit = p.info.kind == control::AxisKind::kLinear ? kMmPerM : kDegPerRad;
  const double lo = std::min(j.lower, j.upper) / p.ratio * unit;
  const double hi = std::max(j.lower, j.upper) / p.ratio * unit;
  if (value < lo - 1e-9 || value > hi + 1e-9)
    where.Fail(Fmt(value) + " is beyond the travel of " + p.info.name + " (" + Fmt(lo) + " .. " +
               Fmt(hi) + ")");
}

int RequireSignal(const NcSetup& nc, const YamlNode& n) {
  if (!nc.present || !nc.signals) n.Fail("the scene has no nc: section (no gateway signals)");
  const std::string name = n.String();
  for (size_t i = 0; i < nc.signals->size(); ++i)
    if ((*nc.signals)[i].name == name) return static_cast<int>(i);
  n.Fail("no gateway signal '" + name + "' (vmt signals MODEL lists them)");
}

// A signal value as written in a scene: true/false for BOOL, a number otherwise.
double SignalValue(const NcSetup& nc, int id, const YamlNode& n) {
  if ((*nc.signals)[id].type == control::gateway::SignalType::kBool) return n.Bool() ? 1 : 0;
  if ((*nc.signals)[id].type == control::gateway::SignalType::kString)
    n.Fail("STRING signals cannot be set from a scene");
  const double value = n.Double();
  const std::string error = control::gateway::ValueError((*nc.signals)[id].type, value);
  if (!error.empty()) n.Fail((*nc.signals)[id].name + ": " + error);
  return value;
}

int RequireIo(const MachineModel& m, const YamlNode& n) {
  const int i = control::IndexOf(m.io, n.String());
  if (i < 0) n.Fail("no I/O point '" + n.String() + "' in the machine model");
  return i;
}

ClutchState ParseClutchState(const YamlNode& n) {
  const std::string s = n.String();
  for (ClutchState c : {ClutchState::kReleased, ClutchState::kEngaging, ClutchState::kBlocked,
                        ClutchState::kEngaged, ClutchState::kReleasing})
    if (s == ToString(c)) return c;
  n.Fail("expected released, engaging, blocked, engaged or releasing");
}

control::channel::ChannelState ParseNcState(const YamlNode& n) {
  using control::channel::ChannelState;
  const std::string s = n.String();
  for (ChannelState c : {ChannelState::kIdle, ChannelState::kRunning, ChannelState::kHold,
                         ChannelState::kEnded, ChannelState::kError})
    if (s == control::channel::ToString(c)) return c;
  n.Fail("expected idle, running, hold, ended or error");
}

Expectation ReadExpectation(const MachineModel& m, const YamlNode& n, size_t i, const NcSetup& nc) {
  n.AllowKeys({"at", "axis", "position", "velocity", "rpm", "following_error", "parameter_set",
               "input", "value", "clutch", "state", "tol", "nc", "signal", "drive", "trip"});
  Expectation e{};
  e.at_s = n.Double("at", -1, 0, kMaxSceneSeconds);
  std::ostringstream text;
  text << "expect[" << i << "]: ";
  if (n.Has("axis")) {
    e.index = RequireDrive(m, n["axis"]);
    int quantities = 0;
    for (const char* k : {"position", "velocity", "rpm", "following_error", "parameter_set"})
      quantities += n.Has(k);
    if (quantities != 1)
      n.Fail(
          "an axis expectation needs exactly one of position, velocity, rpm, following_error, "
          "parameter_set");
    if (n.Has("parameter_set")) {
      // A set number: exact, no tolerance.
      e.quantity = Expectation::Quantity::kParameterSet;
      e.value = n["parameter_set"].Int(0, 7);
      if (e.value < 0 || e.value > 7) n["parameter_set"].Fail("must be in 0..7");
      text << n["axis"].String() << " parameter_set " << Fmt(e.value);
    } else {
      std::string q;
      if (n.Has("position")) e.quantity = Expectation::Quantity::kPosition, q = "position";
      if (n.Has("velocity")) e.quantity = Expectation::Quantity::kVelocity, q = "velocity";
      if (n.Has("rpm")) e.quantity = Expectation::Quantity::kRpm, q = "rpm";
      if (n.Has("following_error"))
        e.quantity = Expectation::Quantity::kFollowingError, q = "following_error";
      e.value = n[q].Double();
      e.tolerance = n["tol"].Double(0, YamlNode::kAnyNumber);
      if (e.tolerance < 0) n["tol"].Fail("must be >= 0");
      text << n["axis"].String() << " " << q << " " << Fmt(e.value) << " +- " << Fmt(e.tolerance);
    }
  } else if (n.Has("input")) {
    e.quantity = Expectation::Quantity::kInput;
    e.index = RequireIo(m, n["input"]);
    e.value = n["value"].Bool() ? 1 : 0;
    text << n["input"].String() << " = " << e.value;
  } else if (n.Has("signal")) {
    e.quantity = Expectation::Quantity::kSignal;
    e.index = RequireSignal(nc, n["signal"]);
    e.value = SignalValue(nc, e.index, n["value"]);
    e.tolerance = n.Double("tol", 0);
    text << n["signal"].String() << " = " << Fmt(e.value);
  } else if (n.Has("nc")) {
    e.quantity = Expectation::Quantity::kNc;
    e.nc = ParseNcState(n["nc"]);
    text << "NC " << control::channel::ToString(e.nc);
  } else if (n.Has("clutch")) {
    e.quantity = Expectation::Quantity::kClutch;
    for (size_t k = 0; k < m.clutches.size(); ++k)
      if (m.clutches[k].name == n["clutch"].String()) e.index = static_cast<int>(k);
    if (e.index < 0) n["clutch"].Fail("no clutch '" + n["clutch"].String() + "'");
    e.clutch = ParseClutchState(n["state"]);
    text << "clutch " << n["clutch"].String() << " " << ToString(e.clutch);
  } else if (n.Has("drive")) {
    using namespace control::drive_status;
    e.quantity = Expectation::Quantity::kDriveTrip;
    e.index = RequireDrive(m, n["drive"]);
    const std::string cause = n["trip"].String();
    if (cause == "overload") e.trip = kOverload;
    if (cause == "overspeed") e.trip = kOverspeed;
    if (cause == "parameter_set_error") e.trip = kParameterSetError;
    if (cause == "any") e.trip = kOverload | kOverspeed | kParameterSetError;
    if (e.trip == 0) n["trip"].Fail("expected overload, overspeed, parameter_set_error or any");
    text << "drive " << n["drive"].String() << " trips (" << cause << ")";
  } else {
    n.Fail("expected axis:, input:, clutch:, nc:, signal: or drive:");
  }
  text << (e.at_s < 0 ? std::string(" at the end") : " at " + Fmt(e.at_s) + " s");
  e.text = text.str();
  return e;
}

}  // namespace vmt::sim
