#pragma once
// C-axis manual 4.4 "Typical SPS Program: C Axis Mode": the main spindle <-> rotary axis (C)
// changeover of a lathe whose C servo drives the spindle through clutch K. At start the AXD
// idents 65013..65015 are initialised; on the NC's ROTMOD / SPMOD the program hunts, switches
// the clutch valves QROTMODE / QSPMODE, waits for the switches IROTMODE / ISPMODE, stops the
// hunting and acknowledges with ROTMOD_Q / SPMOD_Q (4.1). Additions of vmt are marked "vmt".

#include <cstdint>

#include "control/gateway/signal_image.hpp"
#include "control/plc/iec_standard_blocks.hpp"
#include "control/plc/plc_runtime.hpp"

namespace vmt::control::plc {

/// Axis numbers and the values the manual leaves to the machine builder.
struct CAxisChangeoverConfig {
  /// ISP_NR, the main spindle's axis number; 0: the one axis that has Axx.ROTMOD.
  int ISP_NR = 0;
  /// IROT_NR, the C servo's axis number; 0: the axis other than the spindle with the AXD idents
  /// (the one named C if there are several).
  int IROT_NR = 0;
  /// Process whose PxxS.STOP stops the hunting and whose Pxx.MSG_WR carries the messages.
  int process = 0;

  // Initialisation of the spindle (4.4 networks 1-6): 100 1/min, 500 rad/s^2, 0 degrees.
  int64_t spindle_speed = 0x000F4240;  ///< ident 65013 [0.0001 1/min]
  int64_t spindle_acc = 0x000001F4;    ///< ident 65014 [rad/s^2]
  int64_t spindle_pos = 0;             ///< ident 65015 [0.0001 deg]
  // The same for the C servo, whose hunting is a speed specification (65012 bit 2) and so runs
  // at its 65013 / 65014 (vmt: 1 1/min, 6 deg/s, below the relative speed clutch K meshes at).
  int64_t rotary_speed = 10000;  ///< ident 65013 [0.0001 1/min]
  int64_t rotary_acc = 10;       ///< ident 65014 [rad/s^2]
  int64_t rotary_pos = 0;        ///< ident 65015 [0.0001 deg]

  /// vmt: the longest wait for IROTMODE / ISPMODE after the valves switched (hunting included).
  PlcTime T_CLUTCH = std::chrono::seconds(5);
  /// vmt: message numbers (Pxx.MSG_WR) for a clutch that did not engage / did not release.
  int MSG_ROTERR = 220;
  int MSG_SPERR = 221;

  /// The deliberately wrong variant ("c_axis_changeover_wrong"): ROTMOD_Q is given with the
  /// valve, before IROTMODE reports the clutch meshed, so the NC positions C while the servo
  /// may still turn a gear the spindle is not coupled to.
  bool acknowledge_before_clutch = false;
};

struct CAxisChangeover {
  using Config = CAxisChangeoverConfig;

  /// Resolves the signals; throws std::invalid_argument naming what the machine lacks (no
  /// spindle with ROTMOD, no separate rotary axis, a missing valve or switch).
  explicit CAxisChangeover(const gateway::SignalImage& image);
  CAxisChangeover(const gateway::SignalImage& image, const Config& config);
  void operator()(PlcScan& scan);
  /// The scan's parts: the spindle's initialisation (4.4: the AXD idents of hunting), the
  /// changeover to rotary axis mode and to spindle mode (networks 1-11 and 12-21, each with its
  /// switch, whether the clutch has got there, and the immediate stop), the NC message.
  void Initialize(PlcScan& s);
  void ToRotaryAxisMode(PlcScan& s, bool IROT, bool clutch_engaged, bool STOP);
  void ToSpindleMode(PlcScan& s, bool ISP, bool clutch_released, bool STOP);
  void WriteMessage(PlcScan& s);

  Config config;
  int ISP_NR, IROT_NR;

  // Signals (ids in the image), the manual's names; Axx of the spindle (SP) or the C servo (ROT).
  int ROTMOD, ROTMOD_Q, SPMOD, SPMOD_Q;            // A<ISP_NR>.*
  int SP_65012, SP_65013, SP_65014, SP_65015;      // A<ISP_NR>.AXD.*
  int ROT_65012, ROT_65013, ROT_65014, ROT_65015;  // A<IROT_NR>.AXD.*
  int SP_C_READY, ROT_C_READY;                     // AxxC.READY: the drives' controller enable
  int QROTMODE, QSPMODE, IROTMODE, ISPMODE;        // machine I/O
  int PxxS_STOP, Pxx_MSG_WR;

  // Markers of the program (PLC memory, not gateway signals), named as in the manual.
  bool MSPEEDOK = false, MACCOK = false, READY = false;  // initialisation done, step by step
  bool M_ROTAC = false, M_SPLAC = false;                 // changeover flags
  bool MPEND1R = false, MPENDOR = false;                 // hunting ON / OFF, rotary axis
  bool MPEND1S = false, MPENDOS = false;                 // hunting ON / OFF, spindle
  bool M_ROTERR = false, M_SPERR = false;                // vmt: clutch timeouts
  TON T_ROT, T_SP;                                       // vmt: wait for IROTMODE / ISPMODE
  int msg_written = 0;                                   // vmt: what MSG_WR holds from us
};

}  // namespace vmt::control::plc
