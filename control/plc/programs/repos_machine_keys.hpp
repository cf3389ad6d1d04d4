#pragma once
// Repositioning manual 8.2 "SPS Program": the machine keys mREPOS and mRESTA call repositioning
// or NC-block restart in manual mode, while the NC reports it possible (P00S.REPOS) and the
// operator has not switched it off (mRaR_OFF). Each call holds itself until the other key is
// pressed or the enable drops.

#include "control/gateway/signal_image.hpp"
#include "control/plc/plc_runtime.hpp"

namespace vmt::control::plc {

struct ReposMachineKeys {
  explicit ReposMachineKeys(const gateway::SignalImage& image);
  void operator()(PlcScan& scan);

  // Signals (ids in the image).
  int P00S_REPOS, P00C_REPOS, P00C_RESTA;
  int mREPOS, mRESTA, mRaR_OFF;
  // Marker of the program (PLC memory, not a gateway signal).
  bool mRaR_OK = false;
};

}  // namespace vmt::control::plc
