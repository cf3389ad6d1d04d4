#include "control/plc/programs/repos_machine_keys.hpp"

#include <string>

#include "control/plc/programs/require_signal.hpp"

namespace vmt::control::plc {

ReposMachineKeys::ReposMachineKeys(const gateway::SignalImage& image)
    : P00S_REPOS(RequireSignal(image, "P00S.REPOS")),
      P00C_REPOS(RequireSignal(image, "P00C.REPOS")),
      P00C_RESTA(RequireSignal(image, "P00C.RESTA")),
      mREPOS(RequireSignal(image, "mREPOS")),
      mRESTA(RequireSignal(image, "mRESTA")),
      mRaR_OFF(RequireSignal(image, "mRaR_OFF")) {
  for (int id = 0; id < image.size(); ++id) {
    const gateway::Signal& s = image.table()[id];
    for (const char* m : {"M3", "M4", "M5", "M19"}) {
      if (s.pattern != std::string("AxxC.") + m) continue;
      // "A03C.M3" -> the flag "mA03CM3".
      const int flag = image.Find("m" + s.name.substr(0, 4) + m);
      if (flag >= 0) spindle_adjust.push_back({flag, id});
    }
    if (s.pattern == "Axx.ROTMOD_Q") ROTMOD_Q = id;
  }
  if (ROTMOD_Q >= 0) EV30 = image.Find("P00.EV30");
}

void ReposMachineKeys::operator()(PlcScan& s) {
  // Network 1: repositioning / NC-block restart permitted.
  mRaR_OK = s.Bool(P00S_REPOS) && !s.Bool(mRaR_OFF);
  // Network 2: REPOSITIONING, held by its own contact.
  s.SetBool(P00C_REPOS, (s.Bool(mREPOS) || s.Bool(P00C_REPOS)) && mRaR_OK && !s.Bool(mRESTA));
  // Network 3: NC-BLOCK RESTART, the same way.
  s.SetBool(P00C_RESTA, (s.Bool(mRESTA) || s.Bool(P00C_RESTA)) && mRaR_OK && !s.Bool(mREPOS));
  // 8.1 step 3: the adjust flags go to the spindle's gateway signals.
  for (const Adjust& a : spindle_adjust) s.SetBool(a.signal, s.Bool(a.flag));
  // 4.2 instruction: the mode at the interruption, for BES .ROTMOD 30 in the REPOS subroutine.
  interrupted(s.Bool(P00S_REPOS));
  if (interrupted.Q && EV30 >= 0) s.SetBool(EV30, s.Bool(ROTMOD_Q));
}

}  // namespace vmt::control::plc
