// The return to the contour after block search (twincat-cnc-block-search-de.md 4.2): at the
// start the spindle gets its speed back first, then the axes return in one straight G00 move
// that PathGuard checks first (the manual leaves the obstacle to the operator, vmt refuses the
// move; with #CAX TRACK, C is aligned first, 4.2.2; under G31 the line is one of the face), or
// the manual return is checked against mc_cmd_bs_deviation_max_w and its offset kept until the
// program's end (8). Machining then goes on at the continue position, inside its block when a
// covered distance or a distance from program start says so (4.1).
#include <cmath>
#include <limits>

#include "control/channel/block_search_support.hpp"
#include "control/channel/channel.hpp"
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
  BlockSearchRun& s = *search_;
  // 4.2.2: with #CAX TRACK on at the continue position the C axis turns to the path's tangent
  // there first (where the search's tracking has C: channel_cax_track.cpp), then the other
  // axes return; the tracking goes on with the continue block.
  s.return_rest = false;
  // Outside rotary axis mode C is not positioned: it stays where the spindle has it.
  if (headstock_.RotaryAxisOff()) {
    const size_t r = static_cast<size_t>(config_.rotary_axis);
    s.restart[r] = out_.commanded[r];
  }
  if (cax_.command) {
    for (size_t a = 0; a < out_.commanded.size(); ++a) {
      if (config_.axes[a].name != "C" || std::abs(s.restart[a] - out_.commanded[a]) < 1e-12)
        continue;
      std::vector<double> aligned = out_.commanded;
      aligned[a] = s.restart[a];
      s.return_rest = true;
      return StartReturnMove(aligned, "C axis alignment (#CAX TRACK)");
    }
  }
  return StartReturnMove(s.restart, "return to contour");
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
  if (search_->face_return && FictiveJogAxes(x, c) &&
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
  work_.motion = BlockMotion{};
  work_.motion.start = out_.commanded;
  work_.motion.end = to;
  double rate = std::numeric_limits<double>::infinity(), accel = rate;
  for (size_t a = 0; a < out_.commanded.size(); ++a) {
    const double distance = std::abs(work_.motion.end[a] - work_.motion.start[a]);
    if (distance < 1e-12) continue;
    const ChannelAxis& axis = config_.axes[a];
    rate = std::min(rate, axis.rapid_per_s / distance);
    accel = std::min(accel, axis.acceleration / distance);
  }
  if (!std::isfinite(rate)) return true;  // already there
  work_.motion.moves = true;
  work_.motion.length = 0;
  for (size_t a = 0; a < out_.commanded.size(); ++a)
    work_.motion.length += std::pow(work_.motion.end[a] - work_.motion.start[a], 2);
  work_.motion.length = std::sqrt(work_.motion.length);
  // The manual leaves obstacles on this line to the operator (8); vmt asks PathGuard first.
  if (!GuardBlockMove(move)) return false;
  work_.profile.max_rate = rate;
  work_.profile.max_accel = accel;
  work_.active = true;
  return true;
}

bool Channel::ApplySearchOffset() {
  BlockSearchRun& s = *search_;
  double deviation2 = 0;
  for (size_t a = 0; a < out_.commanded.size(); ++a)
    if (MainAxis(config_.axes[a].name)) deviation2 += std::pow(out_.commanded[a] - s.restart[a], 2);
  const double deviation = std::sqrt(deviation2);
  const double allowed = static_cast<double>(bs_.started.deviation_max) * 1e-4;
  if (deviation > allowed + 1e-9) {
    Fail("block search: the axes stand " + Mm(deviation) +
             " mm from the continue position, more than mc_cmd_bs_deviation_max_w allows (" +
             Mm(allowed) + " mm): bring them closer, or select the automatic return",
         kMsgBlockSearchDeviation);
    return false;
  }
  // 4.2, 8: the program goes on offset by where the axes stand, until its end or a reset.
  bs_.offset.assign(out_.commanded.size(), 0.0);
  for (size_t a = 0; a < out_.commanded.size(); ++a) {
    const double offset = out_.commanded[a] - s.restart[a];
    bs_.offset[a] = offset;
    frames_.shift[a] += offset;
    frames_.translation[a] += offset;
    s.restart_motion.start[a] += offset;
    s.restart_motion.end[a] += offset;
  }
  for (int k = 0; k < 2; ++k)
    if (const int axis = s.restart_motion.arc_axes[k]; axis >= 0)
      s.restart_motion.arc_centre[k] += bs_.offset[static_cast<size_t>(axis)];
  return true;
}

void Channel::ContinueAfterSearch() {
  BlockSearchRun& s = *search_;
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
    search_->start_requested = true;
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
