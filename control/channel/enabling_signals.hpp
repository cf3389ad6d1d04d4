#pragma once
// The PLC's enabling signals the channel obeys: PxxC.ENABL for the process, AxxC.ENABL per
// channel axis (C-axis manual 2.3, 4.2).

#include <vector>

namespace vmt::control::channel {

struct EnablingSignals {
  bool process = true;
  std::vector<bool> axes;  ///< per channel axis; empty: all enabled
};

}  // namespace vmt::control::channel
