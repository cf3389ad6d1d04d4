#include "control/channel/fast_measurement.hpp"

#include <algorithm>
#include <cmath>

#include "control/channel/channel_messages.hpp"

namespace vmt::control::channel {

namespace {

/// 6.2 Event 7: the PLC's measuring block sets it when the probe is displaced.
constexpr int kTouchEvent = 7;
/// 6.2 Event 29: collision monitoring, from the start of MOVE / PROBE to the PLC's
/// acknowledgement at the setup position.
constexpr int kCollisionEvent = 29;

/// The latch of `input` that the stylus' switching edge fills, or the other one, or none.
const ProbeEdgeLatch* Latched(const ProbeInputStatus& input, bool normally_closed) {
  const ProbeEdgeLatch& closing = normally_closed ? input.negative : input.positive;
  const ProbeEdgeLatch& other = normally_closed ? input.positive : input.negative;
  if (closing.latched) return &closing;
  if (other.latched) return &other;
  return nullptr;
}

/// Event `n` as BES reads it: the PLC's, or the program's own without a source.
bool EventSet(const ProgramEvents& events, int n) {
  if (events.source) return events.source(n);
  auto it = events.own.find(n);
  return it != events.own.end() && it->second;
}

/// Q function `q` goes to the PLC, with a new strobe.
void OutputQ(AuxOutput& aux, int q) {
  aux.functions.push_back({'Q', 0, static_cast<double>(q)});
  ++aux.strobe;
}

}  // namespace

FastMeasurement::FastMeasurement(const ChannelConfig& config)
    : tool_list_(!config.tools.edges.empty()), aux_handshake_(config.aux_handshake) {
  for (const ChannelAxis& a : config.axes) {
    names_.push_back(a.name);
    drives_.push_back(a.drive);
  }
}

int FastMeasurement::SettingAxis(int n) const {
  if (!data_.setting || n < 0 || n > 2 || data_.setting->axis[n] == 0) return -1;
  const std::string name(1, data_.setting->axis[n]);
  for (size_t a = 0; a < names_.size(); ++a)
    if (names_[a] == name) return static_cast<int>(a);
  return -1;
}

std::vector<double> FastMeasurement::StylusTranslation(const MeasuringLink& c, int sphere) const {
  nc::ModalState m = c.work.block.modal;
  if (data_.setting && data_.pages) {
    const int stylus = data_.setting->stylus;
    m.tool = data_.pages->stylus[static_cast<size_t>(stylus - 1)].tool_number;
    m.correction = sphere;
    m.tool_length = data_.setting->tool_length;
  }
  return c.translation_of(m);
}

measure::MeasuringContext FastMeasurement::ContextNow(const MeasuringLink& c) const {
  measure::MeasuringContext mc;
  mc.setting = data_.setting;
  bool x = false, y = false, z = false;
  for (const std::string& name : names_) {
    x |= name == "X";
    y |= name == "Y";
    z |= name == "Z";
  }
  mc.turning = x && z && !y;
  mc.tool_list = tool_list_;
  const nc::ModalState& m = data_.run ? data_.run->block.modal : c.work.block.modal;
  mc.compensation = m.compensation;
  // The sphere the instruction names (MOVE D, PROBE I): the position is its centre's.
  int sphere = 1;
  if (!c.work.block.calls.empty()) {
    const nc::InstructionCall& call = c.work.block.calls.front();
    const size_t at = call.instruction == nc::Instruction::kMove    ? 3
                      : call.instruction == nc::Instruction::kProbe ? 8
                                                                    : call.args.size();
    if (at < call.args.size() && call.args[at].kind == nc::InstructionArg::Kind::kValue &&
        call.args[at].value >= 1 && call.args[at].value <= measure::kSpheres)
      sphere = static_cast<int>(call.args[at].value);
  }
  const std::vector<double> t = StylusTranslation(c, sphere);
  for (int n = 0; n < 3; ++n) {
    const int a = SettingAxis(n);
    if (a >= 0) mc.position[n] = c.commanded[a] - t[a];
  }
  for (size_t i = 0; i < measure::kSavedGGroups.size(); ++i) {
    bool known = false;
    mc.g_groups[i] =
        static_cast<int16_t>(nc::ModalGroupValue(m, 'G', measure::kSavedGGroups[i], known));
  }
  for (size_t i = 0; i < mc.variables.size(); ++i)
    mc.variables[i] =
        c.work.interpreter ? c.work.interpreter->Variable("@" + std::to_string(100 + i)) : 0;
  mc.feed = m.feed;
  return mc;
}

void FastMeasurement::ApplyState(const MeasuringLink& c, const measure::MeasuringPlan& plan) {
  nc::Interpreter& interpreter = *c.work.interpreter;
  if (plan.setting) {
    // SETTING: its G codes are modal in the program from here (2.1: "Activating the G
    // functions"), as in the blocks the real control generates.
    data_.setting = plan.setting;
    nc::ModalState m = interpreter.modal();
    m.plane = plan.setting->plane;
    m.tool_length = plan.setting->tool_length;
    m.diameter = plan.setting->diameter;
    interpreter.SetModal(m);
  }
  if (plan.restore_variables)
    for (size_t i = 0; i < plan.restore_variables->size(); ++i)
      interpreter.SetVariable("@" + std::to_string(100 + i), (*plan.restore_variables)[i]);
  if (plan.restore_feed) {
    nc::ModalState m = interpreter.modal();
    m.feed = *plan.restore_feed;
    interpreter.SetModal(m);
  }
}

bool FastMeasurement::Start(const MeasuringLink& c) {
  const nc::PreparedBlock& block = c.work.block;
  const nc::Program& program = c.program_of(block.program);
  auto fail = [&](const std::string& text) {
    c.fail({text, kMsgMeasuringInstruction, block.program, block.block, false});
    return false;
  };
  // 4.1 Entering the NC Instructions: one instruction per block, nothing else in it, and not a
  // skippable block: the instruction becomes several blocks of its own.
  if (block.calls.size() > 1)
    return fail("only one measuring instruction may be programmed in a block (4.1)");
  if (block.instructions.size() > 1 || block.programmed != 0 || !block.aux.empty() ||
      !block.events.empty() || block.dwell_s > 0 || block.homing || block.repos ||
      block.set_position)
    return fail("a block with a measuring instruction may hold no other NC syntax (4.1)");
  if (program.blocks[static_cast<size_t>(block.block)].skippable)
    return fail("a block with a measuring instruction may not be a skipped block (4.1)");
  if (!data_.pages) return fail("fast measurement needs its machine data pages (7.1)");

  MeasuringRun run;
  run.block = block;
  run.call = block.calls.front();
  data_.run.emplace(std::move(run));
  data_.run->context = ContextNow(c);
  data_.run->context.compensation = block.modal.compensation;
  const measure::ReverseVectors before = data_.reverse_vectors;
  data_.run->plan = measure::PlanInstruction(data_.run->call, data_.run->context, *data_.pages,
                                             data_.reverse_vectors);
  // Which of the recorded points the stylus already stands at or has passed: the start of a
  // new record, or the whole record a linear path sequence continues.
  const int variant = data_.reverse_vectors.active;
  const auto& list_before =
      variant == 0 ? before.single_point : before.sequence[static_cast<size_t>(variant - 1)];
  const bool continued = variant != 0 && before.active == variant && !list_before.empty();
  data_.run->reached = continued ? list_before.size() : 1;
  if (!data_.run->plan.error.empty()) {
    const std::string error = data_.run->plan.error;
    data_.run.reset();
    return fail(error);
  }
  const measure::MeasuringPlan& plan = data_.run->plan;
  if (!plan.warning.empty()) {
    const nc::SourcePos& pos = program.blocks[static_cast<size_t>(block.block)].pos;
    data_.warnings.push_back(
        (pos.file < program.files.size() ? program.files[pos.file] : "<input>") + ":" +
        std::to_string(pos.line) + ":" + std::to_string(pos.column) + ": warning: " + plan.warning);
  }
  ApplyState(c, plan);
  // The blocks generated for the instruction run in the setting's G codes (a plan that sets
  // has nothing to restore: the modal state now is the setting's).
  if (plan.setting) data_.run->block.modal = c.work.interpreter->modal();
  if (plan.message) {
    // CORRECTION: the Q function goes to the PLC first, the program stops when it has
    // acknowledged it (6.1).
    data_.run->plan.steps.push_back(
        {measure::MeasuringStep::Kind::kAux, 0, false, plan.message->q_function});
    data_.run->message = plan.message;
  }
  return true;
}

bool FastMeasurement::StartMove(const MeasuringLink& c, const measure::MeasuringStep& step) {
  // A generated block: G90 G94 G40, G00 or G01 at the measuring feed, the stylus' sphere as the
  // tool edge, the targets the sphere centre's (radius values: the plan halved diameters).
  nc::PreparedBlock b = data_.run->block;
  b.calls.clear();
  b.instructions.clear();
  b.motion =
      step.kind == measure::MeasuringStep::Kind::kRapid ? nc::Motion::kRapid : nc::Motion::kLinear;
  b.modal.incremental = false;
  b.modal.feed_per_revolution = false;
  b.modal.compensation = nc::Compensation::kOff;
  b.modal.diameter = false;
  b.modal.feed = step.feed;
  b.modal.motion = b.motion;
  if (data_.setting && data_.pages) {
    b.modal.tool = data_.pages->stylus[static_cast<size_t>(data_.setting->stylus - 1)].tool_number;
    b.modal.correction = step.sphere;
    b.modal.tool_length = data_.setting->tool_length;
  }
  if (!c.take_offsets(b.modal, b.program, b.block)) return false;
  b.target.resize(c.commanded.size());
  b.programmed = 0;
  for (size_t a = 0; a < c.commanded.size(); ++a) b.target[a] = c.commanded[a] - c.translation[a];
  for (int n = 0; n < 3; ++n) {
    const int a = SettingAxis(n);
    if (a < 0 || !(step.axes >> n & 1)) continue;
    b.target[static_cast<size_t>(a)] = step.target[static_cast<size_t>(n)];
    b.programmed |= uint64_t{1} << a;
  }
  ProgramInWork& work = c.work;
  work.block = b;
  if (!c.plan_motion()) return false;
  work.profile = PathProfile{};
  work.continuation_ready = false;
  if (!work.motion.moves) return true;
  // The approach moves are checked before they start, as G77's: the ruby touching
  // the part on them is a collision. The measuring path is checked up to where the sphere
  // meets the nominal surface (there PathGuard lets the ruby touch the part): beyond it, on the
  // doubled path, the probe's switch ends the move long before the over-travel lets the shank reach
  // the part.
  if (step.kind == measure::MeasuringStep::Kind::kRapid) {
    if (!c.guard("probe approach", nullptr, false)) return false;
  } else {
    std::vector<double> end = work.motion.end;
    const int axis = SettingAxis(data_.run->plan.measuring_axis);
    if (axis >= 0 && data_.setting) {
      const auto a = static_cast<size_t>(axis);
      const double r = data_.pages->stylus[static_cast<size_t>(data_.setting->stylus - 1)]
                           .sphere_radius[static_cast<size_t>(
                               std::clamp(step.sphere, 1, measure::kSpheres) - 1)];
      const double touch =
          data_.run->plan.command - data_.run->plan.direction * r + c.translation[a];
      const double dir = data_.run->plan.direction;
      // Not beyond the move's end, nor back behind its start.
      end[a] = dir * (touch - work.motion.start[a]) <= 0 ? work.motion.start[a]
               : dir * (touch - work.motion.end[a]) >= 0 ? work.motion.end[a]
                                                         : touch;
    }
    if (!c.guard("measuring path", &end, true)) return false;
  }
  work.profile.max_rate = work.motion.max_rate;
  work.profile.max_accel = work.motion.max_accel;
  work.profile.max_jerk = work.motion.max_jerk;
  work.active = true;
  data_.run->moving = true;
  data_.run->measuring_move = step.kind == measure::MeasuringStep::Kind::kMeasure;
  return true;
}

void FastMeasurement::WatchCollision(const MeasuringLink& c, const AmplifierTelegram& at,
                                     bool reversing) {
  // 6.1 / 7.2 Q_MTstKol: the NC watches the probe as the PLC's block does, from the event 29 of
  // a MOVE or PROBE until the PLC acknowledges the setup position by resetting it (a MOVE
  // leaves it set: the stylus travels on, watched, to the next instruction). After the
  // measuring path the PLC has switched the probe off, and the reverse program takes a
  // deflected stylus away unwatched (network 7 suppresses the PLC's monitoring as well).
  if (!data_.setting || !data_.pages || reversing || !EventSet(c.events, kCollisionEvent)) {
    data_.probe_free_seen = 0;
    return;
  }
  const measure::TastwerkzeugPage& stylus =
      data_.pages->stylus[static_cast<size_t>(data_.setting->stylus - 1)];
  bool displaced = false;
  for (int n = 0; n < 3; ++n) {
    const int axis = SettingAxis(n);
    if (axis < 0) continue;
    const int drive = drives_[static_cast<size_t>(axis)];
    if (drive < 0 || static_cast<size_t>(drive) >= at.feedback.size()) continue;
    const ProbeStatus& probe = at.feedback[static_cast<size_t>(drive)].probe;
    const bool level = (stylus.pin5 ? probe.probe2 : probe.probe1).level;
    // A normally closed contact reads "displaced" while the probe is off or the drive's probe
    // function is not active (S-0-0401 reads 0): only a change from the free level the drive
    // has shown since event 29 counts. A probe already deflected when it switches on thus
    // escapes the NC with such a contact; the PLC's block reports it (Q_MTstKol).
    const auto bit = static_cast<uint8_t>(1u << n);
    if (level == stylus.normally_closed) {
      data_.probe_free_seen |= bit;
    } else if (data_.probe_free_seen & bit) {
      displaced = true;
    }
  }
  if (!displaced) return;
  data_.probe_free_seen = 0;
  // vmt's reading of the NC's reaction: the move in work ends at once (as the latch ends a
  // measuring path) and Q9999 goes to the PLC with the message; fault category 1 leaves only
  // the reverse program, which takes the stylus back the way it came (4.4).
  c.work.active = false;
  c.work.dwell_left_s = 0;
  int32_t block = c.work.block.block;
  uint32_t program = c.work.block.program;
  if (data_.run) {
    data_.run->moving = false;
    data_.run->measuring_move = false;
    block = data_.run->block.block;
    program = data_.run->block.program;
  }
  const measure::MeasuringMessage& message = measure::kProbeDisplacedOutsidePath;
  if (aux_handshake_) OutputQ(c.aux, message.q_function);
  c.fail({message.text, kMsgMeasuringReverseOnly, program, block, false});
}

void FastMeasurement::WatchMove(const MeasuringLink& c, const AmplifierTelegram& at) {
  if (!data_.run || !data_.run->moving || !c.work.active) return;
  // Outside the measuring path the probe is watched for collisions (WatchCollision).
  if (!data_.run->measuring_move) return;
  // The measuring path: the drive of the measuring axis latched its position at the probe's
  // switching edge (7.3); that ends the move (distance to go deleted) and is the measured value.
  const int axis = SettingAxis(data_.run->plan.measuring_axis);
  if (axis < 0 || !data_.setting || !data_.pages) return;
  const measure::TastwerkzeugPage& stylus =
      data_.pages->stylus[static_cast<size_t>(data_.setting->stylus - 1)];
  const int drive = drives_[static_cast<size_t>(axis)];
  if (drive < 0 || static_cast<size_t>(drive) >= at.feedback.size()) return;
  const ProbeStatus& probe = at.feedback[static_cast<size_t>(drive)].probe;
  const ProbeEdgeLatch* latch =
      Latched(stylus.pin5 ? probe.probe2 : probe.probe1, stylus.normally_closed);
  if (!latch) return;
  data_.run->contact = latch->measured_value - c.translation[static_cast<size_t>(axis)];
  c.work.active = false;  // the axes stop where they are this cycle
}

void FastMeasurement::FinishMeasuringPath(MeasuringRun& run) const {
  const measure::MeasuringMessage* message =
      measure::FinishProbe(run.call, run.plan, run.context, *data_.pages, run.contact);
  if (!message && run.contact) {
    // 6.2 event 7: the measuring path ends with the PLC's report of the contact, so its
    // block sees the latch while event 30 is still set (else it would take the path for
    // one without a contact).
    measure::MeasuringStep wait;
    wait.kind = measure::MeasuringStep::Kind::kWaitEvent;
    wait.event = kTouchEvent;
    wait.value = true;
    run.plan.steps.insert(run.plan.steps.begin() + static_cast<std::ptrdiff_t>(run.step), wait);
  }
  if (message) {
    // 6.1: TEST POINT NOT FOUND: the PLC gets Q9999; the measuring path monitoring ends
    // (the event resets still go out), no further move.
    std::vector<measure::MeasuringStep> rest;
    for (size_t i = run.step; i < run.plan.steps.size(); ++i)
      if (run.plan.steps[i].kind == measure::MeasuringStep::Kind::kEvent &&
          !run.plan.steps[i].value)
        rest.push_back(run.plan.steps[i]);
    rest.push_back({measure::MeasuringStep::Kind::kAux, 0, false, message->q_function});
    run.plan.steps.resize(run.step);
    run.plan.steps.insert(run.plan.steps.end(), rest.begin(), rest.end());
    run.message = message;
  }
}

bool FastMeasurement::Cycle(const MeasuringLink& c) {
  // Stopped by a probe collision: the instruction stays interrupted where the stylus stands.
  if (c.state == ChannelState::kError) return false;
  MeasuringRun& run = *data_.run;
  if (run.moving) {
    run.moving = false;
    if (!run.reversal) TrackReverseVectors(c);
    if (run.measuring_move) {
      run.measuring_move = false;
      FinishMeasuringPath(run);
    }
  }
  while (run.step < run.plan.steps.size()) {
    if (c.state != ChannelState::kRunning) return false;
    const measure::MeasuringStep& s = run.plan.steps[run.step];
    switch (s.kind) {
      case measure::MeasuringStep::Kind::kEvent:
        c.events.own[s.event] = s.value;
        if (c.events.sink) c.events.sink(s.event, s.value);
        ++run.step;
        break;
      case measure::MeasuringStep::Kind::kWaitEvent:
        if (EventSet(c.events, s.event) != s.value) return false;
        ++run.step;
        break;
      case measure::MeasuringStep::Kind::kAux: {
        ++run.step;
        // Q9999 (fault category 1) stops the advance program at once: the PLC acknowledges it
        // only when the reverse program has become active (7.2 typical application, network 9).
        const bool fatal =
            run.message && s.q == run.message->q_function && !run.message->advance_continuable();
        if (aux_handshake_) {
          OutputQ(c.aux, s.q);
          if (!fatal) return false;  // the cycle waits for the acknowledgement first
        }
        if (fatal) run.step = run.plan.steps.size();
        break;
      }
      case measure::MeasuringStep::Kind::kRapid:
      case measure::MeasuringStep::Kind::kMeasure:
        ++run.step;
        run.contact.reset();
        if (!StartMove(c, s)) return false;
        if (c.work.active) return false;
        run.moving = false, run.measuring_move = false;
        if (!run.reversal) TrackReverseVectors(c);
        break;
    }
  }
  // The steps are done.
  const measure::MeasuringMessage* message = run.message;
  const bool reversal = run.reversal;
  const nc::PreparedBlock block = run.block;
  End(c);
  if (reversal || !message) return true;
  // Q9998, fault category 2: the program holds with the message; a new start continues.
  // Q9999, fault category 1: the advance program stays inhibited; the reverse program runs.
  const bool hold = message->advance_continuable();
  c.fail({message->text, hold ? kMsgMeasuringContinuable : kMsgMeasuringReverseOnly, block.program,
          block.block, hold});
  return hold;
}

void FastMeasurement::TrackReverseVectors(const MeasuringLink& c) {
  if (!data_.run || !data_.setting) return;
  std::vector<measure::ReversePoint>& list = data_.reverse_vectors.Active();
  // A point is where the axes stood with its own sphere as the tool edge: compare axis positions,
  // not sphere centres, since the record may change spheres.
  auto at = [&](const measure::ReversePoint& p) {
    const std::vector<double> t = StylusTranslation(c, p.sphere);
    for (int n = 0; n < 3; ++n) {
      const int a = SettingAxis(n);
      if (a >= 0 && std::abs(c.commanded[static_cast<size_t>(a)] - t[static_cast<size_t>(a)] -
                             p.centre[static_cast<size_t>(n)]) > 1e-6)
        return false;
    }
    return true;
  };
  size_t& reached = data_.run->reached;
  // Back at a point passed before (the escape): the way out beyond it is not needed any more.
  for (size_t j = 0; j < reached && j < list.size(); ++j)
    if (at(list[j])) {
      list.resize(j + 1);
      reached = j + 1;
      return;
    }
  if (reached < list.size() && at(list[reached])) ++reached;
}

void FastMeasurement::End(const MeasuringLink& c) {
  if (!data_.run) return;
  const nc::PreparedBlock block = data_.run->block;
  data_.run.reset();
  c.work.block = block;
  const nc::ModalState m = c.work.interpreter ? c.work.interpreter->modal() : block.modal;
  c.take_offsets(m, block.program, block.block);
  if (!c.work.interpreter) return;
  // The program goes on from where the stylus stands (its next block's unprogrammed axes stay).
  std::vector<double> position(c.commanded.size());
  for (size_t a = 0; a < position.size(); ++a) position[a] = c.commanded[a] - c.translation[a];
  c.work.interpreter->SetPosition(position);
}

void FastMeasurement::StartReversal(const nc::PreparedBlock& block) {
  if (data_.run && !data_.run->reversal) {
    // Interrupted on its way: the points it has not reached are not part of the way back.
    std::vector<measure::ReversePoint>& list = data_.reverse_vectors.Active();
    if (data_.run->reached < list.size()) list.resize(data_.run->reached);
  }
  data_.run.reset();
  const auto points = data_.reverse_vectors.Reversal();
  if (points.empty() || !data_.setting || !data_.pages) return;
  MeasuringRun run;
  run.block = block;
  run.reversal = true;
  uint8_t axes = 0;
  for (int n = 0; n < 3; ++n)
    if (SettingAxis(n) >= 0) axes |= static_cast<uint8_t>(1u << n);
  for (const measure::ReversePoint& p : points) {
    measure::MeasuringStep s;
    s.kind = measure::MeasuringStep::Kind::kRapid;
    s.target = p.centre;
    s.axes = axes;
    s.sphere = p.sphere;
    run.plan.steps.push_back(s);
  }
  data_.run.emplace(std::move(run));
  data_.reverse_vectors = {};
}

bool FastMeasurement::Simulate(const MeasuringLink& c, const nc::PreparedBlock& b,
                               std::vector<double>& position, std::vector<std::string>& warnings) {
  const nc::Program& program = c.program_of(b.program);
  auto fail = [&](const std::string& text) {
    c.fail({text, kMsgMeasuringInstruction, b.program, b.block, false});
    return false;
  };
  if (b.calls.size() > 1)
    return fail("only one measuring instruction may be programmed in a block (4.1)");
  if (!data_.pages) return fail("fast measurement needs its machine data pages (7.1)");
  const nc::InstructionCall& call = b.calls.front();
  // The context where the program has the stylus, not where it stands (the search moves none).
  measure::MeasuringContext context = ContextNow(c);
  context.compensation = b.modal.compensation;
  for (int n = 0; n < 3; ++n)
    if (const int a = SettingAxis(n); a >= 0)
      context.position[n] += position[static_cast<size_t>(a)] - c.commanded[static_cast<size_t>(a)];
  // Planned on copies: only what the instruction sets as state is taken over below.
  measure::MeasuringPages pages = *data_.pages;
  measure::ReverseVectors reverse = data_.reverse_vectors;
  const measure::MeasuringPlan plan = measure::PlanInstruction(call, context, pages, reverse);
  if (!plan.error.empty()) return fail(plan.error);
  if (call.instruction == nc::Instruction::kSetting || call.instruction == nc::Instruction::kSave ||
      call.instruction == nc::Instruction::kRestore) {
    // No motion, no measurement: as in a run (Start).
    *data_.pages = pages;
    ApplyState(c, plan);
    // Their Q functions (SETTING's Q9992, 6.1) go to the PLC and wait for it, as in a run.
    if (aux_handshake_) {
      for (const measure::MeasuringStep& step : plan.steps)
        if (step.kind == measure::MeasuringStep::Kind::kAux)
          c.aux.functions.push_back({'Q', 0, static_cast<double>(step.q)});
      if (!c.aux.functions.empty()) ++c.aux.strobe;
    }
    return true;
  }
  // The programmed path: the stylus' sphere centre ends where the plan's last move ends (a
  // measuring path at its programmed end: there is no contact to stop it).
  for (const measure::MeasuringStep& step : plan.steps) {
    if (step.kind != measure::MeasuringStep::Kind::kRapid &&
        step.kind != measure::MeasuringStep::Kind::kMeasure)
      continue;
    const std::vector<double> t = StylusTranslation(c, step.sphere);
    for (int n = 0; n < 3; ++n) {
      const int a = SettingAxis(n);
      if (a < 0 || !(step.axes >> n & 1)) continue;
      const auto i = static_cast<size_t>(a);
      position[i] = step.target[static_cast<size_t>(n)] + t[i];
    }
  }
  // Section 8: the operator has to know that nothing was measured.
  const nc::SourcePos& at = program.blocks[static_cast<size_t>(b.block)].pos;
  warnings.push_back(program.files[at.file] + ":" + std::to_string(at.line) + ":" +
                     std::to_string(at.column) + ": warning: measuring instruction " +
                     nc::InstructionName(call.instruction) +
                     " simulated without measuring in block search: its results keep "
                     "their former values");
  return true;
}

}  // namespace vmt::control::channel
