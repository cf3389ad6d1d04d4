// The channel's further spindles (further_spindles.hpp): their Sj= / Mj= words in a program,
// their state at the interruption and their return by G77 Sj=0 (REPOS manual 4.2), their part
// in PxxS.CREST (7.3: all spindles) and their command to the drives.
#include <cmath>
#include <string>

#include "control/channel/channel.hpp"

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

bool Channel::FurtherSpindleWords(const nc::Program& program, const nc::PreparedBlock& b,
                                  std::vector<FurtherSpindleState>& states) {
  auto fail = [&](const nc::AuxFunction& f, const std::string& text) {
    Fail(
        nc::Format({WordPos(program, b, Address(f)), WordText(f) + ": " + text}, program.files),
        kMsgNotAvailable);
    return false;
  };
  for (const nc::AuxFunction& f : b.aux) {
    if (!IsSpindleWord(f)) continue;
    size_t k = 0;
    while (k < config_.spindles.size() && config_.spindles[k].index != f.index) ++k;
    if (k == config_.spindles.size())
      return fail(f, "the channel has no spindle S" + std::to_string(f.index));
    if (f.letter == 'S') {
      if (f.value < 0) return fail(f, "a spindle speed is not negative (Mj=4 turns it back)");
      states[k].rpm = f.value;
      continue;
    }
    const int m = static_cast<int>(std::lround(f.value));
    if (m != f.value || (m != 3 && m != 4 && m != 5))
      return fail(f, m == 19 && m == f.value
                         ? "spindle " + config_.spindles[k].name +
                               " has no position control (M19): only 3, 4 and 5 address it"
                         : "only the spindle functions 3, 4 and 5 address a spindle");
    states[k].m = m;
  }
  return true;
}

bool Channel::CheckReposFurtherSpindles(const nc::Program& program) {
  // 4.2: 'G77 Sj 0' restores spindle j's most recent speed. A further spindle has no rotary
  // axis mode, so the mode rule of 4.2's instruction does not concern it. Mj= has no meaning
  // in a G77 block: its spindle takes its former direction.
  for (const nc::AuxFunction& f : work_.block.aux) {
    if (!IsSpindleWord(f)) continue;
    bool known = false;
    for (const ChannelSpindle& s : config_.spindles) known |= s.index == f.index;
    std::string text;
    if (!known)
      text = "G77: the channel has no spindle S" + std::to_string(f.index) + " to restore";
    else if (f.letter == 'M')
      text = "G77 restores spindle S" + std::to_string(f.index) +
             "'s direction itself: program G77 S" + std::to_string(f.index) + "=0";
    if (text.empty()) continue;
    Fail(nc::Format({WordPos(program, work_.block, Address(f)), WordText(f) + ": " + text},
                    program.files),
         kMsgNotAvailable);
    return false;
  }
  return true;
}

void Channel::RestoreFurtherSpindles(const AmplifierTelegram& at) {
  bool changed = false, named = false;
  for (const nc::AuxFunction& f : work_.block.aux) {
    if (f.letter != 'S' || SpindleIndex(f.index) < 2) continue;
    for (size_t k = 0; k < config_.spindles.size(); ++k)
      if (config_.spindles[k].index == f.index && k < interruption_->further_spindles.size()) {
        const FurtherSpindleState& before = interruption_->further_spindles[k];
        changed |= further_spindles_[k].Command().value != before.Command().value;
        further_spindles_[k] = before;
        named = true;
      }
  }
  // A new command waits at least a cycle: the drive's at-speed bit still answers the old one.
  // A spindle that kept its command is waited for only while it has not reached it.
  further_restoring_ = named && (changed || FurtherSpindlesRamping(at));
}

bool Channel::FurtherSpindleRestored(size_t k, const AmplifierTelegram* at) const {
  const DriveSetpoint before = interruption_->further_spindles[k].Command();
  if (std::abs(further_spindles_[k].Command().value - before.value) > 1e-9) return false;
  const int d = config_.spindles[k].drive;
  if (!at || d < 0 || static_cast<size_t>(d) >= at->feedback.size()) return true;
  // As the main spindle (SpindleRestored): the actual speed close to the command, at speed.
  const double actual = at->feedback[d].velocity;
  if (std::abs(actual - before.value) > std::max(6.0, 0.02 * std::abs(before.value)))
    return false;
  return before.value == 0 || (at->feedback[d].status & drive_status::kAtSpeed);
}

bool Channel::FurtherSpindlesRestored(const AmplifierTelegram& at) const {
  if (!interruption_) return true;
  for (size_t k = 0; k < interruption_->further_spindles.size(); ++k)
    if (!FurtherSpindleRestored(k, &at)) return false;
  return true;
}

bool Channel::FurtherSpindlesRamping(const AmplifierTelegram& at) const {
  for (size_t k = 0; k < further_spindles_.size(); ++k) {
    const int d = config_.spindles[k].drive;
    if (d < 0 || static_cast<size_t>(d) >= at.feedback.size()) continue;
    if (further_spindles_[k].Command().value != 0 &&
        !(at.feedback[d].status & drive_status::kAtSpeed))
      return true;
  }
  return false;
}

void Channel::WriteFurtherSpindles(MasterTelegram& mdt) const {
  for (size_t k = 0; k < further_spindles_.size(); ++k) {
    const int d = config_.spindles[k].drive;
    if (d >= 0 && static_cast<size_t>(d) < mdt.setpoints.size())
      mdt.setpoints[d] = further_spindles_[k].Command();
  }
}

}  // namespace vmt::control::channel
