#pragma once
// The fast-measurement function block QMFB1Axx (mtc200-fast-measurement.md 7.2, figures 7-26 to
// 7-28; its NC side: 6.1 Q9992, 6.2 events 7/29/30, 3.1 BASISMESSPAGE, 7.3 drive probe) and the
// program that runs one instance of it, QMFB1A00, on the gateway as the manual's typical
// application (7.2, network 2) wires it.

#include <array>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "control/gateway/signal_image.hpp"
#include "control/measure/measuring_pages.hpp"
#include "control/plc/plc_runtime.hpp"

namespace vmt::control::plc {

/// BASISMESSPAGE data elements 6..10 (3.1): written by the NC program (SETTING and the stylus
/// page), read by the block when the NC outputs Q9992.
struct BasisMessPage {
  bool PIN_DDS = false;             ///< 6: probe at drive pin 4 (0) or pin 5 (1)
  bool Pushbutton_contact = false;  ///< 7: normally open (0) or normally closed (1) contact
  bool Measuring_axis_1 = false;    ///< 8: measuring axis 1 available
  bool Measuring_axis_2 = false;    ///< 9
  bool Measuring_axis_3 = false;    ///< 10
};

/// What the system function MTD_RD delivers for the page BasisPage of process MessProc.
struct MtdRdResult {
  BasisMessPage page;
  int failed_element = 0;  ///< 0, or the element 6..10 whose reading failed (FEHLER_NR 23..27)
  bool channels_occupied = false;  ///< all eight process data channels busy: the read waits
};

/// What the system function AXD_WR reports for one measuring axis's drive.
struct AxdWrResult {
  bool axis_exists = true;   ///< false: parameters of a non-existent axis (FEHLER_NR 40)
  int failed_parameter = 0;  ///< 0, or the S-0-0nnn number that failed: 303, 307, 169, 170
};

/// The function block itself. Pins are members named as in figure 7-26 (INT is int16_t); the
/// caller sets the inputs, calls it once per scan and reads the outputs. The NC side, which the
/// real block reaches through system functions rather than pins (Q_FKT/Q_FKT_Q, event
/// read/write, MTD_RD, AXD_WR), is a second set of members the caller copies in and out.
///
/// Sequence (7.2 "Functional Sequence", 6.1, 6.2):
///  1. Q_Nummer (Q9992, from SETTING): read BASISMESSPAGE (MTDaktiv, one scan), then write the
///     probe parameters of each requested measuring axis's drive (AXDaktiv, one scan per axis,
///     Init_OK_n as each succeeds), then acknowledge the Q function.
///  2. Koll_EV (29, start of MOVE/PROBE): the selected probe is requested (Q_MTst1/2); while the
///     event is set, a displaced probe is a collision (Q_MTstKol).
///  3. Mess_EV (30, setup position): once the probe is ready (Q_MTstOK) and not displaced, QDDS_n
///     enables the drives' probe latch; a scan later, with every IDDS_n clear, the block resets
///     Koll_EV: that is the acknowledgement the NC waits for before the measuring path.
///  4. Contact on the measuring path (the probe input or a drive's latch IDDS_n): Touch_EV (7).
///  5. Mess_EV reset (end of the measuring path): QDDS_n off, so the next measurement arms a new
///     latch (7.3: only the first edge after the enable's 0-1 transition is latched); without a
///     contact, Q_MTstKmp.
struct QMFB1Axx {
  // ---- Inputs (figure 7-26), presets as 7.2 gives them ----
  bool ENABLE = false;  ///< 0: not processed, errors cleared, block reset
  bool RESET = false;   ///< clears errors and resets the measuring sequence (while TRUE)
  int16_t Q_Nummer = 9992;
  int16_t Koll_EV = 29;
  int16_t Mess_EV = 30;
  int16_t Touch_EV = 7;
  int16_t BasisPage = 90;
  int16_t MessProc = 0;
  int16_t ACHS_NR_1 = 0;  ///< 0 = axis does not exist
  int16_t ACHS_NR_2 = 0;
  int16_t ACHS_NR_3 = 0;
  bool I_MT_OK1 = false;  ///< probe 1 ready
  bool I_MTast1 = false;  ///< probe 1 contact, in the logic of BASISMESSPAGE element 7
  bool I_MT_OK2 = false;
  bool I_MTast2 = false;
  bool IDDS_1 = false;  ///< axis 1 real-time status bit: the drive latched a measured value
  bool IDDS_2 = false;
  bool IDDS_3 = false;
  bool AXDdisabl = false;  ///< AXD_WR not allowed now: the drive initialisation waits
  bool MTDdisabl = false;  ///< MTD_RD not allowed now: reading the page waits

  // ---- Outputs ----
  bool Init_OK_1 = false, Init_OK_2 = false, Init_OK_3 = false;
  bool QDDS_1 = false, QDDS_2 = false, QDDS_3 = false;  ///< real-time control bits: latch enable
  bool Q_MTst1 = false;                                 ///< activate probe 1
  bool Q_MTst2 = false;                                 ///< activate probe 2
  bool Q_MTstOK = false;                                ///< the requested probe is ready
  bool Q_MTstKol = false;                               ///< probe collision (latched until RESET)
  bool Q_MTstKmp = false;  ///< test point not found (latched until RESET)
  bool Q_MTst = false;     ///< selected probe displaced
  bool FEHLER = false;     ///< error detected (latched until RESET)
  int16_t FEHLER_NR = 0;   ///< figure 7-28
  bool AXDaktiv = false;
  bool MTDaktiv = false;
  bool P_Dat_ovr = false;

  // ---- NC side (system functions) ----
  bool Q_FKT = false;     ///< in: the NC outputs Q function Q_Nummer in process MessProc
  bool Q_FKT_Q = false;   ///< out: its acknowledgement
  bool EV_Koll = false;   ///< in/out: event Koll_EV; the block resets it as acknowledgement
  bool EV_Mess = false;   ///< in: event Mess_EV
  bool EV_Touch = false;  ///< in/out: event Touch_EV; the block sets it on contact
  MtdRdResult MTD_RD;     ///< in: answer to reading BasisPage
  std::array<AxdWrResult, 3> AXD_WR;  ///< in: answer to initialising measuring axis 1..3

  void operator()(PlcTime now);

  /// What an AXD_WR issued in this call (AXDaktiv) writes: into the drive of measuring axis
  /// axd_axis() (0..2), the probe parameters of the page read at Q9992 (AxdWrProbeParameters).
  int axd_axis() const { return axis_; }
  const BasisMessPage& page() const { return page_; }

 private:
  enum class Init : uint8_t { kNone, kReadPage, kWriteDrive };

  void Disable();
  void ResetSequence();
  void CheckParameters();
  void Initialise();
  void IssueRead();
  void IssueWrite();
  void Measure();
  void Fehler(int nr);
  int16_t AchsNr(int n) const;
  bool& InitOk(int n);

  Init init_ = Init::kNone;
  bool issued_ = false;       ///< the current MTD_RD / AXD_WR call has been made (answer next scan)
  int axis_ = 0;              ///< measuring axis (0..2) AXD_WR is initialising
  bool initialised_ = false;  ///< Q9992 completed since ENABLE / the last failed attempt
  BasisMessPage page_;        ///< as MTD_RD read it at the last Q9992
  bool probe2_ = false;       ///< PIN_DDS: pin 5 -> probe 2
  bool nc_contact_ = false;   ///< Pushbutton_contact: the contact opens when displaced
  std::array<bool, 3> requested_{};                 ///< Measuring_axis_1..3
  bool armed_ = false;                              ///< QDDS_n on: the drives' latch is enabled
  bool acked_ = false;                              ///< Koll_EV reset for this measuring path
  bool touched_ = false;                            ///< contact on this measuring path
  bool koll_before_ = false, mess_before_ = false;  ///< the events in the previous call
};

/// The manual's PLC program around the block (7.2 network 2): each scan it copies the pins of
/// the gateway instance QMFB1A00 into the block, the NC side from the process MessProc (event
/// Koll_EV/Mess_EV/Touch_EV -> Pxx.EVn, Q_Nummer -> Pxx.Qnnnn and Pxx.Qnnnn_Q) and the drives of
/// the axes ACHS_NR_n (AxxS.IDDS in, AxxC.QDDS out), calls it and writes its outputs back.
struct ProbeBlockProgram {
  explicit ProbeBlockProgram(const gateway::SignalImage& image);
  void operator()(PlcScan& scan);

  QMFB1Axx Measuring;  ///< the instance (the manual's name for QMFB1A00)
  /// The NC's machine data pages (control/measure): MTD_RD reads BASISMESSPAGE elements 6..10
  /// from page BasisPage of process MessProc there; a page or process the NC does not have
  /// fails the read of element 6 (FEHLER_NR 23). Not owned; null: basis_page below answers.
  const measure::MeasuringPages* measuring_pages = nullptr;
  /// Stands in for BASISMESSPAGE while no pages are connected: the lathe's SETTING(X, Z, , ...)
  /// with the stylus at pin 4 (probe 1) and a normally open contact.
  BasisMessPage basis_page{false, false, true, true, false};
  /// Typical application networks 5, 6 (flags of the program): the NC has output Q9999 / Q9998
  /// in process MessProc and the fault stands (see operator() for what clears each).
  bool M_Q9999 = false;
  bool M_Q9998 = false;

 private:
  /// The typical application's networks in scan order: the pins into the block (returns the
  /// axes ACHS_NR_n name), the NC side and the call, AxxC.QDDS, the Q functions'
  /// acknowledgements and flags, the process lock and messages, the output pins.
  std::array<int, 3> ReadPins(PlcScan& s);
  void CallBlock(PlcScan& s, const std::array<int, 3>& axes);
  void WriteQdds(PlcScan& s, const std::array<int, 3>& axes);
  void AcknowledgeQFunctions(PlcScan& s, bool reversing);
  void TrackQFunctionFlags(PlcScan& s, bool reversing);
  void LockProcess(PlcScan& s, bool reversing);
  void WritePins(PlcScan& s);
  /// The signal of process MessProc in `ids` (-1: none), and its value (false: none).
  int InProcess(const std::map<int, int>& ids) const;
  bool ReadInProcess(const PlcScan& s, const std::map<int, int>& ids) const;

  // Input pins.
  int ENABLE, RESET, Q_Nummer, Koll_EV, Mess_EV, Touch_EV, BasisPage, MessProc;
  std::array<int, 3> ACHS_NR;
  int I_MT_OK1, I_MTast1, I_MT_OK2, I_MTast2, AXDdisabl, MTDdisabl;
  std::array<int, 3> IDDS;
  // Output pins.
  std::array<int, 3> Init_OK, QDDS;
  int Q_MTst1, Q_MTst2, Q_MTstOK, Q_MTstKol, Q_MTstKmp, Q_MTst, FEHLER, FEHLER_NR, AXDaktiv,
      MTDaktiv, P_Dat_ovr;

  // The NC's signals, by process and number / by axis number (-1: not on this machine).
  std::map<std::pair<int, int>, int> events_, q_functions_, q_acks_;
  std::array<int, 33> axis_qdds_, axis_idds_;
  // The probes' wiring where the machine has it (lathe-c1: IPROBE_READY / IPROBE_CONTACT to
  // I_MT_OK1 / I_MTast1, Q_MTst1 switching the probe on with QPROBE_ON; its axial probe
  // IPROBE2_READY / IPROBE2_CONTACT to I_MT_OK2 / I_MTast2, Q_MTst2 to QPROBE2_ON); -1: not
  // wired.
  int probe_ready_ = -1, probe_contact_ = -1, probe_on_ = -1;
  int probe2_ready_ = -1, probe2_contact_ = -1, probe2_on_ = -1;
  std::vector<int> qdds_axes_;  ///< axes whose AxxC.QDDS the program wrote last scan
  /// AXD_WR's answers to the writes issued last scan, per measuring axis, where the runtime
  /// connects AXD_WR to the drives (PlcScan::axd_wr).
  std::array<AxdWrResult, 3> axd_answers_{};
  int q_ack_ = -1;              ///< the Pxx.Qnnnn_Q written last scan
  std::map<int, int> reverse_running_;  ///< PxxS.REV by process
  /// PxxC.REV (reverse program start), PxxC.RESET (Control-Reset), PxxS.STOP by process: what
  /// clears M_Q9999 / M_Q9998.
  std::map<int, int> reverse_start_, control_reset_, program_stopped_;
  bool q9998_stopped_ = false;  ///< the program has stopped since M_Q9998 was set
  bool q9999_before_ = false, q9998_before_ = false;  ///< the NC's Q outputs last scan
  /// PxxC.ENABL, Pxx.MSG_WR, Pxx.MSG_WR_N by process: the typical application's reaction to a
  /// probe collision or an error of the block.
  std::map<int, int> process_enable_, message_, message_n_;
};

}  // namespace vmt::control::plc
