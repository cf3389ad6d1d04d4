// #CAX TRACK in the channel (cax_track.hpp): the command switches tracking in a run and in
// block search alike; each motion block then gets its C target from the tangent of its path as
// it starts (TrackC), and a turn beyond ANGLIMIT a C-only move before the block. The search
// simulates the same, so the continue position's C is the tangent's there, the angle the
// return aligns C to first (block search 4.2.2, channel_return_to_contour.cpp), and the run goes
// on tracking from there.
#include <cmath>
#include <limits>

#include "control/channel/channel.hpp"

namespace vmt::control::channel {

int Channel::TrackedAxis() const {
  // P-CHAN-00095 names the tracking axis in ISG; vmt's machines call it C.
  for (size_t a = 0; a < config_.axes.size(); ++a)
    if (config_.axes[a].name == "C" && config_.axes[a].rotary) return static_cast<int>(a);
  return -1;
}

std::optional<bool> Channel::CaxTrackInstruction(const nc::Program& program,
                                                 const nc::Statement& st, nc::PreparedBlock& b,
                                                 double c_machine) {
  std::string error;
  const auto command = ParseCaxTrack(program.texts[st.text], &error);
  if (!command) return std::nullopt;
  auto fail = [&](const std::string& text) {
    Fail(nc::Format({st.pos, text}, program.files), kMsgNotAvailable);
    return false;
  };
  if (!error.empty()) return fail(error);
  const int c = TrackedAxis();
  if (c < 0) return fail("#CAX TRACK needs a rotary axis C in the channel");
  if (command->on) {
    cax_.command = *command;
    return true;
  }
  cax_.command.reset();
  // The program goes on from where tracking left C: the interpreter still has the C the
  // program last wrote, which the blocks after OFF would otherwise go back to.
  const auto ci = static_cast<size_t>(c);
  work_.interpreter->SetAxisPosition(ci, c_machine - frames_.translation[ci]);
  if (!(b.programmed >> c & 1)) b.target[ci] = c_machine - frames_.translation[ci];
  return true;
}

bool Channel::TrackC(nc::PreparedBlock& b, const std::vector<double>& from, double rev_per_s,
                     std::optional<double>& align_to) {
  align_to.reset();
  if (!cax_.command || b.motion == nc::Motion::kNone || b.homing || b.repos || b.measuring)
    return true;
  const int c = TrackedAxis();
  const auto ci = static_cast<size_t>(c);
  const nc::Program& program = *ProgramOf(b.program);
  if (c < 0) {
    Fail(program, b.block, "#CAX TRACK needs a rotary axis C in the channel", kMsgNotAvailable);
    return false;
  }
  if (b.programmed >> c & 1) {
    Fail(program, b.block,
         "C follows the path while #CAX TRACK is on: a block cannot program it (switch the "
         "tracking off first)",
         kMsgNotAvailable);
    return false;
  }
  if (nc::SpindleSynchronous(b.motion)) {
    Fail(program, b.block, "threads and tapping cannot run while #CAX TRACK is on",
         kMsgNotAvailable);
    return false;
  }
  // In a run C must be a positioned axis; in the search the headstock's mode is the program's.
  if (headstock_.RotaryAxisOff() && bs_.state == BlockSearchState::kInactive) {
    Fail(program, b.block, "#CAX TRACK needs C in rotary axis mode", kMsgNotAvailable);
    return false;
  }
  auto axis = [&](const char* name) {
    for (size_t a = 0; a < config_.axes.size(); ++a)
      if (config_.axes[a].name == name) return static_cast<int>(a);
    return -1;
  };
  const nc::Plane plane = b.modal.plane;
  const int p0 = axis(plane == nc::Plane::kXY ? "X" : plane == nc::Plane::kZX ? "Z" : "Y");
  const int p1 = axis(plane == nc::Plane::kXY ? "Y" : plane == nc::Plane::kZX ? "X" : "Z");
  if (p0 < 0 || p1 < 0) {
    Fail(program, b.block, "#CAX TRACK needs both axes of the plane G" + std::to_string(nc::GCode(plane)),
         kMsgNotAvailable);
    return false;
  }
  const double c_now = from[ci] - frames_.translation[ci];
  b.target[ci] = c_now;  // out of the plane C stands, whatever the interpreter last had
  BlockMotion m;
  if (PlanBlockMotion(b, from, frames_.translation, config_.axes, rev_per_s, m, FollowUpAxes(b)))
    return true;  // the block's own planning reports its error
  const CaxTrackStep step = TrackStep(m, p0, p1, c_now, *cax_.command);
  if (!step.in_plane) return true;
  if (step.align) align_to = step.start_deg + frames_.translation[ci];
  b.target[ci] = step.end_deg;
  b.programmed |= uint64_t{1} << c;
  return true;
}

bool Channel::StartCaxAlignment(double to) {
  // The C-only move of a turn beyond ANGLIMIT, at C's rapid limits, the path standing.
  const auto ci = static_cast<size_t>(TrackedAxis());
  work_.motion = BlockMotion{};
  work_.motion.start = out_.commanded;
  work_.motion.end = out_.commanded;
  work_.motion.end[ci] = to;
  const double distance = std::abs(to - out_.commanded[ci]);
  work_.profile = PathProfile{};
  work_.continuation_ready = false;
  look_.carry_speed = look_.carry_accel = look_.carry_leftover = 0;
  if (distance < 1e-12) return true;
  const ChannelAxis& axis = config_.axes[ci];
  work_.motion.moves = true;
  work_.motion.length = distance;
  work_.motion.max_rate = axis.rapid_per_s / distance;
  work_.motion.max_accel = axis.acceleration / distance;
  work_.profile.max_rate = work_.motion.max_rate;
  work_.profile.max_accel = work_.motion.max_accel;
  if (!repos_.run()) RecordPath(work_.motion, true);
  work_.active = true;
  return true;
}

}  // namespace vmt::control::channel
