#pragma once
// What the SERCOS ring carries between the PLC's probe block and the measuring axes' drives
// (fast-measurement 7.2 and 7.3), in the runner: AXD_WR writes the probe parameters into a
// drive, which keeps them (S-0-0303, S-0-0307, S-0-0169, S-0-0170); each drive tick real-time
// control bit 2 (AxxC.QDDS) drives the enable S-0-0303 names, and real-time status bit 2
// (AxxS.IDDS) shows the latched flag S-0-0307 names.
//
// The channel writes each axis's whole DriveSetpoint every tick, so the probe control is set
// after it: WriteSetpoints runs between the channel and the backend.

#include <cstdint>
#include <vector>

#include "control/drive_bus.hpp"
#include "control/gateway/signal_image.hpp"
#include "control/plc/axd_wr.hpp"
#include "control/plc/programs/probe_drive_parameters.hpp"
#include "sim/model/machine_model.hpp"

namespace vmt::sim {

class ProbeGlue {
 public:
  /// The gateway's axes (GatewayLayoutOf) that are drives of `model`; `image` must outlive it.
  ProbeGlue(const MachineModel& model, control::gateway::SignalImage& image);

  /// AXD_WR: S-0-`ident` := `value` in the drive of axis number `axis`. A drive takes what its
  /// probe function has: S-0-0303 405/406 (or 0: none), S-0-0307 409..412 (or 0), S-0-0169
  /// (16 bits), S-0-0170 0..3; any other ident or value it refuses.
  control::plc::AxdWrStatus Write(int axis, int ident, int64_t value);

  /// After the channel has written `mdt`: each drive that was given probe parameters gets its
  /// probe control, the enable from AxxC.QDDS.
  void WriteSetpoints(control::MasterTelegram& mdt) const;

  /// AxxS.IDDS of each such drive from its probe status.
  void ReadStatus(const control::AmplifierTelegram& at);

  /// The parameters a drive keeps (zero until AXD_WR wrote them).
  const control::plc::ProbeDriveParameters& parameters(int drive) const {
    return drives_[drive].parameters;
  }

 private:
  struct Drive {
    int axis = -1;     ///< gateway axis number, -1: not an NC axis
    int qdds = -1;     ///< signal ids of AxxC.QDDS / AxxS.IDDS, -1: not in the image
    int idds = -1;
    bool written = false;  ///< AXD_WR has written a parameter
    control::plc::ProbeDriveParameters parameters;
  };

  control::gateway::SignalImage* image_;
  std::vector<Drive> drives_;  ///< per drive of the model
};

}  // namespace vmt::sim
