#include "control/plc/programs/c_axis_changeover.hpp"

#include <stdexcept>
#include <string>
#include <vector>

#include "control/gateway/signal_table.hpp"
#include "control/plc/programs/require_signal.hpp"

namespace vmt::control::plc {
namespace {

using gateway::InstanceName;

// 65012 request bits (2.2): the manual writes the whole word, as AXD_WR transfers four bytes.
constexpr int64_t kHuntingSpindle = 0b00000001;  // 2#00000001, bit 0: spindle hunting
constexpr int64_t kSpeedSpec = 0b00000100;       // 2#00000100, bit 2: speed specification
constexpr int64_t kNoFunction = 0b00000000;      // 2#00000000

[[noreturn]] void Missing(const std::string& what) {
  throw std::invalid_argument("the C-axis changeover program needs " + what);
}

// ISP_NR: the spindle the standard functions ROTMOD / SPMOD are called with (AXIS input).
int FindSpindle(const gateway::SignalImage& image) {
  std::vector<int> found;
  for (const gateway::Signal& s : image.table())
    if (s.pattern == "Axx.ROTMOD") found.push_back(s.instance);
  if (found.empty()) Missing("a main spindle with ROTMOD/SPMOD (Axx.ROTMOD); the machine has none");
  if (found.size() > 1) Missing("ISP_NR in its Config: the machine has several spindles");
  return found.front();
}

// IROT_NR: the separate C servo, which has the AXD idents without being the spindle (4.3).
int FindRotaryAxis(const gateway::SignalImage& image, int isp_nr) {
  std::vector<const gateway::Signal*> found;
  for (const gateway::Signal& s : image.table())
    if (s.pattern == "Axx.AXD.65012" && s.instance != isp_nr) found.push_back(&s);
  if (found.empty())
    Missing("a rotary axis for the C mode of the spindle " + InstanceName("Axx", isp_nr) +
            " (an NC axis with Axx.AXD.65012 besides it); the machine has none");
  if (found.size() == 1) return found.front()->instance;
  for (const gateway::Signal* s : found)
    if (s->instance_name == "C") return s->instance;
  Missing("IROT_NR in its Config: the machine has several rotary axes, none of them called C");
}

int Axis(const gateway::SignalImage& image, std::string_view pattern, int number) {
  return RequireSignal(image, InstanceName(pattern, number));
}

}  // namespace

CAxisChangeover::CAxisChangeover(const gateway::SignalImage& image)
    : CAxisChangeover(image, Config{}) {}

CAxisChangeover::CAxisChangeover(const gateway::SignalImage& image, const Config& c)
    : config(c),
      ISP_NR(c.ISP_NR > 0 ? c.ISP_NR : FindSpindle(image)),
      IROT_NR(c.IROT_NR > 0 ? c.IROT_NR : FindRotaryAxis(image, ISP_NR)),
      ROTMOD(Axis(image, "Axx.ROTMOD", ISP_NR)),
      ROTMOD_Q(Axis(image, "Axx.ROTMOD_Q", ISP_NR)),
      SPMOD(Axis(image, "Axx.SPMOD", ISP_NR)),
      SPMOD_Q(Axis(image, "Axx.SPMOD_Q", ISP_NR)),
      SP_65012(Axis(image, "Axx.AXD.65012", ISP_NR)),
      SP_65013(Axis(image, "Axx.AXD.65013", ISP_NR)),
      SP_65014(Axis(image, "Axx.AXD.65014", ISP_NR)),
      SP_65015(Axis(image, "Axx.AXD.65015", ISP_NR)),
      ROT_65012(Axis(image, "Axx.AXD.65012", IROT_NR)),
      ROT_65013(Axis(image, "Axx.AXD.65013", IROT_NR)),
      ROT_65014(Axis(image, "Axx.AXD.65014", IROT_NR)),
      ROT_65015(Axis(image, "Axx.AXD.65015", IROT_NR)),
      SP_C_READY(Axis(image, "AxxC.READY", ISP_NR)),
      ROT_C_READY(Axis(image, "AxxC.READY", IROT_NR)),
      QROTMODE(RequireSignal(image, "QROTMODE")),
      QSPMODE(RequireSignal(image, "QSPMODE")),
      IROTMODE(RequireSignal(image, "IROTMODE")),
      ISPMODE(RequireSignal(image, "ISPMODE")),
      PxxS_STOP(RequireSignal(image, InstanceName("PxxS.STOP", c.process))),
      Pxx_MSG_WR(RequireSignal(image, InstanceName("Pxx.MSG_WR", c.process))) {
  if (ISP_NR == IROT_NR) Missing("two different axes for ISP_NR and IROT_NR");
}

void CAxisChangeover::operator()(PlcScan& s) {
  Initialize(s);
  // vmt: no changeover before the drives know their hunting values.
  if (!READY) return;
  const bool IROT = s.Bool(IROTMODE), ISP = s.Bool(ISPMODE);
  // 2.3 / 3.3 Immediate Stop: movements the SPS causes in the changeover phase (the hunting)
  // stop at once while PxxSSTOP is 1, and resume with it (the NC keeps the changeover pending).
  const bool STOP = s.Bool(PxxS_STOP);
  ToRotaryAxisMode(s, IROT, IROT && !ISP, STOP);
  ToSpindleMode(s, ISP, ISP && !IROT, STOP);
  WriteMessage(s);
}

void CAxisChangeover::Initialize(PlcScan& s) {
  // ---- Initializing the main spindle (4.4, "simple solution" without safety request) -------
  // INIT is the cold start: the program's first scan. Each AXD_WR starts when the previous one
  // is done, as the manual chains them; a write here is done within the scan, so all three
  // happen in the first one.
  // vmt: the C servo gets its idents as well, since its hunting (network 5) is a speed
  // specification that runs at its own 65013 / 65014, which the manual leaves unwritten.
  const bool INIT = !MSPEEDOK;
  if (INIT) {  // networks 1-2, WRSPEED
    s.SetInt(SP_65013, config.spindle_speed);
    s.SetInt(ROT_65013, config.rotary_speed);
    MSPEEDOK = true;
  }
  if (MSPEEDOK && !MACCOK) {  // networks 3-4, WRACC
    s.SetInt(SP_65014, config.spindle_acc);
    s.SetInt(ROT_65014, config.rotary_acc);
    MACCOK = true;
  }
  if (MACCOK && !READY) {  // networks 5-6, WRPOS
    s.SetInt(SP_65015, config.spindle_pos);
    s.SetInt(ROT_65015, config.rotary_pos);
    READY = true;
  }
}

void CAxisChangeover::ToRotaryAxisMode(PlcScan& s, bool IROT, bool clutch_engaged, bool STOP) {
  // ---- Rotary axis mode / spindle mode changeover --------------------------------------------
  // Networks 1-2: changeover to rotary axis mode: ROTMOD(ACTIVE := 1, AXIS := ISP_NR). The
  // pre-selection is a level for as long as rotary axis mode is selected (4.1), so the networks
  // below run on every scan of it. vmt: ROTMOD together with SPMOD is no state the NC should
  // give; spindle mode (clutch out) wins.
  M_ROTAC = s.Bool(ROTMOD) && !s.Bool(SPMOD);
  if (M_ROTAC) {
    // The spindle-side markers restart, so that the next changeover to spindle mode hunts and
    // stops hunting again (the manual's MPENDIS is MPEND1S). vmt: a changeover to spindle mode
    // that was still hunting (the NC gave it up, e.g. reverse 2.3) stops its hunting first.
    if (MPEND1S && !MPENDOS) s.SetInt(SP_65012, kNoFunction);
    MPENDOS = false;
    MPEND1S = false;
  }
  // Network 3: JMPCN norot.
  if (M_ROTAC) {
    // vmt (4.3): the C servo needs its controller enable to hunt and to take the spindle over.
    s.SetBool(ROT_C_READY, true);
    // Networks 4-5: AXD1R, hunting ON for the rotary axis while the clutch is not engaged, so
    // the dogs find a tooth gap: 65012 := 2#00000100 (speed specification) on IROT_NR.
    if (!IROT && !MPEND1R && !STOP && !M_ROTERR) {
      s.SetInt(ROT_65012, kSpeedSpec);
      MPEND1R = true;
    }
    // Networks 6-7: trigger the valves for the changeover to rotary axis mode.
    s.SetBool(QSPMODE, false);
    s.SetBool(QROTMODE, true);
    // Networks 8-9: AXD0R, hunting OFF for the rotary axis once the clutch is engaged.
    if (clutch_engaged && !MPENDOR) {
      s.SetInt(ROT_65012, kNoFunction);
      MPENDOR = true;
      // vmt (4.4 "Mechanical Structure"): once the clutch has switched, the spindle's controller
      // enable goes off, so that the spindle idles and C alone holds it.
      s.SetBool(SP_C_READY, false);
    }
  }
  // vmt: the wait for IROTMODE is limited. The manual's program waits for ever, and the NC with
  // it (1.2: block preparation stops until the switching is completed). After T_CLUTCH the
  // hunting stops (an SPS movement must not go on unwatched), the NC gets a message, ROTMOD_Q
  // stays off and the valves stay as they are: Control-Reset ends the NC's request (2.3), which
  // clears the error, and a new request hunts again. Time under PxxSSTOP does not count.
  T_ROT(M_ROTAC && !clutch_engaged && !STOP, config.T_CLUTCH, s.now());
  if (T_ROT.Q) M_ROTERR = true;
  if (!M_ROTAC || clutch_engaged) M_ROTERR = false;
  if ((STOP || M_ROTERR) && MPEND1R && !MPENDOR) {
    s.SetInt(ROT_65012, kNoFunction);
    MPEND1R = false;
  }
  // Networks 10-11, label norot: acknowledge rotary axis mode. Outside the jump, so that
  // ROTMOD_Q is applied for as long as rotary axis mode is selected (4.1: after Control-Reset
  // and power-on as well); MPENDOR makes it drop in the scan after the NC asks for spindle mode
  // (network 12 resets it), before the clutch has moved.
  s.SetBool(ROTMOD_Q, config.acknowledge_before_clutch ? M_ROTAC : clutch_engaged && MPENDOR);
}

void CAxisChangeover::ToSpindleMode(PlcScan& s, bool ISP, bool clutch_released, bool STOP) {
  // Networks 12-13: changeover to spindle mode: SPMOD(ACTIVE := 1, AXIS := ISP_NR).
  M_SPLAC = s.Bool(SPMOD);
  if (M_SPLAC) {
    // vmt: a changeover to rotary axis mode that was still hunting stops its hunting first.
    if (MPEND1R && !MPENDOR) s.SetInt(ROT_65012, kNoFunction);
    MPENDOR = false;
    MPEND1R = false;
  }
  // Network 14: JMPCN nosp.
  if (M_SPLAC) {
    // vmt (4.3, and 4.4 "the controller enabling signal is activated upon the changeover to
    // main axis mode"): the spindle takes the load at once; C trails in follow-up mode, engaged
    // until the clutch opens, so that it does not hold against the spindle's hunting.
    s.SetBool(SP_C_READY, true);
    s.SetBool(ROT_C_READY, false);
    // Networks 15-16: AXD1S, hunting ON for the spindle while the clutch is not released:
    // 65012 := 2#00000001 on ISP_NR. The manual's contact MPEND1R here is read as MPEND1S, the
    // mirror of network 5: MPEND1R is always 0 in this branch, and would rewrite every scan.
    if (!ISP && !MPEND1S && !STOP && !M_SPERR) {
      s.SetInt(SP_65012, kHuntingSpindle);
      MPEND1S = true;
    }
    // Networks 17-18: trigger the valves for the changeover to spindle mode.
    s.SetBool(QROTMODE, false);
    s.SetBool(QSPMODE, true);
    // Networks 19-20: AXD0S, hunting OFF for the spindle once the clutch is released.
    if (clutch_released && !MPENDOS) {
      s.SetInt(SP_65012, kNoFunction);
      MPENDOS = true;
    }
  }
  // vmt: the wait for ISPMODE is limited as the wait for IROTMODE.
  T_SP(M_SPLAC && !clutch_released && !STOP, config.T_CLUTCH, s.now());
  if (T_SP.Q) M_SPERR = true;
  if (!M_SPLAC || clutch_released) M_SPERR = false;
  if ((STOP || M_SPERR) && MPEND1S && !MPENDOS) {
    s.SetInt(SP_65012, kNoFunction);
    MPEND1S = false;
  }
  // Network 21, label nosp: acknowledge spindle mode. As the manual has it, from the switches
  // alone: with the clutch released SPMOD_Q is applied even before the NC selects a mode, so at
  // power-on the NC takes spindle mode from the SPS (2.3 / 3.3 Power-On State); it drops when
  // the clutch leaves the released position.
  s.SetBool(SPMOD_Q, clutch_released);
}

void CAxisChangeover::WriteMessage(PlcScan& s) {
  // vmt: the messages to the NC (MSG_WR, fast-measurement 6.3), written only when they change,
  // and cleared only if the number is still ours.
  const int msg = M_ROTERR ? config.MSG_ROTERR : M_SPERR ? config.MSG_SPERR : 0;
  if (msg != msg_written) {
    if (msg != 0 || s.Int(Pxx_MSG_WR) == msg_written) s.SetInt(Pxx_MSG_WR, msg);
    msg_written = msg;
  }
}

}  // namespace vmt::control::plc
