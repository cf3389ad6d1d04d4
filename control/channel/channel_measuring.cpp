// Fast measurement in the channel (mtc200-fast-measurement.md): a block with a measuring
// instruction runs the plan measure::PlanInstruction makes of it, step by step, as the real
// control runs the NC blocks it generates for the instruction: events to and from the PLC's
// measuring block (6.2), Q functions with their acknowledgement (6.1), G00 and G94 G01 moves of
// the stylus' sphere centre, and on the measuring path the drive's latch (7.3) stops the move
// and gives the measured value.
#include <algorithm>
#include <cmath>

#include "control/channel/channel.hpp"

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

}  // namespace

int Channel::SettingAxis(int n) const {
  if (!meas_.setting || n < 0 || n > 2 || meas_.setting->axis[n] == 0) return -1;
  const std::string name(1, meas_.setting->axis[n]);
  for (size_t a = 0; a < config_.axes.size(); ++a)
    if (config_.axes[a].name == name) return static_cast<int>(a);
  return -1;
}

bool Channel::EventSet(int n) const {
  if (events_.source) return events_.source(n);
  auto it = events_.own.find(n);
  return it != events_.own.end() && it->second;
}

std::vector<double> Channel::StylusTranslation(int sphere) const {
  nc::ModalState m = work_.block.modal;
  if (meas_.setting && meas_.pages) {
    const int stylus = meas_.setting->stylus;
    m.tool = meas_.pages->stylus[static_cast<size_t>(stylus - 1)].tool_number;
    m.correction = sphere;
    m.tool_length = meas_.setting->tool_length;
  }
  return TranslationOf(m);
}

measure::MeasuringContext Channel::MeasuringContextNow() const {
  measure::MeasuringContext c;
  c.setting = meas_.setting;
  bool x = false, y = false, z = false;
  for (const ChannelAxis& a : config_.axes) {
    x |= a.name == "X";
    y |= a.name == "Y";
    z |= a.name == "Z";
  }
  c.turning = x && z && !y;
  c.tool_list = !config_.tools.edges.empty();
  const nc::ModalState& m = meas_.run ? meas_.run->block.modal : work_.block.modal;
  c.compensation = m.compensation;
  // The sphere the instruction names (MOVE D, PROBE I): the position is its centre's.
  int sphere = 1;
  if (!work_.block.calls.empty()) {
    const nc::InstructionCall& call = work_.block.calls.front();
    const size_t at = call.instruction == nc::Instruction::kMove    ? 3
                      : call.instruction == nc::Instruction::kProbe ? 8
                                                                    : call.args.size();
    if (at < call.args.size() && call.args[at].kind == nc::InstructionArg::Kind::kValue &&
        call.args[at].value >= 1 && call.args[at].value <= measure::kSpheres)
      sphere = static_cast<int>(call.args[at].value);
  }
  const std::vector<double> t = StylusTranslation(sphere);
  for (int n = 0; n < 3; ++n) {
    const int a = SettingAxis(n);
    if (a >= 0) c.position[n] = out_.commanded[a] - t[a];
  }
  for (size_t i = 0; i < measure::kSavedGGroups.size(); ++i) {
    bool known = false;
    c.g_groups[i] =
        static_cast<int16_t>(nc::ModalGroupValue(m, 'G', measure::kSavedGGroups[i], known));
  }
  for (size_t i = 0; i < c.variables.size(); ++i)
    c.variables[i] =
        work_.interpreter ? work_.interpreter->Variable("@" + std::to_string(100 + i)) : 0;
  c.feed = m.feed;
  return c;
}

void Channel::ApplyMeasuringState(const measure::MeasuringPlan& plan) {
  if (plan.setting) {
    // SETTING: its G codes are modal in the program from here (2.1: "Activating the G
    // functions"), as in the blocks the real control generates.
    meas_.setting = plan.setting;
    nc::ModalState m = work_.interpreter->modal();
    m.plane = plan.setting->plane;
    m.tool_length = plan.setting->tool_length;
    m.diameter = plan.setting->diameter;
    work_.interpreter->SetModal(m);
  }
  if (plan.restore_variables)
    for (size_t i = 0; i < plan.restore_variables->size(); ++i)
      work_.interpreter->SetVariable("@" + std::to_string(100 + i), (*plan.restore_variables)[i]);
  if (plan.restore_feed) {
    nc::ModalState m = work_.interpreter->modal();
    m.feed = *plan.restore_feed;
    work_.interpreter->SetModal(m);
  }
}

bool Channel::StartMeasuring(const AmplifierTelegram& at) {
  (void)at;
  const nc::Program& program = *ProgramOf(work_.block.program);
  auto fail = [&](const std::string& text) {
    Fail(program, work_.block.block, text, kMsgMeasuringInstruction);
    return false;
  };
  // 4.1 Entering the NC Instructions: one instruction per block, nothing else in it, and not a
  // skippable block: the instruction becomes several blocks of its own.
  if (work_.block.calls.size() > 1)
    return fail("only one measuring instruction may be programmed in a block (4.1)");
  if (work_.block.instructions.size() > 1 || work_.block.programmed != 0 ||
      !work_.block.aux.empty() || !work_.block.events.empty() || work_.block.dwell_s > 0 ||
      work_.block.homing || work_.block.repos || work_.block.set_position)
    return fail("a block with a measuring instruction may hold no other NC syntax (4.1)");
  if (program.blocks[static_cast<size_t>(work_.block.block)].skippable)
    return fail("a block with a measuring instruction may not be a skipped block (4.1)");
  if (!meas_.pages) return fail("fast measurement needs its machine data pages (7.1)");

  MeasuringRun run;
  run.block = work_.block;
  run.call = work_.block.calls.front();
  meas_.run.emplace(std::move(run));
  meas_.run->context = MeasuringContextNow();
  meas_.run->context.compensation = work_.block.modal.compensation;
  const measure::ReverseVectors before = meas_.reverse_vectors;
  meas_.run->plan = measure::PlanInstruction(meas_.run->call, meas_.run->context, *meas_.pages,
                                             meas_.reverse_vectors);
  // Which of the recorded points the stylus already stands at or has passed: the start of a
  // new record, or the whole record a linear path sequence continues.
  const int variant = meas_.reverse_vectors.active;
  const auto& list_before =
      variant == 0 ? before.single_point : before.sequence[static_cast<size_t>(variant - 1)];
  const bool continued = variant != 0 && before.active == variant && !list_before.empty();
  meas_.run->reached = continued ? list_before.size() : 1;
  if (!meas_.run->plan.error.empty()) {
    const std::string error = meas_.run->plan.error;
    meas_.run.reset();
    return fail(error);
  }
  const measure::MeasuringPlan& plan = meas_.run->plan;
  if (!plan.warning.empty()) {
    const nc::SourcePos& pos = program.blocks[static_cast<size_t>(work_.block.block)].pos;
    meas_.warnings.push_back(
        (pos.file < program.files.size() ? program.files[pos.file] : "<input>") + ":" +
        std::to_string(pos.line) + ":" + std::to_string(pos.column) + ": warning: " + plan.warning);
  }
  ApplyMeasuringState(plan);
  // The blocks generated for the instruction run in the setting's G codes (a plan that sets
  // has nothing to restore: the modal state now is the setting's).
  if (plan.setting) meas_.run->block.modal = work_.interpreter->modal();
  if (plan.message) {
    // CORRECTION: the Q function goes to the PLC first, the program stops when it has
    // acknowledged it (6.1).
    meas_.run->plan.steps.push_back(
        {measure::MeasuringStep::Kind::kAux, 0, false, plan.message->q_function});
    meas_.run->message = plan.message;
  }
  return true;
}

bool Channel::StartMeasuringMove(const measure::MeasuringStep& step) {
  // A generated block: G90 G94 G40, G00 or G01 at the measuring feed, the stylus' sphere as the
  // tool edge, the targets the sphere centre's (radius values: the plan halved diameters).
  nc::PreparedBlock b = meas_.run->block;
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
  if (meas_.setting && meas_.pages) {
    b.modal.tool = meas_.pages->stylus[static_cast<size_t>(meas_.setting->stylus - 1)].tool_number;
    b.modal.correction = step.sphere;
    b.modal.tool_length = meas_.setting->tool_length;
  }
  const nc::Program& program = *ProgramOf(b.program);
  if (!UpdateTranslation(b.modal, program, b.block)) return false;
  b.target.resize(out_.commanded.size());
  b.programmed = 0;
  for (size_t a = 0; a < out_.commanded.size(); ++a)
    b.target[a] = out_.commanded[a] - frames_.translation[a];
  for (int n = 0; n < 3; ++n) {
    const int a = SettingAxis(n);
    if (a < 0 || !(step.axes >> n & 1)) continue;
    b.target[static_cast<size_t>(a)] = step.target[static_cast<size_t>(n)];
    b.programmed |= uint64_t{1} << a;
  }
  work_.block = b;
  for (size_t a = 0; a < out_.commanded.size(); ++a)
    if (!frames_.homed[a] && (b.programmed >> a & 1)) {
      Fail(program, b.block,
           "axis " + config_.axes[a].name + " has no reference: home it first (G74)", kMsgNotHomed);
      return false;
    }
  sync_.Clear();
  if (const auto error =
          PlanBlockMotion(work_.block, out_.commanded, frames_.translation, config_.axes, 0,
                          work_.motion, FollowUpAxes(work_.block))) {
    Fail(program, b.block, error->text, error->number);
    return false;
  }
  work_.profile = PathProfile{};
  work_.continuation_ready = false;
  look_.carry_speed = look_.carry_accel = look_.carry_leftover = 0;
  if (!work_.motion.moves) return true;
  // The approach moves are checked before they start, as G77's: the ruby touching
  // the part on them is a collision. The measuring path is checked up to where the sphere
  // meets the nominal surface (there PathGuard lets the ruby touch the part): beyond it, on the
  // doubled path, the probe's switch ends the move long before the over-travel lets the shank reach
  // the part.
  if (step.kind == measure::MeasuringStep::Kind::kRapid) {
    if (!GuardBlockMove("probe approach")) return false;
  } else {
    std::vector<double> end = work_.motion.end;
    const int axis = SettingAxis(meas_.run->plan.measuring_axis);
    if (axis >= 0 && meas_.setting) {
      const auto a = static_cast<size_t>(axis);
      const double r = meas_.pages->stylus[static_cast<size_t>(meas_.setting->stylus - 1)]
                           .sphere_radius[static_cast<size_t>(
                               std::clamp(step.sphere, 1, measure::kSpheres) - 1)];
      const double touch =
          meas_.run->plan.command - meas_.run->plan.direction * r + frames_.translation[a];
      const double dir = meas_.run->plan.direction;
      // Not beyond the move's end, nor back behind its start.
      end[a] = dir * (touch - work_.motion.start[a]) <= 0 ? work_.motion.start[a]
               : dir * (touch - work_.motion.end[a]) >= 0 ? work_.motion.end[a]
                                                          : touch;
    }
    if (!GuardBlockMove("measuring path", &end, true)) return false;
  }
  work_.profile.max_rate = work_.motion.max_rate;
  work_.profile.max_accel = work_.motion.max_accel;
  work_.profile.max_jerk = work_.motion.max_jerk;
  work_.active = true;
  meas_.run->moving = true;
  meas_.run->measuring_move = step.kind == measure::MeasuringStep::Kind::kMeasure;
  return true;
}

void Channel::WatchProbeCollision(const AmplifierTelegram& at) {
  // 6.1 / 7.2 Q_MTstKol: the NC watches the probe as the PLC's block does, from the event 29 of
  // a MOVE or PROBE until the PLC acknowledges the setup position by resetting it (a MOVE
  // leaves it set: the stylus travels on, watched, to the next instruction). After the
  // measuring path the PLC has switched the probe off, and the reverse program takes a
  // deflected stylus away unwatched (network 7 suppresses the PLC's monitoring as well).
  if (!meas_.setting || !meas_.pages || reversing_ || !EventSet(kCollisionEvent)) {
    meas_.probe_free_seen = 0;
    return;
  }
  const measure::TastwerkzeugPage& stylus =
      meas_.pages->stylus[static_cast<size_t>(meas_.setting->stylus - 1)];
  bool displaced = false;
  for (int n = 0; n < 3; ++n) {
    const int axis = SettingAxis(n);
    if (axis < 0) continue;
    const int drive = config_.axes[static_cast<size_t>(axis)].drive;
    if (drive < 0 || static_cast<size_t>(drive) >= at.feedback.size()) continue;
    const ProbeStatus& probe = at.feedback[static_cast<size_t>(drive)].probe;
    const bool level = (stylus.pin5 ? probe.probe2 : probe.probe1).level;
    // A normally closed contact reads "displaced" while the probe is off or the drive's probe
    // function is not active (S-0-0401 reads 0): only a change from the free level the drive
    // has shown since event 29 counts. A probe already deflected when it switches on thus
    // escapes the NC with such a contact; the PLC's block reports it (Q_MTstKol).
    const auto bit = static_cast<uint8_t>(1u << n);
    if (level == stylus.normally_closed) {
      meas_.probe_free_seen |= bit;
    } else if (meas_.probe_free_seen & bit) {
      displaced = true;
    }
  }
  if (!displaced) return;
  meas_.probe_free_seen = 0;
  // vmt's reading of the NC's reaction: the move in work ends at once (as the latch ends a
  // measuring path) and Q9999 goes to the PLC with the message; fault category 1 leaves only
  // the reverse program, which takes the stylus back the way it came (4.4).
  work_.active = false;
  work_.dwell_left_s = 0;
  int32_t block = work_.block.block;
  uint32_t program_index = work_.block.program;
  if (meas_.run) {
    meas_.run->moving = false;
    meas_.run->measuring_move = false;
    block = meas_.run->block.block;
    program_index = meas_.run->block.program;
  }
  const measure::MeasuringMessage& message = measure::kProbeDisplacedOutsidePath;
  if (config_.aux_handshake) {
    aux_.functions.push_back({'Q', 0, static_cast<double>(message.q_function)});
    ++aux_.strobe;
  }
  const nc::Program& program = *ProgramOf(program_index);
  const std::string text =
      block >= 0 ? nc::Format({program.blocks[static_cast<size_t>(block)].pos, message.text},
                              program.files)
                 : std::string(message.text);
  Fail(text, kMsgMeasuringReverseOnly);
}

void Channel::WatchMeasuringMove(const AmplifierTelegram& at) {
  if (!meas_.run || !meas_.run->moving || !work_.active) return;
  // Outside the measuring path the probe is watched for collisions (WatchProbeCollision).
  if (!meas_.run->measuring_move) return;
  // The measuring path: the drive of the measuring axis latched its position at the probe's
  // switching edge (7.3); that ends the move (distance to go deleted) and is the measured value.
  const int axis = SettingAxis(meas_.run->plan.measuring_axis);
  if (axis < 0 || !meas_.setting || !meas_.pages) return;
  const measure::TastwerkzeugPage& stylus =
      meas_.pages->stylus[static_cast<size_t>(meas_.setting->stylus - 1)];
  const int drive = config_.axes[static_cast<size_t>(axis)].drive;
  if (drive < 0 || static_cast<size_t>(drive) >= at.feedback.size()) return;
  const ProbeStatus& probe = at.feedback[static_cast<size_t>(drive)].probe;
  const ProbeEdgeLatch* latch =
      Latched(stylus.pin5 ? probe.probe2 : probe.probe1, stylus.normally_closed);
  if (!latch) return;
  meas_.run->contact = latch->measured_value - frames_.translation[static_cast<size_t>(axis)];
  work_.active = false;  // the axes stop where they are this cycle
}

bool Channel::MeasuringCycle(const AmplifierTelegram& at) {
  (void)at;
  // Stopped by a probe collision: the instruction stays interrupted where the stylus stands.
  if (state_ == ChannelState::kError) return false;
  MeasuringRun& run = *meas_.run;
  const nc::Program& program = *ProgramOf(run.block.program);
  if (run.moving) {
    run.moving = false;
    if (!run.reversal) TrackReverseVectors();
    if (run.measuring_move) {
      run.measuring_move = false;
      const measure::MeasuringMessage* message =
          measure::FinishProbe(run.call, run.plan, run.context, *meas_.pages, run.contact);
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
  }
  while (run.step < run.plan.steps.size()) {
    if (state_ != ChannelState::kRunning) return false;
    const measure::MeasuringStep& s = run.plan.steps[run.step];
    switch (s.kind) {
      case measure::MeasuringStep::Kind::kEvent:
        events_.own[s.event] = s.value;
        if (events_.sink) events_.sink(s.event, s.value);
        ++run.step;
        break;
      case measure::MeasuringStep::Kind::kWaitEvent:
        if (EventSet(s.event) != s.value) return false;
        ++run.step;
        break;
      case measure::MeasuringStep::Kind::kAux: {
        ++run.step;
        // Q9999 (fault category 1) stops the advance program at once: the PLC acknowledges it
        // only when the reverse program has become active (7.2 typical application, network 9).
        const bool fatal =
            run.message && s.q == run.message->q_function && !run.message->advance_continuable();
        if (config_.aux_handshake) {
          aux_.functions.push_back({'Q', 0, static_cast<double>(s.q)});
          ++aux_.strobe;
          if (!fatal) return false;  // the cycle waits for the acknowledgement first
        }
        if (fatal) run.step = run.plan.steps.size();
        break;
      }
      case measure::MeasuringStep::Kind::kRapid:
      case measure::MeasuringStep::Kind::kMeasure:
        ++run.step;
        run.contact.reset();
        if (!StartMeasuringMove(s)) return false;
        if (work_.active) return false;
        run.moving = false, run.measuring_move = false;
        if (!run.reversal) TrackReverseVectors();
        break;
    }
  }
  // The steps are done.
  const measure::MeasuringMessage* message = run.message;
  const bool reversal = run.reversal;
  const nc::PreparedBlock block = run.block;
  EndMeasuring();
  if (reversal) return true;
  if (message) {
    const std::string text = nc::Format(
        {program.blocks[static_cast<size_t>(block.block)].pos, message->text}, program.files);
    if (message->advance_continuable()) {
      // Q9998, fault category 2: the program holds with the message; a new start continues.
      state_ = ChannelState::kHold;
      error_ = text;
      error_number_ = kMsgMeasuringContinuable;
    } else {
      // Q9999, fault category 1: the advance program stays inhibited; the reverse program runs.
      Fail(text, kMsgMeasuringReverseOnly);
      return false;
    }
  }
  return true;
}

void Channel::TrackReverseVectors() {
  if (!meas_.run || !meas_.setting) return;
  std::vector<measure::ReversePoint>& list = meas_.reverse_vectors.Active();
  // A point is where the axes stood with its own sphere as the tool edge: compare axis positions,
  // not sphere centres, since the record may change spheres.
  auto at = [&](const measure::ReversePoint& p) {
    const std::vector<double> t = StylusTranslation(p.sphere);
    for (int n = 0; n < 3; ++n) {
      const int a = SettingAxis(n);
      if (a >= 0 && std::abs(out_.commanded[static_cast<size_t>(a)] - t[static_cast<size_t>(a)] -
                             p.centre[static_cast<size_t>(n)]) > 1e-6)
        return false;
    }
    return true;
  };
  size_t& reached = meas_.run->reached;
  // Back at a point passed before (the escape): the way out beyond it is not needed any more.
  for (size_t j = 0; j < reached && j < list.size(); ++j)
    if (at(list[j])) {
      list.resize(j + 1);
      reached = j + 1;
      return;
    }
  if (reached < list.size() && at(list[reached])) ++reached;
}

void Channel::EndMeasuring() {
  if (!meas_.run) return;
  const nc::PreparedBlock block = meas_.run->block;
  meas_.run.reset();
  work_.block = block;
  const nc::ModalState m = work_.interpreter ? work_.interpreter->modal() : block.modal;
  UpdateTranslation(m, *ProgramOf(block.program), block.block);
  if (!work_.interpreter) return;
  // The program goes on from where the stylus stands (its next block's unprogrammed axes stay).
  std::vector<double> position(out_.commanded.size());
  for (size_t a = 0; a < position.size(); ++a)
    position[a] = out_.commanded[a] - frames_.translation[a];
  work_.interpreter->SetPosition(position);
}

void Channel::StartReversal() {
  if (meas_.run && !meas_.run->reversal) {
    // Interrupted on its way: the points it has not reached are not part of the way back.
    std::vector<measure::ReversePoint>& list = meas_.reverse_vectors.Active();
    if (meas_.run->reached < list.size()) list.resize(meas_.run->reached);
  }
  meas_.run.reset();
  const auto points = meas_.reverse_vectors.Reversal();
  if (points.empty() || !meas_.setting || !meas_.pages) {
    meas_.run.reset();
    return;
  }
  MeasuringRun run;
  run.block = work_.block;
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
  meas_.run.emplace(std::move(run));
  meas_.reverse_vectors = {};
}

}  // namespace vmt::control::channel
