#include "control/channel/further_spindle_control.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "control/nc/source_pos.hpp"

namespace vmt::control::channel {
namespace {

/// The word of `b` whose address is `address` ("S2"), for an error at its column; the block's
/// start if the program does not hold it as a word.
nc::SourcePos WordPos(const nc::Program& program, const nc::PreparedBlock& b,
                      const std::string& address) {
  const nc::Block& block = program.blocks[b.block];
  for (const nc::Word& w : program.Words(block))
    if (program.symbols.Name(w.address) == address) return program.PosAt(w.offset);
  return block.pos;
}

std::string Address(const nc::AuxFunction& f) {
  return std::string(1, f.letter) + (f.index > 0 ? std::to_string(f.index) : "");
}

std::string WordText(const nc::AuxFunction& f) {
  std::string value = std::to_string(f.value);
  value.erase(value.find_last_not_of('0') + 1);
  if (value.back() == '.') value.pop_back();
  return Address(f) + "=" + value;
}

bool IsSpindleWord(const nc::AuxFunction& f) {
  return (f.letter == 'S' || f.letter == 'M') && SpindleIndex(f.index) >= 2;
}

}  // namespace

FurtherSpindleControl::FurtherSpindleControl(std::vector<ChannelSpindle> spindles)
    : spindles_(std::move(spindles)), states_(spindles_.size()) {}

std::string FurtherSpindleControl::TakeWords(const nc::Program& program,
                                             const nc::PreparedBlock& b) {
  auto error = [&](const nc::AuxFunction& f, const std::string& text) {
    return nc::Format({WordPos(program, b, Address(f)), WordText(f) + ": " + text}, program.files);
  };
  for (const nc::AuxFunction& f : b.aux) {
    if (!IsSpindleWord(f)) continue;
    size_t k = 0;
    while (k < spindles_.size() && spindles_[k].index != f.index) ++k;
    if (k == spindles_.size())
      return error(f, "the channel has no spindle S" + std::to_string(f.index));
    if (f.letter == 'S') {
      if (f.value < 0) return error(f, "a spindle speed is not negative (Mj=4 turns it back)");
      states_[k].rpm = f.value;
      continue;
    }
    const int m = static_cast<int>(std::lround(f.value));
    if (m != f.value || (m != 3 && m != 4 && m != 5))
      return error(f, m == 19 && m == f.value
                          ? "spindle " + spindles_[k].name +
                                " has no position control (M19): only 3, 4 and 5 address it"
                          : "only the spindle functions 3, 4 and 5 address a spindle");
    states_[k].m = m;
  }
  return {};
}

std::string FurtherSpindleControl::CheckRepos(const nc::Program& program,
                                              const nc::PreparedBlock& b) const {
  // 4.2: 'G77 Sj 0' restores spindle j's most recent speed. A further spindle has no rotary
  // axis mode, so the mode rule of 4.2's instruction does not concern it. Mj= has no meaning
  // in a G77 block: its spindle takes its former direction.
  for (const nc::AuxFunction& f : b.aux) {
    if (!IsSpindleWord(f)) continue;
    bool known = false;
    for (const ChannelSpindle& s : spindles_) known |= s.index == f.index;
    std::string text;
    if (!known)
      text = "G77: the channel has no spindle S" + std::to_string(f.index) + " to restore";
    else if (f.letter == 'M')
      text = "G77 restores spindle S" + std::to_string(f.index) +
             "'s direction itself: program G77 S" + std::to_string(f.index) + "=0";
    if (!text.empty())
      return nc::Format({WordPos(program, b, Address(f)), WordText(f) + ": " + text},
                        program.files);
  }
  return {};
}

void FurtherSpindleControl::Restore(const nc::PreparedBlock& b,
                                    const std::vector<FurtherSpindleState>& before,
                                    const AmplifierTelegram& at) {
  bool changed = false, named = false;
  for (const nc::AuxFunction& f : b.aux) {
    if (f.letter != 'S' || SpindleIndex(f.index) < 2) continue;
    for (size_t k = 0; k < spindles_.size(); ++k)
      if (spindles_[k].index == f.index && k < before.size()) {
        changed |= states_[k].Command().value != before[k].Command().value;
        states_[k] = before[k];
        named = true;
      }
  }
  // A new command waits at least a cycle: the drive's at-speed bit still answers the old one.
  // A spindle that kept its command is waited for only while it has not reached it.
  restoring_ = named && (changed || Ramping(at));
}

bool FurtherSpindleControl::UpdateRestoring(const AmplifierTelegram& at) {
  if (restoring_) restoring_ = Ramping(at);
  return restoring_;
}

void FurtherSpindleControl::Reset() { states_.assign(spindles_.size(), FurtherSpindleState{}); }

bool FurtherSpindleControl::Restored(size_t k, const std::vector<FurtherSpindleState>& before,
                                     const AmplifierTelegram* at) const {
  const DriveSetpoint command = before[k].Command();
  if (std::abs(states_[k].Command().value - command.value) > 1e-9) return false;
  const int d = spindles_[k].drive;
  if (!at || d < 0 || static_cast<size_t>(d) >= at->feedback.size()) return true;
  // As the main spindle (Repositioning::SpindleRestored): the actual speed close to the command, at
  // speed.
  const double actual = at->feedback[d].velocity;
  if (std::abs(actual - command.value) > std::max(6.0, 0.02 * std::abs(command.value)))
    return false;
  return command.value == 0 || (at->feedback[d].status & drive_status::kAtSpeed);
}

bool FurtherSpindleControl::AllRestored(const std::vector<FurtherSpindleState>& before,
                                        const AmplifierTelegram& at) const {
  for (size_t k = 0; k < before.size(); ++k)
    if (!Restored(k, before, &at)) return false;
  return true;
}

std::vector<ReposFurtherSpindleStatus> FurtherSpindleControl::ReposStatus(
    const std::vector<FurtherSpindleState>& before, const AmplifierTelegram* at) const {
  std::vector<ReposFurtherSpindleStatus> lines;
  for (size_t k = 0; k < before.size(); ++k) {
    ReposFurtherSpindleStatus f;
    f.name = spindles_[k].name;
    f.command_rpm = before[k].Command().value / 6;
    f.command_m = before[k].m;
    f.actual_m = states_[k].m;
    const int d = spindles_[k].drive;
    if (at && d >= 0 && static_cast<size_t>(d) < at->feedback.size())
      f.actual_rpm = at->feedback[d].velocity / 6;
    else
      f.actual_rpm = states_[k].Command().value / 6;
    f.adjust = !Restored(k, before, at);
    lines.push_back(f);
  }
  return lines;
}

bool FurtherSpindleControl::Ramping(const AmplifierTelegram& at) const {
  for (size_t k = 0; k < states_.size(); ++k) {
    const int d = spindles_[k].drive;
    if (d < 0 || static_cast<size_t>(d) >= at.feedback.size()) continue;
    if (states_[k].Command().value != 0 && !(at.feedback[d].status & drive_status::kAtSpeed))
      return true;
  }
  return false;
}

void FurtherSpindleControl::WriteSetpoints(MasterTelegram& mdt) const {
  for (size_t k = 0; k < states_.size(); ++k) {
    const int d = spindles_[k].drive;
    if (d >= 0 && static_cast<size_t>(d) < mdt.setpoints.size())
      mdt.setpoints[d] = states_[k].Command();
  }
}

}  // namespace vmt::control::channel
