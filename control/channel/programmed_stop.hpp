#pragma once
// M00 (programmed stop) and M01 (optional stop): the block that holds the word runs to its end,
// its motion and the PLC's acknowledgement of its auxiliary functions included (the M function
// goes to the PLC as any other), and the channel then holds until the next start. M01 holds
// only while the optional-stop signal (PxxC.OPSTP) is set. vmt reads that signal when the block
// ends, where the stop takes effect: the operator may still set it while the block runs.

#include <cmath>
#include <cstdint>

#include "control/nc/interpreter.hpp"

namespace vmt::control::channel {

struct ProgrammedStop {
  enum class Kind : uint8_t { kNone, kM00, kM01 };
  Kind pending = Kind::kNone;  ///< the block in work has M00 or M01 (M00 if both)
  Kind held = Kind::kNone;     ///< the channel holds at this stop
  bool optional = false;       ///< the optional-stop signal

  /// The block about to run.
  void Prepare(const nc::PreparedBlock& b) {
    pending = Kind::kNone;
    for (const nc::AuxFunction& f : b.aux) {
      if (f.letter != 'M') continue;
      const long m = std::lround(f.value);
      if (m == 0) pending = Kind::kM00;
      if (m == 1 && pending == Kind::kNone) pending = Kind::kM01;
    }
  }
  /// That block has ended: true if the channel holds now.
  bool Finish() {
    const Kind kind = pending;
    pending = Kind::kNone;
    if (kind != Kind::kM00 && (kind != Kind::kM01 || !optional)) return false;
    held = kind;
    return true;
  }
  /// A start, the reverse program or Control-Reset leaves the stop.
  void Leave() { pending = held = Kind::kNone; }
};

}  // namespace vmt::control::channel
