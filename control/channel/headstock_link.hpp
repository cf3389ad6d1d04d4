#pragma once
// What the channel keeps of the headstock changeover (C-axis manual 2.3, 3.3, 4.1-4.3) besides
// the sequencer itself (axes::HeadstockChangeover): the PLC's side, the block waiting for a
// mode, the mode the operator is shown.

#include "control/axes/headstock_changeover.hpp"

namespace vmt::control::channel {

/// The channel's side of the headstock changeover (the sequencer is axes::HeadstockChangeover).
struct HeadstockLink {
  axes::HeadstockPlc plc;  ///< ROTMOD_Q, SPMOD_Q, enables and AXD idents, as the gateway gave
  bool known = false;      ///< the power-on mode has been taken from the PLC
  axes::HeadstockMode waiting_for = axes::HeadstockMode::kNone;  ///< the block in work's need
  bool manual = false;  ///< the changeover in progress was commanded by a key
  /// The mode whose designation the user interface shows (the last completed changeover's).
  axes::HeadstockMode shown_mode = axes::HeadstockMode::kSpindle;
  double rotary_translation = 0;  ///< the rotary axis' translation in rotary axis mode
};

}  // namespace vmt::control::channel
