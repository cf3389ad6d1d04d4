#include "control/plc/programs/nc_turret.hpp"

#include "control/plc/programs/require_signal.hpp"

namespace vmt::control::plc {

NcTurret::NcTurret(const gateway::SignalImage& image)
    : P00C_MGPOS(RequireSignal(image, "P00C.MGPOS")),
      P00C_MGNEG(RequireSignal(image, "P00C.MGNEG")),
      mMGPOS(RequireSignal(image, "mMGPOS")),
      mMGNEG(RequireSignal(image, "mMGNEG")),
      QTURRET_UNCLAMP(RequireSignal(image, "QTURRET_UNCLAMP")) {}

void NcTurret::operator()(PlcScan& s, bool door_closed) {
  // Clamped, the turret would hold against the NC's drive (the clamp's torque is ten times
  // the drive's); the NC holds it at its station in position control instead.
  s.SetBool(QTURRET_UNCLAMP, true);
  s.SetBool(P00C_MGPOS, s.Bool(mMGPOS) && door_closed);
  s.SetBool(P00C_MGNEG, s.Bool(mMGNEG) && door_closed);
}

}  // namespace vmt::control::plc
