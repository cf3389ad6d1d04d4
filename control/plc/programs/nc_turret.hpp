#pragma once
// The PLC's part for an NC-controlled tool storage axis (repositioning manual 3.4, 4.2 Tool
// Storage Axis): the NC commands the turret's drive, so the PLC neither indexes it nor keeps it
// clamped against the drive - it releases the clamp (QTURRET_UNCLAMP) once and leaves the
// turret to the NC's position control - and passes the turret's jog keys mMGPOS / mMGNEG to
// PxxC.MGPOS / PxxC.MGNEG while the door is closed, as the feed axes' jog keys. A network of
// the machine_panel_nc_turret program (MachinePanel with it).

#include "control/gateway/signal_image.hpp"
#include "control/plc/plc_runtime.hpp"

namespace vmt::control::plc {

struct NcTurret {
  explicit NcTurret(const gateway::SignalImage& image);
  void operator()(PlcScan& scan, bool door_closed);

  // Signals (ids in the image).
  int P00C_MGPOS, P00C_MGNEG, mMGPOS, mMGNEG, QTURRET_UNCLAMP;
};

}  // namespace vmt::control::plc
