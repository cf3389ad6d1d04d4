#pragma once
// The PLC program of lathe-c1's operator panel and machine functions, as a machine builder
// would write it around the NC: panel keys become the NC's control signals (mode, cycle start,
// feed hold, reset, single block, jog), the door, tailstock quill and coolant are operated from
// their keys and from M functions (M08/M09 coolant), with the interlocks a real machine has:
//  - the door opens only with the program not running and every spindle at standstill; an
//    open door holds the feed and refuses cycle start;
//  - the quill moves only with the program not running;
//  - M08 is acknowledged when the coolant pressure switch reports flow (a pump that never
//    builds pressure keeps the block waiting, visibly), every other M/H/T function at once
//    (the NC itself runs M3/M4/M5/M19).
// The repositioning manual's machine keys (8.2) are a network of it (ReposMachineKeys), and so is
// the C-axis manual's changeover of a headstock with a clutch (4.4, CAxisChangeover). A panel
// with jog mode keys mJOGM0..2 toggles PxxC.JOGM0..2 with them (the jog mode's code, bit by
// bit); its override switches (selectors mFOVR, mSOVR_<spindle>) are the feed override PxxC.FOVR
// and the spindle's override AxxC.SOVR, in percent. machine_panel_nc_turret is the same program for
// a machine whose turret the NC controls (NcTurret).

#include <optional>
#include <vector>

#include "control/gateway/signal_image.hpp"
#include "control/plc/iec_standard_blocks.hpp"
#include "control/plc/plc_runtime.hpp"
#include "control/plc/programs/c_axis_changeover.hpp"
#include "control/plc/programs/nc_turret.hpp"
#include "control/plc/programs/repos_machine_keys.hpp"

namespace vmt::control::plc {

struct MachinePanel {
  explicit MachinePanel(const gateway::SignalImage& image, bool nc_turret = false);
  void operator()(PlcScan& scan);

  // NC signals (ids in the image).
  int C_AUTO, C_MANU, C_START, C_STOP, C_RESET, C_SBL, C_AUXACK;
  int S_RUN, S_AUXSTB, S_MFUNC;
  std::vector<int> standstill;  ///< AxxS.N_NMIN of every spindle
  struct JogKey {
    int key, signal;  ///< mJGPOS_X -> A01C.JGPOS
  };
  std::vector<JogKey> jog;
  struct JogModeBit {
    int key = -1, signal = -1;  ///< mJOGM1 -> P00C.JOGM1
    R_TRIG press;
    bool on = false;
  };
  std::vector<JogModeBit> jog_mode;
  struct OverrideSwitch {
    int selector, signal;  ///< mFOVR -> P00C.FOVR, mSOVR_S -> A03C.SOVR
  };
  std::vector<OverrideSwitch> overrides;
  // Machine I/O and panel keys.
  int mAUTO, mMANU, mSTART, mSTOP, mRESET, mSBL, mCOOLANT, mDOOR, mTAILSTOCK;
  int QDOOR_OPEN, IDOOR_CLOSED, QTAILSTOCK, QCOOLANT, ICOOLANT_PRESSURE;

  // PLC memory.
  R_TRIG start_key, stop_key, sbl_key, coolant_key, door_key, quill_key;
  bool feed_hold = false, single_block = false, coolant = false, door_open = false, quill = false;
  bool aux_acked = false;  ///< AUXACK pulsed last scan: drop it for one scan (edge for the NC)
  std::optional<ReposMachineKeys> repos;
  std::optional<CAxisChangeover> changeover;
  std::optional<NcTurret> nc_turret;
};

}  // namespace vmt::control::plc
