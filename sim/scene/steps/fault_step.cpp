// `fault: {...}`: fault injection, what breaks on a real machine, for the PLC program and the NC
// to meet: a sensor or valve stuck, a drive not ready, a PLC that misses scans or is gone, and
// the clearing of a fault.
#include "sim/model/yaml_reader.hpp"
#include "sim/scene/scene_steps.hpp"
#include "sim/scene/steps/step_kind.hpp"

namespace vmt::sim {
namespace {

void Read(const StepSource& src, TimelineStep& s, std::ostringstream& text) {
  const MachineModel& m = src.m;
  const YamlNode f = src.n["fault"];
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
}

bool Play(const TimelineStep& s, const StepTick&, TimelinePlay& play) {
  using F = TimelineStep::Fault;
  InjectedFaults& faults = play.faults;
  faults.any = true;
  if (s.fault == F::kSensorStuck) faults.sensor[s.io] = s.level;
  if (s.fault == F::kValveStuck) faults.valve[s.io] = s.level;
  if (s.fault == F::kDrive) faults.drive[s.drive] = true;
  if (s.fault == F::kPlcOverrun) faults.plc_missed_scans = s.code;
  if (s.fault == F::kPlcClientGone) ++faults.plc_client_gone;
  if (s.fault == F::kClear && s.io >= 0) faults.sensor[s.io] = faults.valve[s.io] = -1;
  if (s.fault == F::kClear && s.drive >= 0) faults.drive[s.drive] = false;
  return true;
}

}  // namespace

const StepKind kFaultStep{"fault", Read, Play};

}  // namespace vmt::sim
