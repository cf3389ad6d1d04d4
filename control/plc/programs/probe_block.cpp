#include "control/plc/programs/probe_block.hpp"

#include <algorithm>
#include <charconv>
#include <optional>
#include <string_view>

#include "control/gateway/signal_table.hpp"
#include "control/measure/measuring_messages.hpp"
#include "control/plc/programs/probe_drive_parameters.hpp"
#include "control/plc/programs/require_signal.hpp"

namespace vmt::control::plc {

// ---- The block -------------------------------------------------------------------------------

void QMFB1Axx::operator()(PlcTime /*now*/) {
  // The manual's block has no timer of its own: figure 7-28 has no timeout, and waiting for a
  // probe that is not ready is the NC's (it waits for the acknowledgement) and the user's
  // adaptation (networks 1, 3 and 4 time the Renishaw probe). `now` keeps the call like the
  // standard blocks'.
  if (!ENABLE) {
    Disable();
  } else if (RESET) {
    ResetSequence();
  } else {
    if (Q_FKT_Q && !Q_FKT) Q_FKT_Q = false;  // the NC has taken the acknowledgement
    if (!FEHLER) CheckParameters();
    if (!FEHLER) Initialise();
    if (!FEHLER) Measure();
  }
  koll_before_ = EV_Koll;
  mess_before_ = EV_Mess;
}

void QMFB1Axx::Disable() {
  // "0 = FB is not processed; pending errors are cleared and the FB is reset": the drives'
  // initialisation too, so the next ENABLE needs a new Q9992. The NC's events are left alone:
  // a block that is not processed writes nothing.
  ResetSequence();
  initialised_ = false;
  Init_OK_1 = Init_OK_2 = Init_OK_3 = false;
  Q_FKT_Q = false;
}

void QMFB1Axx::ResetSequence() {
  // RESET clears the errors and the measuring sequence but keeps a completed initialisation:
  // the drives stay configured, as they would on the real machine. One in progress is dropped;
  // if the NC still outputs Q9992 it starts again once RESET is released.
  FEHLER = false;
  FEHLER_NR = 0;
  Q_MTstKol = Q_MTstKmp = false;
  if (init_ != Init::kNone) {
    init_ = Init::kNone;
    initialised_ = false;
    Init_OK_1 = Init_OK_2 = Init_OK_3 = false;
  }
  issued_ = false;
  AXDaktiv = MTDaktiv = P_Dat_ovr = false;
  armed_ = acked_ = touched_ = false;
  Q_MTst1 = Q_MTst2 = Q_MTstOK = Q_MTst = false;
  QDDS_1 = QDDS_2 = QDDS_3 = false;
  if (Q_FKT_Q && !Q_FKT) Q_FKT_Q = false;
}

void QMFB1Axx::Fehler(int nr) {
  // An error stops the block where it is until RESET; the notes to FEHLER, Q_MTstKol and
  // Q_MTstKmp leave the NC stop to the user's program. A drive already prepared stays so
  // (Init_OK_n), but a failed initialisation is not acknowledged: the NC stays in SETTING.
  FEHLER = true;
  FEHLER_NR = static_cast<int16_t>(nr);
  if (init_ != Init::kNone) {
    init_ = Init::kNone;
    initialised_ = false;
  }
  issued_ = false;
  AXDaktiv = MTDaktiv = P_Dat_ovr = false;
  armed_ = acked_ = touched_ = false;
  Q_MTst1 = Q_MTst2 = Q_MTstOK = Q_MTst = false;
  QDDS_1 = QDDS_2 = QDDS_3 = false;
}

int16_t QMFB1Axx::AchsNr(int n) const {
  return n == 0 ? ACHS_NR_1 : n == 1 ? ACHS_NR_2 : ACHS_NR_3;
}

bool& QMFB1Axx::InitOk(int n) { return n == 0 ? Init_OK_1 : n == 1 ? Init_OK_2 : Init_OK_3; }

void QMFB1Axx::CheckParameters() {
  // Figure 7-28 numbers the checks 1, then "> 32" for axes 1..3, then "< 1" for axes 1..3; the
  // first that fails is reported. "< 1" cannot include 0, which the pins define as "axis does
  // not exist" (and a lathe leaves ACHS_NR_3 at 0): it catches negative numbers.
  if (ACHS_NR_1 == 0 && ACHS_NR_2 == 0 && ACHS_NR_3 == 0) return Fehler(1);
  for (int n = 0; n < 3; ++n)
    if (AchsNr(n) > gateway::kMaxAxisNumber) return Fehler(2 + n);
  for (int n = 0; n < 3; ++n)
    if (AchsNr(n) < 0) return Fehler(5 + n);
}

void QMFB1Axx::IssueRead() {
  // MTDdisabl and AXDdisabl make the block wait rather than fail: they lend the channel to
  // other SPS code (the c-axis program writes AXD idents too), after which the block goes on.
  MTDaktiv = P_Dat_ovr = false;
  if (MTDdisabl) return;
  if (MTD_RD.channels_occupied) {
    P_Dat_ovr = true;
    return;
  }
  MTDaktiv = true;
  issued_ = true;
}

void QMFB1Axx::IssueWrite() {
  AXDaktiv = false;
  if (AXDdisabl) return;
  AXDaktiv = true;
  issued_ = true;
}

void QMFB1Axx::Initialise() {
  if (init_ == Init::kNone) {
    // Q9992 (SETTING): read the page and prepare the drives, again on every SETTING.
    if (!Q_FKT || Q_FKT_Q) return;
    initialised_ = false;
    Init_OK_1 = Init_OK_2 = Init_OK_3 = false;
    init_ = Init::kReadPage;
    issued_ = false;
    return IssueRead();
  }
  if (!issued_) return init_ == Init::kReadPage ? IssueRead() : IssueWrite();

  issued_ = false;
  if (init_ == Init::kReadPage) {
    MTDaktiv = false;
    // Elements 6..10 in the order of 23..27: probe selection, probe logic, axes 1..3.
    if (MTD_RD.failed_element >= 6 && MTD_RD.failed_element <= 10)
      return Fehler(23 + MTD_RD.failed_element - 6);
    const BasisMessPage& page = MTD_RD.page;
    page_ = page;
    // Pin 4 / pin 5 of the drive are its probe inputs 1 / 2 (7.3), so PIN DDS selects which of
    // the block's probes (I_MT_OK1/I_MTast1 or I_MT_OK2/I_MTast2) the program measures with.
    probe2_ = page.PIN_DDS;
    nc_contact_ = page.Pushbutton_contact;
    requested_ = {page.Measuring_axis_1, page.Measuring_axis_2, page.Measuring_axis_3};
    if (std::none_of(requested_.begin(), requested_.end(), [](bool r) { return r; }))
      return Fehler(11);
    for (int n = 0; n < 3; ++n)
      if (requested_[n] && AchsNr(n) == 0) return Fehler(20 + n);
    init_ = Init::kWriteDrive;
    axis_ = static_cast<int>(std::find(requested_.begin(), requested_.end(), true) -
                             requested_.begin());
    return IssueWrite();
  }

  AXDaktiv = false;
  const AxdWrResult& result = AXD_WR[axis_];
  if (!result.axis_exists) return Fehler(40);
  switch (result.failed_parameter) {
    case 0:
      break;
    case 303:
      return Fehler(28 + axis_);
    case 307:
      return Fehler(31 + axis_);
    case 169:
      return Fehler(34 + axis_);
    case 170:
      // Figure 7-28 stops at 38 (axis 2); S-0-0170 of axis 3 falls to 40, "error in setting
      // the parameter values", rather than to a number the manual does not give.
      return Fehler(axis_ < 2 ? 37 + axis_ : 40);
    default:
      return Fehler(40);
  }
  InitOk(axis_) = true;
  while (++axis_ < 3)
    if (requested_[axis_]) return IssueWrite();
  init_ = Init::kNone;
  initialised_ = true;
  Q_FKT_Q = Q_FKT;  // 6.1: "from now on, measuring is possible"
}

void QMFB1Axx::Measure() {
  const bool koll_rise = EV_Koll && !koll_before_;
  const bool mess_rise = EV_Mess && !mess_before_;
  const bool mess_fall = !EV_Mess && mess_before_;
  // 12 and 13 read as the two wrong orders: the measuring path event without the collision
  // event, and the collision event arriving while the measuring path event was already set.
  if ((koll_rise || mess_rise) && !initialised_) return Fehler(10);
  if (mess_rise && !EV_Koll) return Fehler(12);
  if (koll_rise && EV_Mess && mess_before_) return Fehler(13);

  if (!initialised_) {
    armed_ = acked_ = touched_ = false;
    Q_MTst1 = Q_MTst2 = Q_MTstOK = Q_MTst = false;
    QDDS_1 = QDDS_2 = QDDS_3 = false;
    return;
  }
  // The probe is requested for the MOVE/PROBE instruction, from its collision event to the end
  // of its measuring path: the Renishaw of the example switches on with each request's edge
  // (network 3) and off by itself after a while.
  const bool requested = EV_Koll || EV_Mess;
  const bool ready = probe2_ ? I_MT_OK2 : I_MT_OK1;
  const bool contact = probe2_ ? I_MTast2 : I_MTast1;
  // A probe that is not ready says nothing with its contact: the Renishaw trips contact and
  // ready together when it switches itself off (network 3).
  const bool displaced = ready && contact != nc_contact_;
  Q_MTst1 = requested && !probe2_;
  Q_MTst2 = requested && probe2_;
  Q_MTstOK = requested && ready;
  Q_MTst = displaced;

  if (mess_rise) {  // a new measurement: its own latch, its own event 7
    armed_ = acked_ = touched_ = false;
    EV_Touch = false;
  }
  if (EV_Koll && displaced) Q_MTstKol = true;
  const bool latched = (Init_OK_1 && IDDS_1) || (Init_OK_2 && IDDS_2) || (Init_OK_3 && IDDS_3);

  if (EV_Mess && !acked_) {
    // At the setup position: enable the latch first, acknowledge a scan later with every
    // latch clear, so the drives are armed before the NC starts the measuring path.
    if (EV_Koll && Q_MTstOK && !displaced && !Q_MTstKol) {
      if (!armed_) {
        armed_ = true;
      } else if (!latched) {
        EV_Koll = false;  // 6.2 event 30: "acknowledgement from the SPS program (event 29 = 0)"
        acked_ = true;
      }
    }
  } else if (EV_Mess && !touched_ && (displaced || latched)) {
    // The drive scans its probe input every 250 us, the SPS once a scan: a contact too short
    // for the SPS input still shows as the drive's latch.
    touched_ = true;
    EV_Touch = true;
  }
  if (mess_fall) {
    if (acked_ && !touched_) Q_MTstKmp = true;
    armed_ = acked_ = touched_ = false;
  }
  QDDS_1 = armed_ && Init_OK_1;
  QDDS_2 = armed_ && Init_OK_2;
  QDDS_3 = armed_ && Init_OK_3;
}

// ---- The program -----------------------------------------------------------------------------

namespace {

/// The number after `prefix` in `pattern` ("Pxx.EV29" after "Pxx.EV" -> 29), if that is all
/// that follows.
std::optional<int> NumberAfter(std::string_view pattern, std::string_view prefix) {
  if (!pattern.starts_with(prefix) || pattern.size() == prefix.size()) return std::nullopt;
  int n = 0;
  const char* end = pattern.data() + pattern.size();
  const auto [ptr, ec] = std::from_chars(pattern.data() + prefix.size(), end, n);
  if (ec != std::errc() || ptr != end) return std::nullopt;
  return n;
}

int Lookup(const std::map<std::pair<int, int>, int>& ids, int process, int number) {
  const auto it = ids.find({process, number});
  return it == ids.end() ? -1 : it->second;
}

int AxisId(const std::array<int, 33>& ids, int axis) {
  return axis >= gateway::kMinAxisNumber && axis <= gateway::kMaxAxisNumber ? ids[axis] : -1;
}

// MTD_RD of BASISMESSPAGE elements 6..10 (3.1) through the NC's MTD access: the first element
// that cannot be read is the failed one; a page number that is not BASISMESSPAGE's fails at 6.
MtdRdResult ReadBasisMessPage(const measure::MeasuringPages& pages, int page, int process) {
  MtdRdResult r;
  if (pages.PageOf(page) != measure::Page::kBasisMessPage) {
    r.failed_element = 6;
    return r;
  }
  bool* const element[] = {&r.page.PIN_DDS, &r.page.Pushbutton_contact, &r.page.Measuring_axis_1,
                           &r.page.Measuring_axis_2, &r.page.Measuring_axis_3};
  for (int e = 6; e <= 10; ++e) {
    const measure::MtdRead read = measure::ReadMtd(
        pages,
        {static_cast<double>(page), static_cast<double>(process), {}, static_cast<double>(e)},
        process);
    if (!read.error.empty()) {
      r.failed_element = e;
      return r;
    }
    *element[e - 6] = read.value != 0;
  }
  return r;
}

}  // namespace

ProbeBlockProgram::ProbeBlockProgram(const gateway::SignalImage& image)
    : ENABLE(RequireSignal(image, "QMFB1A00.ENABLE")),
      RESET(RequireSignal(image, "QMFB1A00.RESET")),
      Q_Nummer(RequireSignal(image, "QMFB1A00.Q_Nummer")),
      Koll_EV(RequireSignal(image, "QMFB1A00.Koll_EV")),
      Mess_EV(RequireSignal(image, "QMFB1A00.Mess_EV")),
      Touch_EV(RequireSignal(image, "QMFB1A00.Touch_EV")),
      BasisPage(RequireSignal(image, "QMFB1A00.BasisPage")),
      MessProc(RequireSignal(image, "QMFB1A00.MessProc")),
      ACHS_NR{RequireSignal(image, "QMFB1A00.ACHS_NR_1"),
              RequireSignal(image, "QMFB1A00.ACHS_NR_2"),
              RequireSignal(image, "QMFB1A00.ACHS_NR_3")},
      I_MT_OK1(RequireSignal(image, "QMFB1A00.I_MT_OK1")),
      I_MTast1(RequireSignal(image, "QMFB1A00.I_MTast1")),
      I_MT_OK2(RequireSignal(image, "QMFB1A00.I_MT_OK2")),
      I_MTast2(RequireSignal(image, "QMFB1A00.I_MTast2")),
      AXDdisabl(RequireSignal(image, "QMFB1A00.AXDdisabl")),
      MTDdisabl(RequireSignal(image, "QMFB1A00.MTDdisabl")) {
  const auto pin = [&image](const char* name) { return RequireSignal(image, name); };
  IDDS = {pin("QMFB1A00.IDDS_1"), pin("QMFB1A00.IDDS_2"), pin("QMFB1A00.IDDS_3")};
  Init_OK = {pin("QMFB1A00.Init_OK_1"), pin("QMFB1A00.Init_OK_2"), pin("QMFB1A00.Init_OK_3")};
  QDDS = {pin("QMFB1A00.QDDS_1"), pin("QMFB1A00.QDDS_2"), pin("QMFB1A00.QDDS_3")};
  Q_MTst1 = pin("QMFB1A00.Q_MTst1");
  Q_MTst2 = pin("QMFB1A00.Q_MTst2");
  Q_MTstOK = pin("QMFB1A00.Q_MTstOK");
  Q_MTstKol = pin("QMFB1A00.Q_MTstKol");
  Q_MTstKmp = pin("QMFB1A00.Q_MTstKmp");
  Q_MTst = pin("QMFB1A00.Q_MTst");
  FEHLER = pin("QMFB1A00.FEHLER");
  FEHLER_NR = pin("QMFB1A00.FEHLER_NR");
  AXDaktiv = pin("QMFB1A00.AXDaktiv");
  MTDaktiv = pin("QMFB1A00.MTDaktiv");
  P_Dat_ovr = pin("QMFB1A00.P_Dat_ovr");

  probe_ready_ = image.Find("IPROBE_READY");
  probe_contact_ = image.Find("IPROBE_CONTACT");
  probe_on_ = image.Find("QPROBE_ON");
  probe2_ready_ = image.Find("IPROBE2_READY");
  probe2_contact_ = image.Find("IPROBE2_CONTACT");
  probe2_on_ = image.Find("QPROBE2_ON");

  // Events, Q functions and axes are chosen by the pins (Koll_EV, Q_Nummer, MessProc, ACHS_NR_n)
  // each scan, so every one the machine has is indexed here.
  axis_qdds_.fill(-1);
  axis_idds_.fill(-1);
  for (int id = 0; id < image.size(); ++id) {
    const gateway::Signal& s = image.table()[id];
    const std::string_view p = s.pattern;
    if (s.scope == gateway::Scope::kProcess) {
      if (const auto n = NumberAfter(p, "Pxx.EV")) {
        events_[{s.instance, *n}] = id;
      } else if (p == "PxxS.REV") {
        reverse_running_[s.instance] = id;
      } else if (p == "PxxC.REV") {
        reverse_start_[s.instance] = id;
      } else if (p == "PxxC.RESET") {
        control_reset_[s.instance] = id;
      } else if (p == "PxxS.STOP") {
        program_stopped_[s.instance] = id;
      } else if (p == "PxxC.ENABL") {
        process_enable_[s.instance] = id;
      } else if (p == "Pxx.MSG_WR") {
        message_[s.instance] = id;
      } else if (p == "Pxx.MSG_WR_N") {
        message_n_[s.instance] = id;
      } else if (p.ends_with("_Q")) {
        if (const auto q = NumberAfter(p.substr(0, p.size() - 2), "Pxx.Q"))
          q_acks_[{s.instance, *q}] = id;
      } else if (const auto q = NumberAfter(p, "Pxx.Q")) {
        q_functions_[{s.instance, *q}] = id;
      }
    } else if (s.scope == gateway::Scope::kAxis && s.instance >= gateway::kMinAxisNumber &&
               s.instance <= gateway::kMaxAxisNumber) {
      if (p == "AxxC.QDDS") axis_qdds_[s.instance] = id;
      if (p == "AxxS.IDDS") axis_idds_[s.instance] = id;
    }
  }
}

int ProbeBlockProgram::InProcess(const std::map<int, int>& ids) const {
  const auto it = ids.find(Measuring.MessProc);
  return it == ids.end() ? -1 : it->second;
}

bool ProbeBlockProgram::ReadInProcess(const PlcScan& s, const std::map<int, int>& ids) const {
  const int id = InProcess(ids);
  return id >= 0 && s.Bool(id);
}

void ProbeBlockProgram::operator()(PlcScan& s) {
  const std::array<int, 3> axes = ReadPins(s);
  CallBlock(s, axes);
  WriteQdds(s, axes);
  const bool reversing = ReadInProcess(s, reverse_running_);
  AcknowledgeQFunctions(s, reversing);
  TrackQFunctionFlags(s, reversing);
  LockProcess(s, reversing);
  WritePins(s);
}

std::array<int, 3> ProbeBlockProgram::ReadPins(PlcScan& s) {
  QMFB1Axx& m = Measuring;
  const auto int16 = [&s](int id) { return static_cast<int16_t>(s.Int(id)); };
  m.ENABLE = s.Bool(ENABLE);
  m.RESET = s.Bool(RESET);
  m.Q_Nummer = int16(Q_Nummer);
  m.Koll_EV = int16(Koll_EV);
  m.Mess_EV = int16(Mess_EV);
  m.Touch_EV = int16(Touch_EV);
  m.BasisPage = int16(BasisPage);
  m.MessProc = int16(MessProc);
  m.ACHS_NR_1 = int16(ACHS_NR[0]);
  m.ACHS_NR_2 = int16(ACHS_NR[1]);
  m.ACHS_NR_3 = int16(ACHS_NR[2]);
  // Typical application, network 2: the probe's ready and contact inputs on probe 1's pins (a
  // second probe, where the machine has one, on probe 2's).
  if (probe_ready_ >= 0) s.SetBool(I_MT_OK1, s.Bool(probe_ready_));
  if (probe_contact_ >= 0) s.SetBool(I_MTast1, s.Bool(probe_contact_));
  if (probe2_ready_ >= 0) s.SetBool(I_MT_OK2, s.Bool(probe2_ready_));
  if (probe2_contact_ >= 0) s.SetBool(I_MTast2, s.Bool(probe2_contact_));
  m.I_MT_OK1 = s.Bool(I_MT_OK1);
  m.I_MTast1 = s.Bool(I_MTast1);
  m.I_MT_OK2 = s.Bool(I_MT_OK2);
  m.I_MTast2 = s.Bool(I_MTast2);
  m.AXDdisabl = s.Bool(AXDdisabl);
  m.MTDdisabl = s.Bool(MTDdisabl);

  // The example wires A01S.IDDS to IDDS_1 for ACHS_NR_1 = 1: here the status bit of whichever
  // axis ACHS_NR_n names, and the pin shows what the block got.
  const std::array<int, 3> axes = {m.ACHS_NR_1, m.ACHS_NR_2, m.ACHS_NR_3};
  std::array<bool, 3> idds{};
  for (int n = 0; n < 3; ++n) {
    const int id = AxisId(axis_idds_, axes[n]);
    idds[n] = id >= 0 && s.Bool(id);
    s.SetBool(IDDS[n], idds[n]);
  }
  m.IDDS_1 = idds[0];
  m.IDDS_2 = idds[1];
  m.IDDS_3 = idds[2];
  return axes;
}

void ProbeBlockProgram::CallBlock(PlcScan& s, const std::array<int, 3>& axes) {
  QMFB1Axx& m = Measuring;
  // NC side. An event or Q function the machine does not have reads FALSE and is not written.
  const int q = Lookup(q_functions_, m.MessProc, m.Q_Nummer);
  const int koll = Lookup(events_, m.MessProc, m.Koll_EV);
  const int mess = Lookup(events_, m.MessProc, m.Mess_EV);
  const int touch = Lookup(events_, m.MessProc, m.Touch_EV);
  m.Q_FKT = q >= 0 && s.Bool(q);
  m.EV_Koll = koll >= 0 && s.Bool(koll);
  m.EV_Mess = mess >= 0 && s.Bool(mess);
  m.EV_Touch = touch >= 0 && s.Bool(touch);
  const bool koll_in = m.EV_Koll, touch_in = m.EV_Touch;
  // MTD_RD answers from the NC's pages where they are connected, else with basis_page. AXD_WR
  // answers what the drives said to last scan's writes where the runtime reaches them; without,
  // it stands in for drives that take any parameter of an axis the machine has.
  m.MTD_RD = measuring_pages ? ReadBasisMessPage(*measuring_pages, m.BasisPage, m.MessProc)
                             : MtdRdResult{basis_page, 0, false};
  const AxdWriter* axd_wr = s.axd_wr();
  for (int n = 0; n < 3; ++n)
    m.AXD_WR[n] = axd_wr ? axd_answers_[n] : AxdWrResult{AxisId(axis_qdds_, axes[n]) >= 0, 0};

  m(s.now());

  if (axd_wr && m.AXDaktiv)
    axd_answers_[m.axd_axis()] =
        WriteProbeParameters(*axd_wr, axes[m.axd_axis()], AxdWrProbeParameters(m.page()));

  // Events are shared with the NC program (SE/RE): written only where the block changed them.
  if (koll >= 0 && m.EV_Koll != koll_in) s.SetBool(koll, m.EV_Koll);
  if (touch >= 0 && m.EV_Touch != touch_in) s.SetBool(touch, m.EV_Touch);
  const int ack = Lookup(q_acks_, m.MessProc, m.Q_Nummer);
  if (q_ack_ >= 0 && q_ack_ != ack) s.SetBool(q_ack_, false);
  if (ack >= 0) s.SetBool(ack, m.Q_FKT_Q);
  q_ack_ = ack;
}

void ProbeBlockProgram::WriteQdds(PlcScan& s, const std::array<int, 3>& axes) {
  const QMFB1Axx& m = Measuring;
  // QDDS_n -> AxxC.QDDS of the axis ACHS_NR_n names; an axis no longer named is released.
  const std::array<bool, 3> qdds = {m.QDDS_1, m.QDDS_2, m.QDDS_3};
  std::vector<int> named;
  for (int n = 0; n < 3; ++n)
    if (AxisId(axis_qdds_, axes[n]) >= 0 &&
        std::find(named.begin(), named.end(), axes[n]) == named.end())
      named.push_back(axes[n]);
  for (int axis : qdds_axes_)
    if (std::find(named.begin(), named.end(), axis) == named.end())
      s.SetBool(axis_qdds_[axis], false);
  for (int axis : named) {
    bool on = false;
    for (int n = 0; n < 3; ++n) on = on || (axes[n] == axis && qdds[n]);
    s.SetBool(axis_qdds_[axis], on);
  }
  qdds_axes_ = std::move(named);
}

void ProbeBlockProgram::AcknowledgeQFunctions(PlcScan& s, bool reversing) {
  const QMFB1Axx& m = Measuring;
  // Typical application, networks 9 and 11 (6.1): Q9999 is acknowledged when the reverse
  // program has become active; Q9998 at once, vmt's program having no error-clear key to wait
  // for (the NC holds with OVERSIZE / UNDERSIZE and a new start continues).
  for (const int number : {measure::kQ9998, measure::kQ9999}) {
    const int qf = Lookup(q_functions_, m.MessProc, number);
    const int qa = Lookup(q_acks_, m.MessProc, number);
    if (qf < 0 || qa < 0) continue;
    s.SetBool(qa, s.Bool(qf) && (number == measure::kQ9998 || reversing));
  }
}

void ProbeBlockProgram::TrackQFunctionFlags(PlcScan& s, bool reversing) {
  const QMFB1Axx& m = Measuring;
  // Typical application, networks 5, 6, 10 and 12: the Q function the NC outputs sets the
  // program's flag (on its rising edge: the output stays until acknowledged, the fault stays
  // until cleared). Q9999's flag clears when the reverse program is started (network 10) or
  // with Control-Reset, which aborts the program that output it and withdraws the output (vmt:
  // the manual's program keeps it, leaving nothing to reverse from). Q9998's flag clears with
  // the reverse program or Control-Reset (network 12) and, vmt having no error-clear key, when
  // the program it stopped is no longer stopped (the new start that acknowledges the message).
  const int q9999 = Lookup(q_functions_, m.MessProc, measure::kQ9999);
  const int q9998 = Lookup(q_functions_, m.MessProc, measure::kQ9998);
  const bool out9999 = q9999 >= 0 && s.Bool(q9999);
  const bool out9998 = q9998 >= 0 && s.Bool(q9998);
  const bool reset = ReadInProcess(s, control_reset_) || !m.ENABLE;
  const bool stopped = ReadInProcess(s, program_stopped_);
  if (out9999 && !q9999_before_) M_Q9999 = true;
  // An output withdrawn: acknowledged (in the reverse program) or dropped by Control-Reset.
  const bool withdrawn = !out9999 && q9999_before_;
  if (reset || reversing || withdrawn || ReadInProcess(s, reverse_start_)) M_Q9999 = false;
  if (out9998 && !q9998_before_) M_Q9998 = true, q9998_stopped_ = false;
  if (M_Q9998 && stopped) q9998_stopped_ = true;
  if (reset || reversing || (q9998_stopped_ && !stopped)) M_Q9998 = false;
  q9999_before_ = out9999;
  q9998_before_ = out9998;
}

void ProbeBlockProgram::LockProcess(PlcScan& s, bool reversing) {
  const QMFB1Axx& m = Measuring;
  // Typical application, networks 7, 8, 13, 14, 18 to 20 and 24 (what reaches the NC): a probe
  // collision, an error of the block or the NC's Q9999 (fault category 1) locks the process (no
  // process enable: the NC stops at once), with message 203 / 202 (probe monitoring 1 / 2), 206
  // (errors 1..13) / 207 (14..) with the error number, or 205. Collision and error are
  // suppressed while the reverse program runs (network 7), so that it can take the stylus away;
  // they last until RESET clears the block. Q9998 (fault category 2) writes 204 and leaves the
  // process enable alone: the NC itself holds the program until the next start (vmt's reading,
  // as its program has no error-clear key that would lift a lock). One message number shows at
  // a time: the probe's own (collision, block error) before the NC's Q functions.
  const bool collision = m.Q_MTstKol && !reversing;
  const bool fault = m.FEHLER && !reversing;
  const measure::QFunctionDefinition& type1 = *measure::QFunction(measure::kQ9999);
  const measure::QFunctionDefinition& type2 = *measure::QFunction(measure::kQ9998);
  // 6.1 fault category 1: process stop and advance inhibit until the reverse program.
  const bool locked = collision || fault || (M_Q9999 && type1.fault_category == 1);
  if (const int id = InProcess(process_enable_); id >= 0) s.SetBool(id, !locked);
  const int message = collision ? (m.page().PIN_DDS ? 202 : 203)
                      : fault   ? (m.FEHLER_NR <= 13 ? 206 : 207)
                      : M_Q9999 ? type1.plc_message
                      : M_Q9998 ? type2.plc_message
                                : 0;
  if (const int id = InProcess(message_); id >= 0) s.SetInt(id, message);
  if (const int id = InProcess(message_n_); id >= 0) s.SetInt(id, collision || !fault ? 0 : m.FEHLER_NR);
}

void ProbeBlockProgram::WritePins(PlcScan& s) {
  const QMFB1Axx& m = Measuring;
  const std::array<bool, 3> qdds = {m.QDDS_1, m.QDDS_2, m.QDDS_3};
  const auto out = [&s](int pin, bool v) { s.SetBool(pin, v); };
  const std::array<bool, 3> init_ok = {m.Init_OK_1, m.Init_OK_2, m.Init_OK_3};
  for (int n = 0; n < 3; ++n) {
    out(Init_OK[n], init_ok[n]);
    out(QDDS[n], qdds[n]);
  }
  out(Q_MTst1, m.Q_MTst1);
  if (probe_on_ >= 0) s.SetBool(probe_on_, m.Q_MTst1);
  out(Q_MTst2, m.Q_MTst2);
  if (probe2_on_ >= 0) s.SetBool(probe2_on_, m.Q_MTst2);
  out(Q_MTstOK, m.Q_MTstOK);
  out(Q_MTstKol, m.Q_MTstKol);
  out(Q_MTstKmp, m.Q_MTstKmp);
  out(Q_MTst, m.Q_MTst);
  out(FEHLER, m.FEHLER);
  s.SetInt(FEHLER_NR, m.FEHLER_NR);
  out(AXDaktiv, m.AXDaktiv);
  out(MTDaktiv, m.MTDaktiv);
  out(P_Dat_ovr, m.P_Dat_ovr);
}

}  // namespace vmt::control::plc
