#include "control/measure/measuring_cycle.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <sstream>

#include "control/measure/compare.hpp"
#include "control/measure/correction.hpp"
#include "control/measure/nc_number.hpp"

namespace vmt::control::measure {
namespace {

constexpr double kMaxPosition = 100000.0;  // 2.1: positions and paths "± 100 000.000"
constexpr int kSequences = 10;             // 2.1 MOVE E / PROBE K: 1 - 10

std::string Written(const InstructionArg& a) {
  switch (a.kind) {
    case InstructionArg::Kind::kOmitted: return "";
    case InstructionArg::Kind::kName: return a.name;
    case InstructionArg::Kind::kValue: return NcNumber(a.value);
  }
  return "";
}

// The call as the program wrote it, the prefix of every error text.
std::string Written(const InstructionCall& call) {
  std::string text = std::string(nc::InstructionName(call.instruction)) + "(";
  for (size_t i = 0; i < call.args.size(); ++i) {
    if (i) text.push_back(',');
    text.append(Written(call.args[i]));
  }
  text.push_back(')');
  return text;
}

// Reads a call's arguments by the manual's letters; the first complaint sticks, later reads
// return nothing, so a planner reads on and checks `error` once.
struct Arguments {
  const InstructionCall& call;
  std::string error;

  void Fail(const std::string& what, const char* section) {
    if (error.empty()) error = Written(call) + ": " + what + " (" + section + ")";
  }
  static char Letter(int i) { return static_cast<char>('A' + i); }
  const InstructionArg* At(int i) const {
    return i < static_cast<int>(call.args.size()) ? &call.args[i] : nullptr;
  }
  bool Omitted(int i) const {
    const InstructionArg* a = At(i);
    return !a || a->kind == InstructionArg::Kind::kOmitted;
  }
  // The number written at i; nullopt when omitted (and an error if `required`) or a name.
  std::optional<double> Raw(int i, const char* what, bool required, const char* section) {
    if (!error.empty()) return std::nullopt;
    const InstructionArg* a = At(i);
    if (!a || a->kind == InstructionArg::Kind::kOmitted) {
      if (required) Fail(std::string(1, Letter(i)) + " (" + what + ") is missing", section);
      return std::nullopt;
    }
    if (a->kind == InstructionArg::Kind::kName) {
      Fail(std::string(1, Letter(i)) + " (" + what + ") " + a->name + " is not a number",
           section);
      return std::nullopt;
    }
    return a->value;
  }
  // A number in [lo, hi].
  std::optional<double> Number(int i, const char* what, double lo, double hi, bool required,
                               const char* section) {
    const std::optional<double> v = Raw(i, what, required, section);
    if (v && (!std::isfinite(*v) || *v < lo || *v > hi)) {
      Fail(std::string(1, Letter(i)) + " (" + what + ") " + NcNumber(*v) + " is not " +
               NcNumber(lo) + ".." + NcNumber(hi),
           section);
      return std::nullopt;
    }
    return v;
  }
  // A whole number in [lo, hi].
  std::optional<int> Whole(int i, const char* what, int lo, int hi, bool required,
                           const char* section) {
    const std::optional<double> v = Raw(i, what, required, section);
    if (!v) return std::nullopt;
    const std::optional<int> n = WholeNumber(*v);
    if (!n || *n < lo || *n > hi) {
      Fail(std::string(1, Letter(i)) + " (" + what + ") " + NcNumber(*v) + " is not " +
               std::to_string(lo) + ".." + std::to_string(hi),
           section);
      return std::nullopt;
    }
    return n;
  }
  // An axis designation: 4.1 allows the linear main axes X, Y, Z only.
  std::optional<char> Axis(int i, const char* what, bool required) {
    if (!error.empty()) return std::nullopt;
    const InstructionArg* a = At(i);
    if (!a || a->kind == InstructionArg::Kind::kOmitted) {
      if (required) Fail(std::string(1, Letter(i)) + " (" + what + ") is missing", "2.1");
      return std::nullopt;
    }
    if (a->kind != InstructionArg::Kind::kName) {
      Fail(std::string(1, Letter(i)) + " (" + what + ") " + Written(*a) +
               " is not an axis designation",
           "2.1");
      return std::nullopt;
    }
    std::string name = a->name;
    for (char& c : name) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    if (name == "X" || name == "Y" || name == "Z") return name[0];
    if (!name.empty() && (name[0] == 'U' || name[0] == 'V' || name[0] == 'W'))
      Fail(std::string(1, Letter(i)) + " (" + what + ") " + a->name +
               ": secondary axes are not permitted, only X, Y and Z",
           "4.1 Programmable NC Axes");
    else
      Fail(std::string(1, Letter(i)) + " (" + what + ") " + a->name +
               " is not one of the linear main axes X, Y, Z",
           "4.1 Programmable NC Axes");
    return std::nullopt;
  }
  // Places beyond `count` must be empty: RESTORE() may reach us as one omitted argument.
  bool AtMost(int count) {
    for (int i = count; i < static_cast<int>(call.args.size()); ++i)
      if (!Omitted(i)) {
        Fail("more than " + std::to_string(count) + " arguments", "2.1");
        break;
      }
    return error.empty();
  }
};

MeasuringPlan Failed(const std::string& error) {
  MeasuringPlan plan;
  plan.error = error;
  return plan;
}

uint8_t SettingAxes(const MeasuringSetting& s) {
  uint8_t mask = 0;
  for (int n = 0; n < 3; ++n)
    if (s.axis[n]) mask |= static_cast<uint8_t>(1u << n);
  return mask;
}

// 4.1 Diameter and Radius Programming: G16 refers to the X axis only; the plan is in radius.
double Radius(const MeasuringSetting& s, int n, double programmed) {
  return s.diameter && s.axis[n] == 'X' ? programmed / 2 : programmed;
}

MeasuringStep Event(int event, bool value) {
  MeasuringStep step;
  step.kind = MeasuringStep::Kind::kEvent;
  step.event = event;
  step.value = value;
  return step;
}

MeasuringStep Rapid(const std::array<double, 3>& target, uint8_t axes, int sphere) {
  MeasuringStep step;
  step.kind = MeasuringStep::Kind::kRapid;
  step.target = target;
  step.axes = axes;
  step.sphere = sphere;
  return step;
}

// Every instruction but SETTING needs the setting (2.1 "Position in the NC program").
bool NeedSetting(const MeasuringContext& context, Arguments& args) {
  if (!context.setting) args.Fail("no SETTING before this instruction", "2.1 SETTING");
  return args.error.empty();
}

// 4.1 Tool Path and Length Correction: G40 before MOVE and PROBE.
bool NeedG40(const MeasuringContext& context, Arguments& args) {
  if (context.compensation != nc::Compensation::kOff)
    args.Fail("tool path correction G" + std::to_string(nc::GCode(context.compensation)) +
                  " is active; program G40 before MOVE and PROBE",
              "4.1 Tool Path and Length Correction");
  return args.error.empty();
}

// 2.1 MOVE / PROBE: "At the beginning, the G code groups 1, 2, 3, 5, 6, 7, 13 are saved in the
// buffer page" (and written back at the end: the plan's own moves say G00/G01 G94 themselves and
// leave the program's modal state alone, so writing back changes nothing here).
void SaveGGroups(const MeasuringContext& context, MeasuringPages& pages) {
  pages.buffer[context.process].g_group = context.g_groups;
}

// 4.4: whether an instruction of reverse variant `variant` opens its record: single point keeps
// only the instruction in progress; a linear path sequence is opened by its first instruction
// and ends when an instruction of another variant follows it.
bool StartsSequence(const ReverseVectors& reverse, int variant) {
  return variant == 0 || reverse.active != variant || reverse.sequence[variant - 1].empty();
}

// The instruction's points go into the record when it is planned, not as the stylus reaches
// them: the record holds where the stylus starts and each point it is to pass on its way in
// (not the escape, which retraces them), so the reversal takes it back out the way it came.
void Record(ReverseVectors& reverse, int variant, int sphere, const std::array<double, 3>& start,
            const std::vector<std::array<double, 3>>& points) {
  if (reverse.active != variant) {
    if (reverse.active == 0)
      reverse.single_point.clear();
    else
      reverse.sequence[reverse.active - 1].clear();
  }
  std::vector<ReversePoint>& list =
      variant == 0 ? reverse.single_point : reverse.sequence[variant - 1];
  if (StartsSequence(reverse, variant)) {
    list.clear();
    list.push_back({start, sphere});
  }
  for (const std::array<double, 3>& p : points) list.push_back({p, sphere});
  reverse.active = variant;
}

bool ValidProcess(const MeasuringContext& context, const MeasuringPages& pages,
                  Arguments& args) {
  if (context.process < 0 || context.process >= static_cast<int>(pages.basis.size()))
    args.Fail("process " + std::to_string(context.process) + " has no measuring pages", "3.1");
  return args.error.empty();
}

MeasuringPlan PlanSetting(Arguments& args, const MeasuringContext& context,
                          MeasuringPages& pages) {
  const char* kSection = "2.1 SETTING";
  args.AtMost(7);
  MeasuringSetting s;
  if (context.setting) s.saved = context.setting->saved;
  for (int n = 0; n < 3; ++n) {
    const char* what[] = {"axis 1", "axis 2", "axis 3"};
    if (std::optional<char> a = args.Axis(n, what[n], false)) s.axis[n] = *a;
  }
  if (!args.error.empty()) return Failed(args.error);
  if (SettingAxes(s) == 0) args.Fail("no measuring axis", kSection);
  for (int n = 0; n < 3; ++n)
    for (int m = n + 1; m < 3; ++m)
      if (s.axis[n] && s.axis[n] == s.axis[m])
        args.Fail(std::string("axis ") + s.axis[n] + " given twice", kSection);

  const std::optional<int> plane = args.Whole(3, "plane selection", 0, 99, true, kSection);
  if (plane && (*plane == 20 || *plane == 29))
    args.Fail("free plane selection G20 (G" + std::to_string(*plane) + ") cannot be used",
              "4.1 Plane Selection");
  else if (plane && (*plane < 17 || *plane > 19))
    args.Fail("D (plane selection) " + std::to_string(*plane) + " is not 17, 18, 19", kSection);
  const std::optional<int> length = args.Whole(4, "tool length correction", 0, 99, true, kSection);
  if (length && *length == 49)
    args.Fail("G49 (negative tool length correction) cannot be programmed",
              "4.1 Tool Path and Length Correction");
  else if (length && *length != 47 && *length != 48)
    args.Fail("E (tool length correction) " + std::to_string(*length) + " is not 47, 48, 49",
              kSection);
  else if (length && *length == 48 && !context.tool_list)
    args.Fail("G48 requires a tools list and there is none; program G47",
              "4.1 Tool Path and Length Correction");
  const std::optional<int> radius = args.Whole(5, "radius/diameter programming", 0, 99, true,
                                               kSection);
  if (radius && *radius != 15 && *radius != 16)
    args.Fail("F (radius/diameter programming) " + std::to_string(*radius) + " is not 15, 16",
              kSection);
  else if (radius && *radius == 16 && !context.turning)
    args.Fail("diameter programming G16 is only possible in turning",
              "4.1 Diameter and Radius Programming");
  else if (radius && *radius == 16 && std::find(s.axis.begin(), s.axis.end(), 'Y') != s.axis.end())
    args.Fail("with G16 only the axes X and Z are entered", "4.1 Diameter and Radius Programming");
  // G: the stylus 1..4 (TASTWERKZEUGPAGE LV1). The manual's own programs (5.1, 5.2, 5.6) write
  // 25 there, which can only be the stylus' T number (TASTWERKZEUGPAGE element 1: "the user must
  // know the T number under which the stylus has been entered"), so a G outside 1..4 names the
  // stylus whose T number it is.
  const std::optional<int> stylus = args.Whole(6, "stylus number", -1000000000, 1000000000, true,
                                               kSection);
  if (stylus && *stylus >= 1 && *stylus <= kStyluses) {
    s.stylus = *stylus;
  } else if (stylus) {
    s.stylus = 0;
    for (int k = 0; k < kStyluses; ++k)
      if (pages.stylus[k].tool_number == *stylus) s.stylus = k + 1;
    if (s.stylus == 0)
      args.Fail("G (stylus number) " + std::to_string(*stylus) +
                    " is neither 1..4 nor the T number of a stylus in TASTWERKZEUGPAGE",
                kSection);
  }
  if (!args.error.empty() || !ValidProcess(context, pages, args)) return Failed(args.error);
  s.plane = static_cast<nc::Plane>(*plane);  // 17..19, checked above
  s.tool_length = static_cast<nc::ToolLength>(*length);  // 47 or 48, checked above
  s.diameter = *radius == 16;

  // 3.1 BASISMESSPAGE 6..10 for the PLC's measuring block, which reads them on Q9992 (6.1).
  const TastwerkzeugPage& t = pages.stylus[s.stylus - 1];
  BasisMessPage& basis = pages.basis[context.process];
  basis.PIN_DDS = t.pin5;
  basis.Pushbutton_contact = t.normally_closed;
  basis.measuring_axis_1 = s.axis[0] != 0;
  basis.measuring_axis_2 = s.axis[1] != 0;
  basis.measuring_axis_3 = s.axis[2] != 0;

  MeasuringPlan plan;
  MeasuringStep q;
  q.kind = MeasuringStep::Kind::kAux;
  q.q = kQ9992;
  plan.steps.push_back(q);
  plan.setting = s;
  return plan;
}

MeasuringPlan PlanSave(Arguments& args, const MeasuringContext& context, MeasuringPages& pages) {
  const char* kSection = "2.1 SAVE";
  args.AtMost(3);
  if (!NeedSetting(context, args)) return Failed(args.error);
  std::array<bool, 3> saved{};
  const char* what[] = {"variables 100 - 112", "axis positions", "F value"};
  for (int k = 0; k < 3; ++k)
    if (std::optional<int> v = args.Whole(k, what[k], 0, 1, true, kSection)) saved[k] = *v == 1;
  if (!args.error.empty() || !ValidProcess(context, pages, args)) return Failed(args.error);
  ZwischenspeicherPage& buffer = pages.buffer[context.process];
  if (saved[0]) buffer.variable = context.variables;
  if (saved[1])
    for (int n = 0; n < 3; ++n)  // the page holds what the program writes: diameters under G16
      buffer.axis_position[n] = context.setting->diameter && context.setting->axis[n] == 'X'
                                    ? 2 * context.position[n]
                                    : context.position[n];
  if (saved[2]) buffer.F_value = context.feed;
  MeasuringPlan plan;
  plan.setting = *context.setting;
  plan.setting->saved = saved;
  return plan;
}

MeasuringPlan PlanRestore(Arguments& args, const MeasuringContext& context,
                          const MeasuringPages& pages) {
  args.AtMost(0);
  if (!NeedSetting(context, args)) return Failed(args.error);
  if (!context.setting->saved) args.Fail("no SAVE before RESTORE", "2.1 RESTORE");
  if (!args.error.empty() || !ValidProcess(context, pages, args)) return Failed(args.error);
  const ZwischenspeicherPage& buffer = pages.buffer[context.process];
  MeasuringPlan plan;
  // 2.1 RESTORE: "refers to the settings that have been programmed in SAVE( )"; the axis
  // positions are not moved.
  if ((*context.setting->saved)[0]) plan.restore_variables = buffer.variable;
  if ((*context.setting->saved)[2]) plan.restore_feed = buffer.F_value;
  return plan;
}

// The sphere I / D of the setting's stylus and its radius (TASTWERKZEUGPAGE 4..8).
double SphereRadius(const MeasuringPages& pages, const MeasuringSetting& s, int sphere) {
  return pages.stylus[s.stylus - 1].sphere_radius[sphere - 1];
}

// The reverse variant E / K: 0 single point, 1..10 a linear path sequence.
std::optional<int> ReverseVariant(Arguments& args, int i, const char* section) {
  return args.Whole(i, "reverse variant", 0, kSequences, true, section);
}

MeasuringPlan PlanMove(Arguments& args, const MeasuringContext& context, MeasuringPages& pages,
                       ReverseVectors& reverse) {
  const char* kSection = "2.1 MOVE";
  args.AtMost(5);
  if (!NeedSetting(context, args) || !NeedG40(context, args)) return Failed(args.error);
  const MeasuringSetting& s = *context.setting;
  std::array<std::optional<double>, 3> given;
  const char* what[] = {"position of axis 1", "position of axis 2", "position of axis 3"};
  for (int n = 0; n < 3; ++n) {
    given[n] = args.Number(n, what[n], -kMaxPosition, kMaxPosition, false, kSection);
    if (given[n] && !s.axis[n])
      args.Fail(std::string(what[n]) + " given, but SETTING has no axis " + std::to_string(n + 1),
                kSection);
  }
  const std::optional<int> sphere = args.Whole(3, "measuring sphere number", 1, kSpheres, true,
                                               kSection);
  const std::optional<int> variant = ReverseVariant(args, 4, kSection);
  if (!args.error.empty()) return Failed(args.error);
  if (*variant != 0 && StartsSequence(reverse, *variant))
    for (int n = 0; n < 3; ++n)
      if (s.axis[n] && !given[n])
        args.Fail(std::string("first MOVE of linear path sequence ") + std::to_string(*variant) +
                      " must give the position of every SETTING axis; " + s.axis[n] +
                      " is missing",
                  "4.4");
  if (!args.error.empty() || !ValidProcess(context, pages, args)) return Failed(args.error);

  SaveGGroups(context, pages);
  std::array<double, 3> target = context.position;
  uint8_t axes = 0;
  for (int n = 0; n < 3; ++n)
    if (given[n]) {
      // 4.3: the position is the sphere centre's; the sphere radius is not taken into account.
      target[n] = Radius(s, n, *given[n]);
      axes |= static_cast<uint8_t>(1u << n);
    }
  MeasuringPlan plan;
  // 6.2 Event 29: set at the beginning of MOVE and PROBE, the PLC's collision monitoring. Figure
  // 6-25 is the PROBE's exchange: only there does E30 hand over to measuring path monitoring
  // (and the PLC acknowledge by resetting E29). A MOVE never enters a measuring path, so it
  // ends with E29 still set: collision monitoring stays on while the stylus travels free.
  plan.steps.push_back(Event(29, true));
  if (axes) plan.steps.push_back(Rapid(target, axes, *sphere));
  plan.reverse_variant = *variant;
  Record(reverse, *variant, *sphere, context.position, {target});
  return plan;
}

// PROBE's arguments (2.1), each checked; those that may be omitted are nullopt then.
struct ProbeCall {
  std::optional<int> calibration;  ///< 0: a calibration, 1: a measurement
  std::optional<int> point;        ///< the point page entry
  std::array<std::optional<double>, 3> position;
  int axis = -1;  ///< the measuring axis, an index into the SETTING's axes
  std::optional<double> path, feed;
  std::optional<int> sphere, approach, variant;
};

// False with args.error set if an argument is wrong or the process may not measure.
bool ReadProbeCall(Arguments& args, const MeasuringContext& context, MeasuringPages& pages,
                   ProbeCall& call) {
  const char* kSection = "2.1 PROBE";
  args.AtMost(11);
  if (!NeedSetting(context, args) || !NeedG40(context, args)) return false;
  const MeasuringSetting& s = *context.setting;
  call.calibration = args.Whole(1, "calibration/measurement", 0, 1, true, kSection);
  // A: the point page entry; a calibration point is not written there and may omit it (5.1).
  if (call.calibration && (*call.calibration == 1 || !args.Omitted(0)))
    call.point = args.Whole(0, "point number", 1, pages.config.points, true, kSection);
  std::array<std::optional<double>, 3>& position = call.position;
  const char* what[] = {"measuring position of axis 1", "measuring position of axis 2",
                        "measuring position of axis 3"};
  for (int n = 0; n < 3; ++n) {
    position[n] = args.Number(2 + n, what[n], -kMaxPosition, kMaxPosition, false, kSection);
    if (!args.error.empty()) break;
    // A test point is a point: every SETTING axis has its coordinate, an empty place none.
    if (position[n] && !s.axis[n])
      args.Fail(std::string(what[n]) + " given, but SETTING has no axis " + std::to_string(n + 1),
                kSection);
    else if (!position[n] && s.axis[n])
      args.Fail(std::string(what[n]) + " (" + s.axis[n] + ") is missing", kSection);
  }
  const std::optional<char> axis_name = args.Axis(5, "measuring axis", true);
  int& axis = call.axis;
  if (axis_name) {
    for (int n = 0; n < 3; ++n)
      if (s.axis[n] == *axis_name) axis = n;
    if (axis < 0)
      args.Fail(std::string("measuring axis ") + *axis_name + " is not an axis of the SETTING",
                "4.1 Programmable NC Axes");
  }
  call.path = args.Number(6, "measuring path", -kMaxPosition, kMaxPosition, true, kSection);
  if (call.path && *call.path == 0)
    args.Fail("G (measuring path) 0: there is no measuring move", kSection);
  call.feed = args.Number(7, "measuring feed", 0, 1e9, true, kSection);
  if (call.feed && *call.feed <= 0) args.Fail("H (measuring feed) must be above 0", kSection);
  call.sphere = args.Whole(8, "measuring sphere number", 1, kSpheres, true, kSection);
  call.approach = args.Whole(9, "approach variant", 1, 4, true, kSection);
  call.variant = ReverseVariant(args, 10, kSection);
  if (!args.error.empty()) return false;
  if (*call.calibration == 0 && *call.variant != 0)
    args.Fail("a calibration PROBE may not be in a linear path sequence (K " +
                  std::to_string(*call.variant) + ")",
              "4.4");
  return args.error.empty() && ValidProcess(context, pages, args);
}

MeasuringPlan PlanProbe(Arguments& args, const MeasuringContext& context, MeasuringPages& pages,
                        ReverseVectors& reverse) {
  ProbeCall call;
  if (!ReadProbeCall(args, context, pages, call)) return Failed(args.error);
  const MeasuringSetting& s = *context.setting;
  const int axis = call.axis;
  const double path = *call.path, feed = *call.feed;
  const int sphere = *call.sphere, approach = *call.approach, variant = *call.variant;
  const int calibration = *call.calibration;
  MeasuringPlan plan;
  // 3.1 ZWISCHENSPEICHERPAGE element 1 "enables the user to hide the programmed calibration
  // points": such a PROBE does nothing at all.
  if (calibration == 0 && pages.buffer[context.process].calibration_off) return plan;

  SaveGGroups(context, pages);
  const double radius = SphereRadius(pages, s, sphere);
  const uint8_t all = SettingAxes(s);
  const uint8_t measuring = static_cast<uint8_t>(1u << axis);
  const uint8_t across = static_cast<uint8_t>(all & ~measuring);
  // 4.5: the programmed measuring path is the distance to the surface, in the program's
  // measure: under G16 a path along X is a diameter and the stylus stands half of it away.
  const double gap = std::abs(Radius(s, axis, path));
  const int direction = path > 0 ? 1 : -1;

  std::array<double, 3> surface{};
  for (int n = 0; n < 3; ++n)
    if (s.axis[n]) surface[n] = Radius(s, n, *call.position[n]);
  // Setup position (4.2, 4.5): the sphere centre stands the measuring path plus the sphere
  // radius before the surface, against the measuring direction.
  std::array<double, 3> setup = surface;
  setup[axis] = surface[axis] - direction * (gap + radius);
  // 4.5: the actual measuring path is twice the programmed one, so a surface up to one path
  // beyond its command value is still found.
  std::array<double, 3> end = setup;
  end[axis] = setup[axis] + direction * 2 * gap;
  const bool indirect = approach == 2 || approach == 4;
  const bool escape = approach == 1 || approach == 2;
  const std::array<double, 3> start = context.position;
  // 4.2 positioning logic: first parallel to the measuring path into the plane through the
  // setup position perpendicular to the measuring direction, then across to the setup position.
  std::array<double, 3> plane_point = start;
  plane_point[axis] = setup[axis];

  plan.steps.push_back(Event(29, true));  // 6.2: collision monitoring
  std::vector<std::array<double, 3>> passed;
  if (indirect) {
    plan.steps.push_back(Rapid(plane_point, measuring, sphere));
    if (across) plan.steps.push_back(Rapid(setup, across, sphere));
    passed.push_back(plane_point);
  } else {
    plan.steps.push_back(Rapid(setup, all, sphere));  // 4.2: all axes together
  }
  passed.push_back(setup);
  // 6.2 Event 30 / figure 6-25: at the setup position the measuring path begins; the PLC
  // switches collision monitoring off and measuring path monitoring on and acknowledges by
  // resetting E29 before the stylus moves on.
  plan.steps.push_back(Event(30, true));
  MeasuringStep wait;
  wait.kind = MeasuringStep::Kind::kWaitEvent;
  wait.event = 29;
  wait.value = false;
  plan.steps.push_back(wait);
  MeasuringStep measure;
  measure.kind = MeasuringStep::Kind::kMeasure;
  measure.target = end;
  measure.axes = measuring;
  measure.feed = feed;
  measure.sphere = sphere;
  plan.steps.push_back(measure);
  plan.steps.push_back(Event(30, false));
  // Off the surface again: back to the setup position, where the variants without escape stay.
  plan.steps.push_back(Rapid(setup, measuring, sphere));
  if (escape) {
    // 4.2: escape in the reverse order of the approach.
    if (indirect) {
      if (across) plan.steps.push_back(Rapid(plane_point, across, sphere));
      plan.steps.push_back(Rapid(start, measuring, sphere));
    } else {
      plan.steps.push_back(Rapid(start, all, sphere));
    }
  }
  // 3.1 EICHWERTEPAGE keeps each direction's calibration value beside the feed it was found
  // at: the deflection, switching travel and latch delay the value holds grow with the feed, so
  // at another feed the measured value is off by the difference. The manual has no message
  // for it (its PROBE does not check the feed, 4.1 Feed Programming): vmt warns and measures.
  const double calibration_feed =
      pages.calibration[static_cast<size_t>(s.stylus - 1)][static_cast<size_t>(sphere - 1)]
          .measuring_feed[static_cast<size_t>(2 * axis + (direction < 0 ? 1 : 0))];
  if (calibration == 1 && calibration_feed > 0 && feed != calibration_feed) {
    std::ostringstream w;
    w << "PROBE measures at F" << feed << " but axis " << s.axis[axis]
      << (direction < 0 ? '-' : '+') << " of sphere " << sphere << " was calibrated at F"
      << calibration_feed << ": the measured value is off by the latch delay's difference (3.1)";
    plan.warning = w.str();
  }
  plan.measuring_axis = axis;
  plan.direction = direction;
  plan.command = surface[axis];
  plan.reverse_variant = variant;
  Record(reverse, variant, sphere, start, passed);
  return plan;
}

// The values of a call that takes numbers only, omitted ones as nullopt.
std::vector<std::optional<double>> Values(Arguments& args, int count, const char* section) {
  std::vector<std::optional<double>> v(count);
  args.AtMost(count);
  for (int i = 0; i < count; ++i) {
    const InstructionArg* a = args.At(i);
    if (a && a->kind == InstructionArg::Kind::kName)
      args.Fail(std::string(1, Arguments::Letter(i)) + " " + a->name + " is not a number", section);
    else if (a && a->kind == InstructionArg::Kind::kValue)
      v[i] = a->value;
  }
  return v;
}

MeasuringPlan PlanCompare(Arguments& args, const MeasuringContext& context,
                          MeasuringPages& pages) {
  const char* kSection = "2.1 COMPARE";
  if (!NeedSetting(context, args)) return Failed(args.error);
  const std::vector<std::optional<double>> v = Values(args, 4, kSection);
  if (!v[0]) args.Fail("A (storage point number) is missing", kSection);
  if (!v[1]) args.Fail("B (comparison strategy) is missing", kSection);
  if (!args.error.empty()) return Failed(args.error);
  const std::string why = Compare(pages, context.process, {*v[0], *v[1], v[2], v[3]});
  // Compare names the call itself; its arguments are the program's, so add the section only.
  return why.empty() ? MeasuringPlan{} : Failed(why + " (" + kSection + ")");
}

MeasuringPlan PlanCorrection(Arguments& args, const MeasuringContext& context,
                             MeasuringPages& pages) {
  const char* kSection = "2.1 CORRECTION";
  if (!NeedSetting(context, args)) return Failed(args.error);
  const std::vector<std::optional<double>> v = Values(args, 10, kSection);
  const char* what[] = {"compare number",   "upper allowance",     "lower allowance",
                        "upper limit",      "correction limit",    "empirical value",
                        "correction strategy", "weighting/percentage factor",
                        "partial correction", "lower limit"};
  for (int i = 0; i < 10; ++i)
    if (!v[i])
      args.Fail(std::string(1, Arguments::Letter(i)) + " (" + what[i] + ") is missing", kSection);
  if (!args.error.empty()) return Failed(args.error);
  const CorrectionInstruction in = {*v[0], *v[1], *v[2], *v[3], *v[4],
                                    *v[5], *v[6], *v[7], *v[8], *v[9]};
  const CorrectionRun run = RunCorrection(pages, context.process, in);
  if (!run.error.empty()) return Failed(run.error + " (" + kSection + ")");
  MeasuringPlan plan;
  // 4.6 Dimensional accuracy / 6.1: the message and its Q function (Q9998 / Q9999) to issue.
  if (const std::optional<MeasuringMessage>& m = run.correction.message) {
    for (const MeasuringMessage* known :
         {&kOversize, &kUndersize, &kCheckTool, &kIllegallyHighDimensionalDeviation})
      if (known->q_function == m->q_function && std::strcmp(known->text, m->text) == 0)
        plan.message = known;
  }
  return plan;
}

}  // namespace

std::vector<ReversePoint>& ReverseVectors::Active() {
  return active == 0 ? single_point : sequence[static_cast<size_t>(std::clamp(active, 1, 10) - 1)];
}

const std::vector<ReversePoint>& ReverseVectors::Active() const {
  return active == 0 ? single_point : sequence[static_cast<size_t>(std::clamp(active, 1, 10) - 1)];
}

std::vector<ReversePoint> ReverseVectors::Reversal() const {
  const std::vector<ReversePoint>& list = Active();
  return {list.rbegin(), list.rend()};
}

MeasuringPlan PlanInstruction(const InstructionCall& call, const MeasuringContext& context,
                              MeasuringPages& pages, ReverseVectors& reverse) {
  Arguments args{call, ""};
  using nc::Instruction;
  switch (call.instruction) {
    case Instruction::kSetting:
      return PlanSetting(args, context, pages);
    case Instruction::kSave:
      return PlanSave(args, context, pages);
    case Instruction::kMove:
      return PlanMove(args, context, pages, reverse);
    case Instruction::kProbe:
      return PlanProbe(args, context, pages, reverse);
    case Instruction::kCompare:
      return PlanCompare(args, context, pages);
    case Instruction::kCorrection:
      return PlanCorrection(args, context, pages);
    case Instruction::kRestore:
      return PlanRestore(args, context, pages);
    default:
      return Failed(Written(call) + ": not a measuring instruction (2)");
  }
}

const MeasuringMessage* FinishProbe(const InstructionCall& call, const MeasuringPlan& plan,
                                    const MeasuringContext& context, MeasuringPages& pages,
                                    std::optional<double> contact) {
  // A hidden calibration (no steps) or a plan that failed: nothing was measured.
  if (plan.measuring_axis < 0 || !context.setting || call.args.size() < 9) return nullptr;
  // 6.1: no switch on the whole measuring path (a latch that is not a number is none either).
  if (!contact || !std::isfinite(*contact)) return &kTestPointNotFound;
  const MeasuringSetting& s = *context.setting;
  const int axis = plan.measuring_axis;
  const int sphere = static_cast<int>(call.args[8].value);
  const double radius = SphereRadius(pages, s, sphere);
  // EICHWERTEPAGE: per sphere of the stylus, per measuring direction (the direction the stylus
  // moves in): axis n +, axis n -.
  EichwertePage& page = pages.calibration[s.stylus - 1][sphere - 1];
  const int slot = 2 * axis + (plan.direction < 0 ? 1 : 0);
  const bool calibration = call.args[1].value == 0;
  // The surface touched lies one effective radius from the centre, in the measuring direction;
  // the effective radius is the sphere radius plus the direction's calibration value (what
  // deflection, switching travel and latch delay at this feed add to it). Calibration on a
  // surface whose position is the command value solves the same relation for that value, so a
  // measurement of the same surface afterwards reads the command value exactly.
  if (calibration) {
    page.measuring_direction[slot] = plan.direction * (plan.command - *contact) - radius;
    // 3.1: the page holds the measuring feed of each direction beside its value: the value is
    // only right at the feed it was found at.
    page.measuring_feed[slot] = call.args[7].value;
    return nullptr;
  }
  const double actual = *contact + plan.direction * (radius + page.measuring_direction[slot]);
  RecordTestPoint(pages, context.process, call.args[0].value, s.axis[axis], plan.command, actual);
  return nullptr;
}

}  // namespace vmt::control::measure
