// The return to the contour after block search (twincat-cnc-block-search-de.md 4.2): at the
// start the spindle gets its speed back first, then the axes return in one straight G00 move
// that PathGuard checks first (the manual leaves the obstacle to the operator, vmt refuses the
// move; with #CAX TRACK, C is aligned first, 4.2.2; under G31 the line is one of the face), or
// the manual return is checked against mc_cmd_bs_deviation_max_w and its offset kept until the
// program's end (8). Machining then goes on at the continue position, inside its block when a
// covered distance or a distance from program start says so (4.1).
#include "control/channel/block_search_support.hpp"
#include "control/channel/channel.hpp"
#include "control/channel/return_to_contour.hpp"
#include "control/nc/coordinate_transformation.hpp"

namespace vmt::control::channel {

bool Channel::SpindleReady(const AmplifierTelegram& at) const {
  if (config_.spindle_drive < 0 || at.feedback.size() <= static_cast<size_t>(config_.spindle_drive))
    return true;
  const uint32_t status = at.feedback[config_.spindle_drive].status;
  if (sp_.command.mode == DriveMode::kPosition) return status & drive_status::kInPosition;
  return sp_.command.value == 0 || (status & drive_status::kAtSpeed);
}

bool Channel::StartReturnToContour() {
  BlockSearchRun& s = search_.run();
  // 4.2.2: with #CAX TRACK on at the continue position the C axis turns to the path's tangent
  // there first (where the search's tracking has C: channel_cax_track.cpp), then the other
  // axes return; the tracking goes on with the continue block.
  s.return_rest = false;
  // Outside rotary axis mode C is not positioned: it stays where the spindle has it.
  if (headstock_.RotaryAxisOff()) {
    const size_t r = static_cast<size_t>(config_.rotary_axis);
    s.restart[r] = out_.commanded[r];
  }
  const ReturnLeg leg =
      FirstReturnLeg(out_.commanded, s.restart, config_.axes, cax_.command.has_value());
  s.return_rest = leg.c_alignment;
  return StartReturnMove(leg.to,
                         leg.c_alignment ? "C axis alignment (#CAX TRACK)" : "return to contour");
}

bool Channel::StartReturnMove(const std::vector<double>& to, const std::string& move) {
  work_.profile = PathProfile{};
  work_.continuation_ready = false;
  look_.carry_speed = look_.carry_accel = look_.carry_leftover = 0;
  // Under G31 (rotary axis mode) the return is a line of the face, as the programmed moves
  // around it are and as G77 X1=0 Y1=0 returns (REPOS manual 5.2): straight in X and C it
  // would sweep a spiral across the face. A line through the centre, where C is undefined,
  // stays straight in the axes (the operator's start there is no program's move to refuse).
  int x = -1, c = -1;
  if (search_.run().face_return && FictiveJogAxes(x, c) &&
      !nc::FaceLineOf(
           nc::MachineToFace(out_.commanded[x] - frames_.translation[x],
                             out_.commanded[c] - frames_.translation[c]),
           nc::MachineToFace(to[x] - frames_.translation[x], to[c] - frames_.translation[c]))
           .through_centre) {
    nc::PreparedBlock b;
    b.motion = nc::Motion::kRapid;
    b.fictive = true;
    b.modal.transformation = nc::Transformation::kFace;
    b.target.resize(to.size());
    for (size_t a = 0; a < to.size(); ++a) b.target[a] = to[a] - frames_.translation[a];
    if (const auto error = PlanBlockMotion(b, out_.commanded, frames_.translation, config_.axes, 0,
                                           work_.motion, FollowUpAxes(b))) {
      Fail("block search: return to contour: " + error->text, error->number);
      return false;
    }
    if (!work_.motion.moves) return true;
    if (!GuardBlockMove(move)) return false;
    work_.profile.max_rate = work_.motion.max_rate;
    work_.profile.max_accel = work_.motion.max_accel;
    work_.profile.max_jerk = work_.motion.max_jerk;
    work_.active = true;
    return true;
  }
  // 4.2: one straight move at the rapid limits, every axis ending together.
  const StraightReturn straight = PlanStraightReturn(out_.commanded, to, config_.axes);
  work_.motion = straight.motion;
  if (!work_.motion.moves) return true;  // already there
  // The manual leaves obstacles on this line to the operator (8); vmt asks PathGuard first.
  if (!GuardBlockMove(move)) return false;
  work_.profile.max_rate = straight.rate;
  work_.profile.max_accel = straight.accel;
  work_.active = true;
  return true;
}

bool Channel::ApplySearchOffset() {
  BlockSearchRun& s = search_.run();
  const ManualReturn manual =
      CheckManualReturn(out_.commanded, s.restart, config_.axes, bs_.started.deviation_max);
  if (!manual.within) {
    Fail("block search: the axes stand " + Mm(manual.deviation_mm) +
             " mm from the continue position, more than mc_cmd_bs_deviation_max_w allows (" +
             Mm(manual.allowed_mm) + " mm): bring them closer, or select the automatic return",
         kMsgBlockSearchDeviation);
    return false;
  }
  // 4.2, 8: the program goes on offset by where the axes stand, until its end or a reset.
  bs_.offset = manual.offset;
  for (size_t a = 0; a < bs_.offset.size(); ++a) {
    frames_.shift[a] += bs_.offset[a];
    frames_.translation[a] += bs_.offset[a];
    s.restart_motion.start[a] += bs_.offset[a];
    s.restart_motion.end[a] += bs_.offset[a];
  }
  for (int k = 0; k < 2; ++k)
    if (const int axis = s.restart_motion.arc_axes[k]; axis >= 0)
      s.restart_motion.arc_centre[k] += bs_.offset[static_cast<size_t>(axis)];
  return true;
}

void Channel::ContinueAfterSearch() {
  BlockSearchRun& s = search_.run();
  bs_.state = BlockSearchState::kInactive;
  state_ = ChannelState::kRunning;
  s.start_requested = false;
  if (sp_.command.mode == DriveMode::kPosition) sp_.referencing = true;
  if (!s.restart_motion.moves) return;  // the next block starts the real run
  // The rest of the continue block, from the continue position on; a breakpoint in the rest
  // cuts it as it would cut the block whole.
  work_.motion = s.restart_motion;
  const double u = bs_.program_distance.ContinueInBlock(s.restart_distance, s.restart_length,
                                                        s.restart_u, work_.motion);
  if (s.restart_u >= 1) return;
  work_.profile = ProfileFrom(work_.motion, u);
  work_.continuation_ready = false;
  look_.carry_speed = look_.carry_accel = look_.carry_leftover = 0;
  work_.active = true;
}

void Channel::StartBlockSearchHold() {
  if (bs_.program_distance.holding()) {
    // 3.5: after the breakpoint the rest of its block runs on.
    double u = 0;
    std::optional<BlockMotion> rest = bs_.program_distance.Resume(u);
    if (bs_.state == BlockSearchState::kWaitForContinueContour)
      bs_.state = BlockSearchState::kInactive;
    state_ = ChannelState::kRunning;
    if (rest) {
      work_.motion = std::move(*rest);
      work_.profile = ProfileFrom(work_.motion, u);
      work_.active = true;
    }
    return;
  }
  if (bs_.state == BlockSearchState::kWaitReturnToContour ||
      bs_.state == BlockSearchState::kWaitForContinueContour)
    search_.run().start_requested = true;
  state_ = ChannelState::kRunning;  // a feed hold during the search or the return ends
}

void Channel::RemoveSearchOffset() {
  for (size_t a = 0; a < bs_.offset.size() && a < frames_.shift.size(); ++a) {
    frames_.shift[a] -= bs_.offset[a];
    frames_.translation[a] -= bs_.offset[a];
  }
  bs_.offset.clear();
}

}  // namespace vmt::control::channel
