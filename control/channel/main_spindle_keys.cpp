#include "control/channel/main_spindle_keys.hpp"

namespace vmt::control::channel {

std::optional<SpindleKeyMove> SpindleMKey(int m, const axes::AxisParameters& spindle) {
  const double speed = spindle.jog_per_s;  // the main spindle's "Jogging speed"
  switch (m) {
    case 3:
      return SpindleKeyMove{{DriveMode::kVelocity, speed, 0}};
    case 4:
      return SpindleKeyMove{{DriveMode::kVelocity, -speed, 0}};
    case 5:
      return SpindleKeyMove{{DriveMode::kVelocity, 0, 0}};
    case 19:
      return SpindleKeyMove{{DriveMode::kPosition, spindle.jog_spindle_position, 0}, false, true};
    default:
      return std::nullopt;
  }
}

SpindleKeyMove SpindleHomeKey(const axes::AxisParameters& spindle) {
  return {{DriveMode::kPosition, spindle.reference_position, 0}, false, true};
}

std::optional<SpindleKeyMove> SpindleJogKey(int direction, const JogRules& rules, double position,
                                            const axes::AxisParameters& spindle) {
  // 4.3: the jog mode selects the type of the spindle's jogging as of the feed axes. An
  // increment positions it by that many degrees from where it stands (the spindle set's
  // position control, as M19: vmt's reading, the manual names no separate spindle increment).
  const double rapid = spindle.jog_rapid_per_s > 0 ? spindle.jog_rapid_per_s : spindle.jog_per_s;
  switch (rules.mode) {
    case JogMode::kContinuous:
    case JogMode::kRapid:
      return SpindleKeyMove{
          {DriveMode::kVelocity,
           direction * (rules.mode == JogMode::kRapid ? rapid : spindle.jog_per_s), 0},
          true};
    case JogMode::kHandwheel:
      return std::nullopt;
    default:
      return SpindleKeyMove{
          {DriveMode::kPosition, position + direction * rules.Increment(spindle), 0}};
  }
}

}  // namespace vmt::control::channel
