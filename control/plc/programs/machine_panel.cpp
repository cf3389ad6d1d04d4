#include "control/plc/programs/machine_panel.hpp"

#include <string>

#include "control/plc/programs/require_signal.hpp"

namespace vmt::control::plc {

MachinePanel::MachinePanel(const gateway::SignalImage& image, bool nc_turret_controlled)
    : C_AUTO(RequireSignal(image, "P00C.AUTO")),
      C_MANU(RequireSignal(image, "P00C.MANU")),
      C_START(RequireSignal(image, "P00C.START")),
      C_STOP(RequireSignal(image, "P00C.STOP")),
      C_RESET(RequireSignal(image, "P00C.RESET")),
      C_SBL(RequireSignal(image, "P00C.SBL")),
      C_AUXACK(RequireSignal(image, "P00C.AUXACK")),
      S_RUN(RequireSignal(image, "P00S.RUN")),
      S_AUXSTB(RequireSignal(image, "P00S.AUXSTB")),
      S_MFUNC(RequireSignal(image, "P00S.MFUNC")),
      mAUTO(RequireSignal(image, "mAUTO")),
      mMANU(RequireSignal(image, "mMANU")),
      mSTART(RequireSignal(image, "mSTART")),
      mSTOP(RequireSignal(image, "mSTOP")),
      mRESET(RequireSignal(image, "mRESET")),
      mSBL(RequireSignal(image, "mSBL")),
      mCOOLANT(RequireSignal(image, "mCOOLANT")),
      mDOOR(RequireSignal(image, "mDOOR")),
      mTAILSTOCK(RequireSignal(image, "mTAILSTOCK")),
      QDOOR_OPEN(RequireSignal(image, "QDOOR_OPEN")),
      IDOOR_CLOSED(RequireSignal(image, "IDOOR_CLOSED")),
      QTAILSTOCK(RequireSignal(image, "QTAILSTOCK")),
      QCOOLANT(RequireSignal(image, "QCOOLANT")),
      ICOOLANT_PRESSURE(RequireSignal(image, "ICOOLANT_PRESSURE")) {
  // Every jog key mJGPOS_<axis> / mJGNEG_<axis> goes to that axis' JGPOS / JGNEG; every spindle
  // reports its standstill.
  for (int id = 0; id < image.size(); ++id) {
    const gateway::Signal& s = image.table()[id];
    if (s.pattern == "AxxS.N_NMIN") standstill.push_back(id);
    if (s.pattern == "AxxC.SOVR")
      if (const int sel = image.Find("mSOVR_" + s.instance_name); sel >= 0)
        overrides.push_back({sel, id});
    for (const char* dir : {"JGPOS", "JGNEG"}) {
      if (s.pattern != std::string("AxxC.") + dir) continue;
      const int key = image.Find("m" + std::string(dir) + "_" + s.instance_name);
      if (key >= 0) jog.push_back({key, id});
    }
  }
  for (int bit = 0; bit < 3; ++bit) {
    const int key = image.Find("mJOGM" + std::to_string(bit));
    if (key < 0) continue;
    JogModeBit b;
    b.key = key;
    b.signal = RequireSignal(image, "P00C.JOGM" + std::to_string(bit));
    jog_mode.push_back(b);
  }
  if (const int sel = image.Find("mFOVR"); sel >= 0)
    overrides.push_back({sel, RequireSignal(image, "P00C.FOVR")});
  if (image.Find("mREPOS") >= 0) repos.emplace(image);
  if (nc_turret_controlled) nc_turret.emplace(image);
  // A headstock whose spindle has a rotary axis mode through clutch K.
  bool rotmod = false;
  for (const gateway::Signal& s : image.table()) rotmod = rotmod || s.pattern == "Axx.ROTMOD";
  if (rotmod && image.Find("QROTMODE") >= 0) changeover.emplace(image);
}

void MachinePanel::operator()(PlcScan& s) {
  const bool running = s.Bool(S_RUN);
  bool spindles_stopped = true;
  for (int id : standstill) spindles_stopped = spindles_stopped && s.Bool(id);
  const bool door_closed = s.Bool(IDOOR_CLOSED);

  // Door: a key toggles the request; it opens only at rest and closes at any time.
  door_key(s.Bool(mDOOR));
  if (door_key.Q) door_open = door_open ? false : !running && spindles_stopped;
  s.SetBool(QDOOR_OPEN, door_open);

  // Mode, reset, single block: the NC acts on the signals' edges and levels.
  s.SetBool(C_AUTO, s.Bool(mAUTO));
  s.SetBool(C_MANU, s.Bool(mMANU));
  s.SetBool(C_RESET, s.Bool(mRESET));
  sbl_key(s.Bool(mSBL));
  if (sbl_key.Q) single_block = !single_block;
  s.SetBool(C_SBL, single_block);

  // Feed hold: the STOP key holds until START; an open door holds and refuses START.
  stop_key(s.Bool(mSTOP));
  start_key(s.Bool(mSTART));
  if (stop_key.Q) feed_hold = true;
  if (start_key.Q && door_closed) feed_hold = false;
  s.SetBool(C_STOP, feed_hold || !door_closed);
  s.SetBool(C_START, s.Bool(mSTART) && !feed_hold && door_closed);

  for (const JogKey& j : jog) s.SetBool(j.signal, s.Bool(j.key) && door_closed);
  // Jog mode: each key toggles its bit of the code.
  for (JogModeBit& b : jog_mode) {
    b.press(s.Bool(b.key));
    if (b.press.Q) b.on = !b.on;
    s.SetBool(b.signal, b.on);
  }

  for (const OverrideSwitch& o : overrides) s.SetInt(o.signal, s.Int(o.selector));

  // Tailstock quill: toggled while the program is not running.
  quill_key(s.Bool(mTAILSTOCK));
  if (quill_key.Q && !running) quill = !quill;
  s.SetBool(QTAILSTOCK, quill);

  // Coolant: its key toggles it; M08 / M09 switch it from the program.
  coolant_key(s.Bool(mCOOLANT));
  if (coolant_key.Q) coolant = !coolant;
  const bool strobe = s.Bool(S_AUXSTB);
  const int64_t m = strobe ? s.Int(S_MFUNC) : -1;
  if (m == 8) coolant = true;
  if (m == 9) coolant = false;
  s.SetBool(QCOOLANT, coolant);

  // Acknowledge the auxiliary functions as a pulse, so that the next block's functions get an
  // edge of their own; M08 waits for the coolant pressure.
  const bool done = m != 8 || s.Bool(ICOOLANT_PRESSURE);
  const bool ack = strobe && done && !aux_acked;
  s.SetBool(C_AUXACK, ack);
  aux_acked = ack;

  if (repos) (*repos)(s);
  if (changeover) (*changeover)(s);
  if (nc_turret) (*nc_turret)(s, door_closed);
}

}  // namespace vmt::control::plc
