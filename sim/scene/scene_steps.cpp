// Timeline steps, wait conditions and expectations of a scene (docs/scene-format.md): each
// read with the YAML path of its faults, names resolved against the machine and its NC.
#include "sim/scene/scene_steps.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <sstream>

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
  return n.Double();
}

namespace {

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

// `parameter_set:` of a drive step (0..7, as SERCOS numbers them). A set the drive lacks is
// not refused here: the drive reports it (kParameterSetError), which a scene may want to show.
int ReadDriveParameterSet(const YamlNode& step, std::ostringstream& text) {
  const int set = step.Int("parameter_set", 0);
  if (set < 0 || set > 7) step["parameter_set"].Fail("expected 0..7");
  if (set != 0) text << " (parameter set " << set << ")";
  return set;
}

bool IsRotary(const MachineModel& m, int drive) {
  return m.drives[drive].info.kind == control::AxisKind::kRotary;
}

control::channel::ChannelState ParseNcState(const YamlNode& n) {
  using control::channel::ChannelState;
  const std::string s = n.String();
  for (ChannelState c : {ChannelState::kIdle, ChannelState::kRunning, ChannelState::kHold,
                         ChannelState::kEnded, ChannelState::kError})
    if (s == control::channel::ToString(c)) return c;
  n.Fail("expected idle, running, hold, ended or error");
}

Condition ReadCondition(const MachineModel& m, const YamlNode& n, const NcSetup& nc) {
  Condition c;
  if (n.Has("signal")) {
    n.AllowKeys({"signal", "value", "timeout"});
    c.kind = Condition::Kind::kSignal;
    c.index = RequireSignal(nc, n["signal"]);
    c.signal_value = n.Has("value") ? SignalValue(nc, c.index, n["value"]) : 1;
    return c;
  }
  if (n.Has("nc")) {
    n.AllowKeys({"nc", "timeout"});
    c.kind = Condition::Kind::kNc;
    c.nc = ParseNcState(n["nc"]);
    return c;
  }
  if (n.Has("input")) {
    n.AllowKeys({"input", "value", "timeout"});
    c.kind = Condition::Kind::kInput;
    c.index = RequireIo(m, n["input"]);
    c.value = n.Bool("value", true);
  } else if (n.Has("clutch")) {
    n.AllowKeys({"clutch", "state", "timeout"});
    c.kind = Condition::Kind::kClutch;
    c.index = -1;
    for (size_t k = 0; k < m.clutches.size(); ++k)
      if (m.clutches[k].name == n["clutch"].String()) c.index = static_cast<int>(k);
    if (c.index < 0) n["clutch"].Fail("no clutch '" + n["clutch"].String() + "'");
    c.clutch = ParseClutchState(n["state"]);
  } else if (n.Has("axis")) {
    n.AllowKeys({"axis", "in_position", "at_speed", "standstill", "timeout"});
    c.index = RequireDrive(m, n["axis"]);
    if (n.Has("in_position"))
      c.kind = Condition::Kind::kInPosition, c.value = n.Bool("in_position", true);
    else if (n.Has("at_speed"))
      c.kind = Condition::Kind::kAtSpeed, c.value = n.Bool("at_speed", true);
    else if (n.Has("standstill"))
      c.kind = Condition::Kind::kStandstill, c.value = n.Bool("standstill", true);
    else
      n.Fail("expected one of in_position, at_speed, standstill");
  } else {
    n.Fail("expected input:, clutch:, axis:, nc: or signal:");
  }
  return c;
}

}  // namespace

// `press: KEY` or `press: {name: KEY, for: S}`: the operator presses a machine key and lets it
// go after `for` seconds (0.1 s), three steps of the timeline.
std::vector<TimelineStep> ReadPress(const MachineModel& m, const YamlNode& n, size_t i,
                                    const NcSetup& nc) {
  n.AllowKeys({"at", "press"});
  const YamlNode a = n["press"];
  const YamlNode name = a.IsMap() ? a["name"] : a;
  if (a.IsMap()) a.AllowKeys({"name", "for"});
  const double hold_s = a.IsMap() ? a.Double("for", 0.1) : 0.1;
  if (!(hold_s > 0)) a["for"].Fail("must be > 0");
  const int io = control::IndexOf(m.io, name.String());
  if (io < 0 || !m.io[io].key) name.Fail("'" + name.String() + "' is not a key (io dir: key)");
  TimelineStep press{}, hold{}, release{};
  press.kind = release.kind = TimelineStep::Kind::kSignal;
  press.signal = release.signal = RequireSignal(nc, name);
  press.not_before_s = n.Double("at", 0);
  press.target = 1;
  release.target = 0;
  hold.kind = TimelineStep::Kind::kWait;
  hold.wait_s = hold_s;
  const std::string at = "timeline[" + std::to_string(i) + "]: ";
  press.text = at + "press " + name.String();
  hold.text = at + "hold " + name.String() + " " + Fmt(hold_s) + " s";
  release.text = at + "release " + name.String();
  return {press, hold, release};
}

TimelineStep ReadStep(const MachineModel& m, const YamlNode& n, size_t i, const NcSetup& nc,
                      bool plc) {
  const bool has_nc = nc.present;
  n.AllowKeys({"at", "move", "speed", "orient", "off", "output", "wait", "wait_until", "nc", "jog",
               "handwheel", "signal", "fault", "press"});
  TimelineStep s{};
  s.not_before_s = n.Double("at", 0);
  std::ostringstream text;
  text << "timeline[" << i << "]: ";
  int actions = 0;
  for (const char* k : {"move", "speed", "orient", "off", "output", "wait", "wait_until", "nc",
                        "jog", "handwheel", "signal", "fault"})
    actions += n.Has(k);
  if (actions != 1)
    n.Fail(
        "a step needs exactly one of move, speed, orient, off, output, wait, wait_until, nc, jog, "
        "press, "
        "handwheel, signal, fault");

  if (n.Has("fault")) {
    // Fault injection: what breaks on a real machine, for the PLC program and the NC to meet.
    const YamlNode f = n["fault"];
    f.AllowKeys({"sensor", "valve", "drive", "plc", "cycles", "stuck", "clear"});
    s.kind = TimelineStep::Kind::kFault;
    using F = TimelineStep::Fault;
    const auto io_point = [&](const YamlNode& name, bool output) {
      const int io = control::IndexOf(m.io, name.String());
      if (io < 0 || m.io[io].is_output != output || m.io[io].key)
        name.Fail(std::string("no machine ") +
                  (output ? "valve (io dir: out)" : "sensor (io dir: in)") + " called '" +
                  name.String() + "'");
      return io;
    };
    if (f.Has("sensor") || f.Has("valve")) {
      const bool valve = f.Has("valve");
      s.io = io_point(f[valve ? "valve" : "sensor"], valve);
      s.fault = valve ? F::kValveStuck : F::kSensorStuck;
      s.level = f["stuck"].Bool();
      text << "fault: " << (valve ? "valve " : "sensor ") << m.io[s.io].name << " stuck at "
           << s.level;
    } else if (f.Has("drive")) {
      s.drive = RequireDrive(m, f["drive"]);
      s.fault = F::kDrive;
      text << "fault: drive " << m.drives[s.drive].info.name << " not ready";
    } else if (f.Has("plc")) {
      const std::string what = f["plc"].String();
      if (what == "client_gone") {
        // Gone for good: there is no `clear:` for it, as a lost PLC does not come back by itself.
        f.AllowKeys({"plc"});
        s.fault = F::kPlcClientGone;
        text << "fault: PLC client gone";
      } else if (what == "overrun") {
        s.fault = F::kPlcOverrun;
        s.code = f.Int("cycles", 10);
        if (s.code < 1 || s.code > 1000000) f["cycles"].Fail("must be 1..1000000");
        text << "fault: PLC misses " << s.code << " scans";
      } else {
        f["plc"].Fail("expected overrun or client_gone");
      }
    } else if (f.Has("clear")) {
      const std::string what = f["clear"].String();
      s.fault = F::kClear;
      s.io = control::IndexOf(m.io, what);
      if (s.io < 0) s.drive = RequireDrive(m, f["clear"]);
      text << "fault cleared: " << what;
    } else {
      f.Fail("expected sensor, valve, drive, plc or clear");
    }
    s.text = text.str();
    return s;
  }
  if (n.Has("signal")) {  // the default PLC passes a panel key or value to the NC
    const YamlNode a = n["signal"];
    a.AllowKeys({"name", "value"});
    s.kind = TimelineStep::Kind::kSignal;
    s.signal = RequireSignal(nc, a["name"]);
    const auto& sig = (*nc.signals)[s.signal];
    // The timeline plays the PLC and the operator: it writes what a PLC drives and presses
    // the machine keys; the NC's status and the machine's sensors are not its to set.
    const int io = control::IndexOf(m.io, sig.name);
    const bool key = io >= 0 && m.io[io].key;
    if (sig.direction == control::gateway::Direction::kNcToPlc)
      a["name"].Fail("the NC writes " + sig.name + ": a PLC cannot set it");
    if (sig.direction == control::gateway::Direction::kMachineToPlc && !key)
      a["name"].Fail(sig.name + " is a sensor of the machine: a PLC cannot set it");
    if (plc && !key)
      a["name"].Fail("the scene's PLC program writes " + sig.name +
                     ": with plc: the timeline only presses the operator's keys");
    s.target = SignalValue(nc, s.signal, a["value"]);
    text << "signal " << sig.name << " = " << Fmt(s.target);
    s.text = text.str();
    return s;
  }

  if (n.Has("handwheel")) {  // turn the handwheel of a channel axis by a number of counts
    const YamlNode a = n["handwheel"];
    if (!has_nc) a.Fail("the scene has no nc: section");
    a.AllowKeys({"axis", "counts"});
    s.kind = TimelineStep::Kind::kHandwheel;
    RequireJogAxis(m, nc, a["axis"], s);
    s.code = a["counts"].Int();
    text << "handwheel " << a["axis"].String() << " " << s.code << " counts";
    s.text = text.str();
    return s;
  }

  if (n.Has("jog")) {  // hold a jog key of a channel axis for a time
    const YamlNode a = n["jog"];
    if (!has_nc) a.Fail("the scene has no nc: section");
    a.AllowKeys({"axis", "direction", "hold", "to"});
    s.kind = TimelineStep::Kind::kJog;
    RequireJogAxis(m, nc, a["axis"], s);
    if (a.Has("to")) {
      // To a position, as an operator does it in incremental jog mode: the increment set to
      // the distance, one tap toward it (an increment once started is completed).
      if (s.fictive >= 0) a["to"].Fail("a fictive axis has no drive position");
      if (a.Has("direction")) a["direction"].Fail("give direction or to, not both");
      s.jog_to = true;
      s.target = a["to"].Double();
      s.wait_s = a.Has("hold") ? a["hold"].Double() : 0.05;
      if (s.wait_s <= 0) a["hold"].Fail("must be > 0");
      text << "jog " << a["axis"].String() << " to " << Fmt(s.target);
      s.text = text.str();
      return s;
    }
    const std::string dir = a["direction"].String();
    if (dir != "+" && dir != "-") a["direction"].Fail("expected + or -");
    s.direction = dir == "+" ? 1 : -1;
    s.wait_s = a["hold"].Double();
    if (s.wait_s <= 0) a["hold"].Fail("must be > 0");
    text << "jog " << a["axis"].String() << dir << " for " << Fmt(s.wait_s) << " s";
    s.text = text.str();
    return s;
  }

  if (n.Has("nc")) {
    const YamlNode a = n["nc"];
    if (!has_nc) a.Fail("the scene has no nc: section");
    if (a.IsMap() && a.Has("mode")) {
      a.AllowKeys({"mode"});
      s.kind = TimelineStep::Kind::kNcMode;
      const std::string mode = a["mode"].String();
      using control::channel::ChannelMode;
      if (mode == "manual")
        s.code = static_cast<int>(ChannelMode::kManual);
      else if (mode == "automatic")
        s.code = static_cast<int>(ChannelMode::kAutomatic);
      else if (mode == "mdi")
        s.code = static_cast<int>(ChannelMode::kMdi);
      else
        a["mode"].Fail("expected automatic, manual or mdi");
      text << "mode " << mode;
    } else if (a.IsMap() && a.Has("jog_mode")) {
      // PxxC.JOGM0..2 as a code 0..7 (control/channel/channel.hpp JogMode).
      a.AllowKeys({"jog_mode"});
      s.kind = TimelineStep::Kind::kNcJogMode;
      s.code = a["jog_mode"].Int();
      if (s.code < 0 || s.code > 7) a["jog_mode"].Fail("must be 0..7 (JOGM0..2)");
      text << "jog mode " << s.code;
    } else if (a.IsMap() && a.Has("mdi")) {
      a.AllowKeys({"mdi"});
      s.kind = TimelineStep::Kind::kNcMdi;
      s.mdi = a["mdi"].String();
      text << "MDI " << s.mdi;
    } else if (a.IsMap() && a.Has("select")) {
      // Program selection by name, as the operator picks a program from the NC's store: the
      // file name, with or without its extension, of the scene's program or subprograms.
      a.AllowKeys({"select"});
      s.kind = TimelineStep::Kind::kNcSelect;
      const std::string name = a["select"].String();
      s.code = -1;
      for (size_t k = 0; k < nc.programs.size(); ++k) {
        const std::filesystem::path file(nc.programs[k]->program.files.at(0));
        if (file.filename() != name && file.stem() != name) continue;
        if (s.code >= 0) a["select"].Fail("names more than one of the scene's NC programs");
        s.code = static_cast<int>(k);
      }
      if (s.code < 0)
        a["select"].Fail("is none of the scene's NC programs (nc: program, subprograms)");
      text << "select " << name;
    } else if (a.IsMap() && a.Has("jog_increment")) {
      a.AllowKeys({"jog_increment"});
      s.kind = TimelineStep::Kind::kNcJogIncrement;
      s.target = a["jog_increment"].Double();
      if (s.target < 0) a["jog_increment"].Fail("must be >= 0 (0: continuous)");
      text << "jog increment " << Fmt(s.target);
    } else if (a.IsMap() && (a.Has("zero_offset") || a.Has("tool_length"))) {
      // The operator's edits while a program is interrupted (repositioning manual 2.5).
      const bool offset = a.Has("zero_offset");
      a.AllowKeys({offset ? "zero_offset" : "tool_length"});
      const YamlNode e = a[offset ? "zero_offset" : "tool_length"];
      if (offset)
        e.AllowKeys({"G", "axis", "value"});
      else
        e.AllowKeys({"T", "D", "axis", "value"});
      s.kind = offset ? TimelineStep::Kind::kNcZeroOffset : TimelineStep::Kind::kNcToolLength;
      s.axis = RequireChannelAxis(m, nc, e["axis"]);
      s.target = e["value"].Double();
      if (offset) {
        s.code = e["G"].Int();
        if (s.code < 54 || s.code > 59) e["G"].Fail("expected 54..59");
        text << "zero offset G" << s.code << " " << e["axis"].String() << " = " << Fmt(s.target);
      } else {
        s.code = e["T"].Int();
        s.edge = e.Has("D") ? e["D"].Int() : 1;
        text << "tool T" << s.code << " D" << s.edge << " length " << e["axis"].String() << " = "
             << Fmt(s.target);
      }
    } else if (a.IsMap() && a.Has("single_block")) {
      a.AllowKeys({"single_block"});
      s.kind = TimelineStep::Kind::kNcSingleBlock;
      s.level = a["single_block"].Bool();
      text << "single block " << (s.level ? "on" : "off");
    } else if (a.IsMap() && a.Has("optional_stop")) {
      a.AllowKeys({"optional_stop"});
      s.kind = TimelineStep::Kind::kNcOptionalStop;
      s.level = a["optional_stop"].Bool();
      text << "optional stop " << (s.level ? "on" : "off");
    } else if (a.IsMap()) {
      a.AllowKeys({"override"});
      s.kind = TimelineStep::Kind::kNcOverride;
      s.target = a["override"].Double() / 100;
      if (s.target < 0 || s.target > 2) a["override"].Fail("must be 0..200 (percent)");
      text << "feed override " << Fmt(s.target * 100) << " %";
    } else {
      const std::string cmd = a.String();
      if (cmd == "start")
        s.kind = TimelineStep::Kind::kNcStart;
      else if (cmd == "stop")
        s.kind = TimelineStep::Kind::kNcStop;
      else if (cmd == "reset")
        s.kind = TimelineStep::Kind::kNcReset;
      else if (cmd == "reverse")
        s.kind = TimelineStep::Kind::kNcReverse;
      else
        a.Fail(
            "expected start, stop, reset, reverse, {mode: ..}, {override: percent}, "
            "{single_block: bool}, {optional_stop: bool}, {jog_increment: mm}, {jog_mode: 0..7} or {mdi: blocks}");
      text << "NC " << cmd;
    }
    s.text = text.str();
    return s;
  }

  if (n.Has("move")) {
    const YamlNode a = n["move"];
    a.AllowKeys({"axis", "to", "feed", "parameter_set"});
    s.kind = TimelineStep::Kind::kMove;
    s.drive = RequireDrive(m, a["axis"]);
    s.target = a["to"].Double();
    RequireWithinTravel(m, s.drive, s.target, a["to"]);
    s.feed = a["feed"].Double() / 60.0;  // mm/min | deg/min, as F words
    if (s.feed <= 0) a["feed"].Fail("must be > 0");
    text << "move " << a["axis"].String() << " to " << Fmt(s.target) << " at F" << Fmt(s.feed * 60);
    s.parameter_set = ReadDriveParameterSet(a, text);
  } else if (n.Has("speed")) {
    const YamlNode a = n["speed"];
    s.kind = TimelineStep::Kind::kSpeed;
    s.drive = RequireDrive(m, a["axis"]);
    if (IsRotary(m, s.drive)) {
      a.AllowKeys({"axis", "rpm", "parameter_set"});
      s.target = a["rpm"].Double() * 6.0;  // rpm -> deg/s
      text << "speed " << a["axis"].String() << " " << Fmt(a["rpm"].Double()) << " rpm";
    } else {
      a.AllowKeys({"axis", "feed", "parameter_set"});
      s.target = a["feed"].Double() / 60.0;
      text << "speed " << a["axis"].String() << " F" << Fmt(a["feed"].Double());
    }
    s.parameter_set = ReadDriveParameterSet(a, text);
  } else if (n.Has("orient")) {
    const YamlNode a = n["orient"];
    a.AllowKeys({"axis", "to", "parameter_set"});
    s.kind = TimelineStep::Kind::kOrient;
    s.drive = RequireDrive(m, a["axis"]);
    if (!m.drives[s.drive].spindle) a["axis"].Fail("orient needs a spindle drive");
    s.target = a["to"].Double();
    text << "orient " << a["axis"].String() << " to " << Fmt(s.target);
    s.parameter_set = ReadDriveParameterSet(a, text);
  } else if (n.Has("off")) {
    const YamlNode a = n["off"];
    a.AllowKeys({"axis"});
    s.kind = TimelineStep::Kind::kOff;
    s.drive = RequireDrive(m, a["axis"]);
    text << "controller enable off " << a["axis"].String();
  } else if (n.Has("output")) {
    const YamlNode a = n["output"];
    a.AllowKeys({"name", "value"});
    s.kind = TimelineStep::Kind::kOutput;
    s.io = RequireIo(m, a["name"]);
    if (!m.io[s.io].is_output) a["name"].Fail("'" + a["name"].String() + "' is an input");
    if (plc)
      a["name"].Fail("the scene's PLC program drives the valves (a fault: step makes one stick)");
    s.level = a["value"].Bool();
    text << "output " << a["name"].String() << " = " << (s.level ? 1 : 0);
  } else if (n.Has("wait")) {
    s.kind = TimelineStep::Kind::kWait;
    s.wait_s = n["wait"].Double();
    if (s.wait_s < 0) n["wait"].Fail("must be >= 0");
    text << "wait " << Fmt(s.wait_s) << " s";
  } else {
    const YamlNode a = n["wait_until"];
    s.kind = TimelineStep::Kind::kWaitUntil;
    s.until = ReadCondition(m, a, nc);
    s.timeout_s = a.Double("timeout", 10);
    text << "wait until";
    for (const std::string& k : a.Keys())
      if (k != "timeout") text << " " << k << "=" << a[k].String();
  }
  s.text = text.str();
  return s;
}

Expectation ReadExpectation(const MachineModel& m, const YamlNode& n, size_t i, const NcSetup& nc) {
  n.AllowKeys({"at", "axis", "position", "velocity", "rpm", "following_error", "parameter_set",
               "input", "value", "clutch", "state", "tol", "nc", "signal"});
  Expectation e{};
  e.at_s = n.Double("at", -1);
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
      e.value = n["parameter_set"].Int();
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
      e.tolerance = n["tol"].Double();
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
  } else {
    n.Fail("expected axis:, input:, clutch:, nc: or signal:");
  }
  text << (e.at_s < 0 ? std::string(" at the end") : " at " + Fmt(e.at_s) + " s");
  e.text = text.str();
  return e;
}

}  // namespace vmt::sim
