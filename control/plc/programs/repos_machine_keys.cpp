#include "control/plc/programs/repos_machine_keys.hpp"

#include "control/plc/programs/require_signal.hpp"

namespace vmt::control::plc {

ReposMachineKeys::ReposMachineKeys(const gateway::SignalImage& image)
    : P00S_REPOS(RequireSignal(image, "P00S.REPOS")),
      P00C_REPOS(RequireSignal(image, "P00C.REPOS")),
      P00C_RESTA(RequireSignal(image, "P00C.RESTA")),
      mREPOS(RequireSignal(image, "mREPOS")),
      mRESTA(RequireSignal(image, "mRESTA")),
      mRaR_OFF(RequireSignal(image, "mRaR_OFF")) {}

void ReposMachineKeys::operator()(PlcScan& s) {
  // Network 1: repositioning / NC-block restart permitted.
  mRaR_OK = s.Bool(P00S_REPOS) && !s.Bool(mRaR_OFF);
  // Network 2: REPOSITIONING, held by its own contact.
  s.SetBool(P00C_REPOS, (s.Bool(mREPOS) || s.Bool(P00C_REPOS)) && mRaR_OK && !s.Bool(mRESTA));
  // Network 3: NC-BLOCK RESTART, the same way.
  s.SetBool(P00C_RESTA, (s.Bool(mRESTA) || s.Bool(P00C_RESTA)) && mRaR_OK && !s.Bool(mREPOS));
}

}  // namespace vmt::control::plc
