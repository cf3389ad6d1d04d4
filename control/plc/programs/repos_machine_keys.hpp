#pragma once
// Repositioning manual 8.2 "SPS Program": the machine keys mREPOS and mRESTA call repositioning
// or NC-block restart in manual mode, while the NC reports it possible (P00S.REPOS) and the
// operator has not switched it off (mRaR_OFF). Each call holds itself until the other key is
// pressed or the enable drops.
//
// With the machine's spindle-adjust keys (8.1 step 3: the user interface's flags mAxxCM3,
// mAxxCM4, mAxxCM5, mAxxCM19) it also maps them onto the spindle's AxxC.M3 ... AxxC.M19; and on
// a spindle with rotary axis mode it stores the mode at each interruption in event 30, which
// the REPOS subroutine of 8.3 tests (BES .ROTMOD 30; 4.2 instruction: "the operating mode must
// be stored in the PLC in the event of program interruptions").

#include <vector>

#include "control/gateway/signal_image.hpp"
#include "control/plc/iec_standard_blocks.hpp"
#include "control/plc/plc_runtime.hpp"

namespace vmt::control::plc {

struct ReposMachineKeys {
  explicit ReposMachineKeys(const gateway::SignalImage& image);
  void operator()(PlcScan& scan);

  // Signals (ids in the image).
  int P00S_REPOS, P00C_REPOS, P00C_RESTA;
  int mREPOS, mRESTA, mRaR_OFF;
  struct Adjust {
    int flag, signal;  ///< mAxxCM3 -> AxxC.M3
  };
  std::vector<Adjust> spindle_adjust;
  int ROTMOD_Q = -1, EV30 = -1;  ///< the spindle's rotary axis mode, stored in event 30
  // Markers of the program (PLC memory, not gateway signals).
  bool mRaR_OK = false;
  R_TRIG interrupted;  ///< P00S.REPOS rising: the program has just been interrupted
};

}  // namespace vmt::control::plc
