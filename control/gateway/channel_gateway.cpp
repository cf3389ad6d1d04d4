#include "control/gateway/channel_gateway.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "control/channel/channel.hpp"

namespace vmt::control::gateway {
namespace {

std::string Number2(int n) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "%02d", n);
  return buf;
}

}  // namespace

bool ChannelGateway::Edge::Rising(const SignalImage& image) {
  if (id < 0) return false;
  const bool now = image.Bool(id);
  const bool rising = now && !last;
  last = now;
  return rising;
}

ChannelGateway::ChannelGateway(SignalImage& image, int process,
                               const std::vector<int>& axis_numbers, int spindle_number,
                               int spindle_drive, int rotary_number)
    : image_(&image),
      spindle_drive_(spindle_drive),
      axis_monitor_(image, axis_numbers, spindle_number) {
  prefix_ = "P" + Number2(process);
  const std::string c = prefix_ + "C.", s = prefix_ + "S.";
  auto_.id = Id(c + "AUTO");
  manu_.id = Id(c + "MANU");
  mdi_.id = Id(c + "MDI");
  start_.id = Id(c + "START");
  reset_.id = Id(c + "RESET");
  rev_.id = Id(c + "REV");
  auxack_.id = Id(c + "AUXACK");
  stop_ = Id(c + "STOP");
  sbl_ = Id(c + "SBL");
  opstp_ = Id(c + "OPSTP");
  fovr_ = Id(c + "FOVR");
  if (fovr_ >= 0) last_fovr_ = image.Int(fovr_);  // only changes act (see ReadControls)
  enabl_ = Id(c + "ENABL");
  if (enabl_ >= 0) last_enabl_ = image.Bool(enabl_);
  for (int k = 0; k < 3; ++k) jogm_[k] = Id(c + "JOGM" + std::to_string(k));
  repos_ = Id(c + "REPOS");
  resta_ = Id(c + "RESTA");
  mgpos_ = Id(c + "MGPOS");
  mgneg_ = Id(c + "MGNEG");
  s_auto_ = Id(s + "AUTO");
  s_manu_ = Id(s + "MANU");
  s_mdi_ = Id(s + "MDI");
  s_run_ = Id(s + "RUN");
  s_stop_ = Id(s + "STOP");
  s_repos_ = Id(s + "REPOS");
  s_crest_ = Id(s + "CREST");
  s_rev_ = Id(s + "REV");
  s_error_ = Id(s + "ERROR");
  s_errnr_ = Id(s + "ERRNR");
  s_auxstb_ = Id(s + "AUXSTB");
  s_mfunc_ = Id(s + "MFUNC");
  s_hfunc_ = Id(s + "HFUNC");
  s_tfunc_ = Id(s + "TFUNC");
  msg_wr_ = Id(prefix_ + ".MSG_WR");
  msg_wr_n_ = Id(prefix_ + ".MSG_WR_N");
  for (int number : axis_numbers) {
    const std::string a = "A" + Number2(number);
    AxisSignals sig;
    sig.jgpos = Id(a + "C.JGPOS");
    sig.jgneg = Id(a + "C.JGNEG");
    sig.mvpos = Id(a + "S.MVPOS");
    sig.mvneg = Id(a + "S.MVNEG");
    sig.homed = Id(a + "S.HOMED");
    sig.enabl = Id(a + "C.ENABL");
    if (sig.enabl >= 0) sig.last_enabl = image.Bool(sig.enabl);  // only changes act
    sig.rf = Id(a + "S.RF");
    sig.bbdig = Id(a + "S.BBDIG");
    sig.home.id = Id(a + "C.HOME");
    if (sig.home.id >= 0) sig.home.last = image.Bool(sig.home.id);
    axes_.push_back(sig);
  }
  if (spindle_number > 0) {
    const std::string a = "A" + Number2(spindle_number) + "S.";
    const std::string ac = "A" + Number2(spindle_number) + "C.";
    const char* keys[4] = {"M3", "M4", "M5", "M19"};
    for (int k = 0; k < 4; ++k) spindle_m_[k].id = Id(ac + keys[k]);
    // One axis with rotary axis capability (section 2): its HOME is the rotary axis' key.
    if (std::find(axis_numbers.begin(), axis_numbers.end(), spindle_number) == axis_numbers.end())
      spindle_home_.id = Id(ac + "HOME");
    spindle_jgpos_ = Id(ac + "JGPOS");
    spindle_jgneg_ = Id(ac + "JGNEG");
    spindle_enabl_ = Id(ac + "ENABL");
    if (spindle_enabl_ >= 0) last_spindle_enabl_ = image.Bool(spindle_enabl_);
    spindle_rf_ = Id(a + "RF");
    spindle_bbdig_ = Id(a + "BBDIG");
    nc_nmax_ = Id(a + "NC_NMAX");
    sovr_ = Id(ac + "SOVR");
    if (sovr_ >= 0) last_sovr_ = image.Int(sovr_);
    spindle_homed_ = Id(a + "HOMED");
    n_ncmd_ = Id(a + "N_NCMD");
    n_nmin_ = Id(a + "N_NMIN");
    inpos_ = Id(a + "INPOS");
    md_mdx_ = Id(a + "MD_MDX");
    p_px_ = Id(a + "P_PX");
    load90_ = Id(a + "LOAD90");
  }
  if (spindle_number > 0 && rotary_number > 0) {
    const std::string sp = "A" + Number2(spindle_number), rot = "A" + Number2(rotary_number);
    Headstock& h = headstock_;
    h.rotmod = Id(sp + ".ROTMOD");
    h.spmod = Id(sp + ".SPMOD");
    h.rotmod_q = Id(sp + ".ROTMOD_Q");
    h.spmod_q = Id(sp + ".SPMOD_Q");
    h.spindle_ready = Id(sp + "C.READY");
    h.rotary_ready = Id(rot + "C.READY");
    for (int k = 0; k < 4; ++k) {
      h.spindle_axd[k] = Id(sp + ".AXD." + std::to_string(65012 + k));
      h.rotary_axd[k] = Id(rot + ".AXD." + std::to_string(65012 + k));
    }
  }
  {
    const std::string o = prefix_ + ".mc_cmd_bs_";
    BlockSearch& b = bs_;
    const std::pair<int*, const char*> objects[] = {
        {&b.type_w, "type_w"},
        {&b.auto_return_w, "auto_return_w"},
        {&b.no_hold_w, "no_hold_at_restart_w"},
        {&b.deviation_max_w, "deviation_max_w"},
        {&b.breakpoint_w, "breakpoint_position_w"},
        {&b.distance_w, "distance_prog_start_w"},
        {&b.covered_w, "covered_distance_w"},
        {&b.start_offset_w, "pos_start_offset_w"},
        {&b.start_name_w, "pos_start_name_w"},
        {&b.start_type_w, "pos_start_type_w"},
        {&b.start_count_w, "pos_start_count_w"},
        {&b.end_offset_w, "pos_end_offset_w"},
        {&b.end_name_w, "pos_end_name_w"},
        {&b.end_type_w, "pos_end_type_w"},
        {&b.end_count_w, "pos_end_count_w"},
        {&b.block_count_w, "intern_block_count_w"},
        {&b.block_number_w, "block_number_w"},
        {&b.pass_w, "block_number_pass_w"},
        {&b.prog_name_w, "block_nbr_prog_name_w"},
        {&b.type_r, "type_r"},
        {&b.auto_return_r, "auto_return_r"},
        {&b.no_hold_r, "no_hold_at_restart_r"},
        {&b.deviation_max_r, "deviation_max_r"},
        {&b.breakpoint_r, "breakpoint_position_r"},
        {&b.distance_r, "distance_prog_start_r"},
        {&b.covered_r, "covered_distance_r"},
        {&b.start_offset_r, "pos_start_offset_r"},
        {&b.start_name_r, "pos_start_name_r"},
        {&b.start_type_r, "pos_start_type_r"},
        {&b.start_count_r, "pos_start_count_r"},
        {&b.end_offset_r, "pos_end_offset_r"},
        {&b.end_name_r, "pos_end_name_r"},
        {&b.end_type_r, "pos_end_type_r"},
        {&b.end_count_r, "pos_end_count_r"},
        {&b.block_count_r, "intern_block_count_r"},
        {&b.block_number_r, "block_number_r"},
        {&b.pass_r, "block_number_pass_r"},
        {&b.prog_name_r, "block_nbr_prog_name_r"},
    };
    for (const auto& [id, name] : objects) *id = Id(o + name);
    b.file_offset_w = Id(prefix_ + ".mc_command_file_offset_w");
    const std::string st = prefix_ + ".bahn_state.";
    b.active = Id(st + "block_search_active_r");
    b.state = Id(st + "block_search_state_r");
    b.covered_distance = Id(st + "covered_distance_r");
    b.dist_prog_start = Id(st + "dist_prog_start");
    b.line_count = Id(st + "block_count_r");
    b.path_deviation = Id(st + "block_search_path_deviation_r");
    b.stop_conditions = Id(st + "stop_conditions_r");
    b.distance_object = Id(prefix_ + ".distance_from_program_start");
    const std::string lc = prefix_ + ".bahn_lc_control.block_search.";
    b.command = Id(lc + "command_r");
    b.plc_state = Id(lc + "state_r");
    b.enable = Id(lc + "enable_w");
    b.backward_w = Id(prefix_ + ".backward_motion_w");
    b.backward_r = Id(st + "backward_motion_r");
    b.suspend_w = Id(prefix_ + ".suspend_axis_output_w");
    b.suspended_r = Id(st + "axis_output_suspended_r");
    const std::string jop = prefix_ + ".jog_of_path.";
    b.jop_start_w = Id(jop + "start_w");
    b.jop_stop_w = Id(jop + "stop_w");
    b.jop_state_r = Id(jop + "state_r");
    b.jop_output_r = Id(jop + "axis_output_r");
  }
  // Q functions the table knows: Pxx.Qnnnn out, Pxx.Qnnnn_Q acknowledgement.
  const std::string q = prefix_ + ".Q";
  for (int id = 0; id < image.size(); ++id) {
    const std::string& name = image.table()[id].name;
    if (name.rfind(q, 0) != 0 || name.find('_') != std::string::npos) continue;
    const int ack = Id(name + "_Q");
    if (ack >= 0) q_.push_back({std::atoi(name.c_str() + q.size()), id, ack});
  }
}

bool ChannelGateway::Event(int n) const {
  const int id = image_->Find(prefix_ + ".EV" + std::to_string(n));
  if (id >= 0) return image_->Bool(id);
  auto it = hidden_events_.find(n);
  return it != hidden_events_.end() && it->second;
}

void ChannelGateway::SetEvent(int n, bool value) {
  const int id = image_->Find(prefix_ + ".EV" + std::to_string(n));
  if (id >= 0)
    image_->SetBool(id, value);
  else
    hidden_events_[n] = value;
}

void ChannelGateway::ReadControls(channel::Channel& ch) {
  SignalImage& im = *image_;
  // Mode selection: the rising edge asks for a mode; the channel refuses while a program runs,
  // and PxxS.AUTO/MANU/MDI show what it is in.
  if (auto_.Rising(im)) ch.SetMode(channel::ChannelMode::kAutomatic);
  if (manu_.Rising(im)) ch.SetMode(channel::ChannelMode::kManual);
  if (mdi_.Rising(im)) ch.SetMode(channel::ChannelMode::kMdi);
  if (reset_.Rising(im)) {
    ch.Reset();
    // Block search 7: a CNC reset clears the signal of the CNC and the PLC's.
    if (bs_.plc_state >= 0) im.SetBool(bs_.plc_state, false);
    if (bs_.command >= 0) im.SetBool(bs_.command, false);
  }
  ReadBlockSearch(ch);
  // The process enabling signal, before START and the keys: without it nothing starts.
  if (enabl_ >= 0 && im.Bool(enabl_) != last_enabl_)
    ch.SetProcessEnable(last_enabl_ = im.Bool(enabl_));
  // Feed hold as long as STOP is 1; START (rising edge) starts or continues.
  const bool stop = stop_ >= 0 && im.Bool(stop_);
  if (stop) ch.Stop();
  if (start_.Rising(im) && !stop) ch.Start();
  if (rev_.Rising(im)) ch.Reverse();
  // Repositioning manual 7.1: levels; the NC evaluates them only in the situation of 2.1.
  ch.SetReposition(repos_ >= 0 && im.Bool(repos_), resta_ >= 0 && im.Bool(resta_));
  // Levels act when they change, so that the operator's other ways in (a scene's nc: steps)
  // are not overwritten every cycle.
  if (sbl_ >= 0 && im.Bool(sbl_) != last_sbl_) ch.SetSingleBlock(last_sbl_ = im.Bool(sbl_));
  if (opstp_ >= 0 && im.Bool(opstp_) != last_opstp_)
    ch.SetOptionalStop(last_opstp_ = im.Bool(opstp_));
  if (fovr_ >= 0) {
    const int64_t percent = im.Int(fovr_);
    if (percent != last_fovr_)
      ch.SetFeedOverride(static_cast<double>(percent) / 100), last_fovr_ = percent;
  }
  if (sovr_ >= 0) {
    const int64_t percent = im.Int(sovr_);
    if (percent != last_sovr_)
      ch.SetSpindleOverride(static_cast<double>(percent) / 100), last_sovr_ = percent;
  }
  // C-axis manual 4.2: a safety limit or thermal protection switch that opens stops all first.
  axis_monitor_.ReadControls(ch);
  // C-axis manual 4.2: the axis enabling signals, before the keys they gate. Like the process
  // enabling signal they act when they change: a PLC that never writes them (a machine
  // without one, a scene's timeline) leaves the axes enabled.
  for (AxisSignals& sig : axes_)
    if (sig.enabl >= 0 && im.Bool(sig.enabl) != sig.last_enabl)
      ch.SetAxisEnable(static_cast<size_t>(&sig - axes_.data()), sig.last_enabl = !sig.last_enabl);
  if (spindle_enabl_ >= 0 && im.Bool(spindle_enabl_) != last_spindle_enabl_)
    ch.SetSpindleEnable(spindle_enabled_ = last_spindle_enabl_ = !last_spindle_enabl_);
  const int spindle_m[4] = {3, 4, 5, 19};
  for (int k = 0; k < 4; ++k)
    if (spindle_m_[k].Rising(im)) ch.ManualSpindle(spindle_m[k]);
  if (spindle_home_.Rising(im)) ch.HomeSpindle();
  if (jogm_[0] >= 0 && jogm_[1] >= 0 && jogm_[2] >= 0) {
    const int code = im.Bool(jogm_[0]) | im.Bool(jogm_[1]) << 1 | im.Bool(jogm_[2]) << 2;
    if (code != last_jogm_) ch.SetJogMode(code), last_jogm_ = code;
  }
  // The main spindle's own jog keys (C-axis manual 4.3), levels; both at once: no motion. A
  // key held while the axis enabling signal comes back acts then, as a feed axis' jog key does.
  {
    const bool pos = spindle_jgpos_ >= 0 && im.Bool(spindle_jgpos_);
    const bool neg = spindle_jgneg_ >= 0 && im.Bool(spindle_jgneg_);
    const int key = pos == neg ? 0 : pos ? 1 : -1;
    if (key != last_spindle_key_ || (spindle_enabled_ && !spindle_key_enabled_))
      ch.JogSpindle(key), last_spindle_key_ = key;
    spindle_key_enabled_ = spindle_enabled_;
  }
  for (size_t a = 0; a < axes_.size(); ++a) {
    AxisSignals& sig = axes_[a];
    if (sig.home.Rising(im)) ch.HomeAxis(a);  // 4.2: homing, as for the remaining axes
    const bool pos = sig.jgpos >= 0 && im.Bool(sig.jgpos);
    const bool neg = sig.jgneg >= 0 && im.Bool(sig.jgneg);
    const int key = pos == neg ? 0 : pos ? 1 : -1;  // both keys: no motion
    if (key != sig.last_key) ch.Jog(a, key), sig.last_key = key;
  }
  // REPOS manual 3.4: the tool storage axis' jog keys, levels; both at once: no motion.
  {
    const bool pos = mgpos_ >= 0 && im.Bool(mgpos_), neg = mgneg_ >= 0 && im.Bool(mgneg_);
    const int key = pos == neg ? 0 : pos ? 1 : -1;
    if (key != last_mg_key_) ch.JogToolStorage(key), last_mg_key_ = key;
  }
  // Acknowledgement of the auxiliary functions: AUXACK's edge, or every pending Q function
  // acknowledged on its own signal.
  bool ack = auxack_.Rising(im);
  if (!ch.aux_output().empty() && !ack) {
    bool all_q = true;
    for (const nc::AuxFunction& f : ch.aux_output()) {
      bool acked = false;
      if (f.letter == 'Q')
        for (const QSignal& qs : q_)
          if (qs.number == static_cast<int>(f.value)) acked = im.Bool(qs.ack);
      all_q = all_q && acked;
    }
    ack = all_q;
  }
  if (ack) ch.AcknowledgeAux();
  // Fast-measurement 6.3: the PLC's messages to the NC go to its message list.
  if (msg_wr_ >= 0)
    ch.SetPlcMessage({static_cast<int>(im.Int(msg_wr_)), msg_wr_n_ >= 0 ? im.Int(msg_wr_n_) : 0});

  if (ch.headstock()) {
    const Headstock& h = headstock_;
    axes::HeadstockPlc plc;
    const auto level = [&](int id, bool missing) { return id >= 0 ? im.Bool(id) : missing; };
    plc.rotmod_q = level(h.rotmod_q, false);
    plc.spmod_q = level(h.spmod_q, false);
    plc.spindle_ready = level(h.spindle_ready, true);
    plc.rotary_ready = level(h.rotary_ready, true);
    for (int k = 0; k < 4; ++k) {
      plc.spindle_axd[k] = h.spindle_axd[k] >= 0 ? im.Int(h.spindle_axd[k]) : 0;
      plc.rotary_axd[k] = h.rotary_axd[k] >= 0 ? im.Int(h.rotary_axd[k]) : 0;
    }
    ch.SetHeadstockPlc(plc);
  }
}

void ChannelGateway::WriteStatus(const channel::Channel& ch, const AmplifierTelegram& at) {
  SignalImage& im = *image_;
  auto set = [&](int id, bool v) {
    if (id >= 0) im.SetBool(id, v);
  };
  auto set_int = [&](int id, int64_t v) {
    if (id >= 0) im.SetInt(id, v);
  };
  set(s_auto_, ch.mode() == channel::ChannelMode::kAutomatic);
  set(s_manu_, ch.mode() == channel::ChannelMode::kManual);
  set(s_mdi_, ch.mode() == channel::ChannelMode::kMdi);
  set(s_run_, ch.state() == channel::ChannelState::kRunning);
  set(s_stop_, ch.state() == channel::ChannelState::kHold);
  // Repositioning manual 7.2: set each time the program is interrupted, reset when it resumes
  // or on Control-Reset; 7.3: the state before the interruption restored.
  set(s_repos_, ch.repos_allowed());
  set(s_crest_, ch.conditions_restored());
  set(s_rev_, ch.reversing());
  set(s_error_, ch.state() == channel::ChannelState::kError);
  set_int(s_errnr_, ch.error_number());
  // The strobe is for M, H and T; a Q function has its own signal and acknowledgement.
  const auto& aux = ch.aux_output();
  bool strobe = false;
  for (const nc::AuxFunction& f : aux) strobe = strobe || f.letter != 'Q';
  set(s_auxstb_, strobe);
  int64_t m = -1, h = -1, t = -1;
  for (const nc::AuxFunction& f : aux) {
    if (f.letter == 'M' && m < 0) m = static_cast<int64_t>(f.value);
    if (f.letter == 'H' && h < 0) h = static_cast<int64_t>(f.value);
    if (f.letter == 'T' && t < 0) t = static_cast<int64_t>(f.value);
  }
  set_int(s_mfunc_, m);
  set_int(s_hfunc_, h);
  set_int(s_tfunc_, t);
  for (const QSignal& qs : q_) {
    bool out = false;
    for (const nc::AuxFunction& f : aux)
      out = out || (f.letter == 'Q' && static_cast<int>(f.value) == qs.number);
    im.SetBool(qs.out, out);
  }
  for (size_t a = 0; a < axes_.size(); ++a) {
    const int motion = ch.AxisMotion(a);
    set(axes_[a].mvpos, motion > 0);
    set(axes_[a].mvneg, motion < 0);
    set(axes_[a].homed, ch.homed(a));
    // 4.2: the controller enable the NC gives the drive over SERCOS, and the drive's ready.
    const int drive = a < ch.config().axes.size() ? ch.config().axes[a].drive : -1;
    if (drive >= 0 && drive < static_cast<int>(at.feedback.size())) {
      set(axes_[a].rf, at.feedback[drive].status & drive_status::kEnabled);
      set(axes_[a].bbdig, at.feedback[drive].status & drive_status::kReady);
    }
  }
  if (const axes::HeadstockChangeover* hs = ch.headstock()) {
    const Headstock& h = headstock_;
    set(h.rotmod, hs->rotmod());
    set(h.spmod, hs->spmod());
    // 65012's acknowledgement bits (8..10) are the drive's answer to the PLC's request bits.
    const auto answer = [&](int id, int64_t word) {
      if (id < 0) return;
      const int64_t v = (im.Int(id) & ~int64_t{0xff00}) | (word & 0xff00);
      if (v != im.Int(id)) im.SetInt(id, v);
    };
    answer(h.spindle_axd[0], hs->SpindleFunctionWord());
    if (hs->config().separate_servo()) answer(h.rotary_axd[0], hs->RotaryFunctionWord());
  }
  WriteBlockSearch(ch);
  // A spindle that is also a channel axis (C-axis manual section 2) has one reference.
  set(spindle_homed_, ch.spindle_homed());
  if (spindle_drive_ >= 0 && spindle_drive_ < static_cast<int>(at.feedback.size())) {
    const uint32_t st = at.feedback[spindle_drive_].status;
    set(n_ncmd_, st & drive_status::kAtSpeed);
    set(n_nmin_, st & drive_status::kStandstill);
    set(inpos_, st & drive_status::kInPosition);
    set(spindle_rf_, st & drive_status::kEnabled);
    set(spindle_bbdig_, st & drive_status::kReady);
    // 4.2's SERCOS threshold status of the spindle drive (|Md| >= Mdx, |P| >= Px, 90 % load).
    set(md_mdx_, st & drive_status::kTorqueThreshold);
    set(p_px_, st & drive_status::kPowerThreshold);
    set(load90_, st & drive_status::kLoad90);
  }
  set(nc_nmax_, ch.SpindleAtSpeedLimit());
  axis_monitor_.WriteStatus(ch, at);
}

double ChannelGateway::Number(int id) const {
  if (id < 0) return 0;
  switch (image_->table()[id].type) {
    case SignalType::kBool:
      return image_->Bool(id) ? 1 : 0;
    case SignalType::kReal:
    case SignalType::kLreal:
      return image_->Real(id);
    case SignalType::kString:
      return 0;
    default:
      return static_cast<double>(image_->Int(id));
  }
}

void ChannelGateway::SetNumber(int id, double value) {
  if (id < 0) return;
  switch (image_->table()[id].type) {
    case SignalType::kBool:
      image_->SetBool(id, value != 0);
      return;
    case SignalType::kReal:
    case SignalType::kLreal:
      image_->SetReal(id, value);
      return;
    case SignalType::kString:
      return;
    default:
      image_->SetInt(id, static_cast<int64_t>(std::llround(value)));
  }
}

void ChannelGateway::ReadBlockSearch(channel::Channel& ch) {
  const BlockSearch& b = bs_;
  if (b.type_w < 0) return;  // a machine without the block search objects
  auto text = [&](int id) { return id >= 0 ? image_->String(id) : std::string(); };
  auto integer = [&](int id, int64_t missing) {
    return id >= 0 ? static_cast<int64_t>(std::llround(Number(id))) : missing;
  };
  channel::BlockSearchParameters p;
  p.type = static_cast<channel::BlockSearchType>(integer(b.type_w, 0));
  p.auto_return = Number(b.auto_return_w) != 0;
  p.no_hold_at_restart = Number(b.no_hold_w) != 0;
  p.deviation_max = integer(b.deviation_max_w, 0);
  p.file_offset = integer(b.file_offset_w, 0);
  p.breakpoint_position = Number(b.breakpoint_w);
  p.distance_prog_start = Number(b.distance_w);
  p.covered_distance = Number(b.covered_w);
  // 5.2: the start offset 0 is the file's first line like any other; the end position is
  // optional, and an end at offset 0 without a file name is taken as none given (it would end
  // the program before it began).
  p.start = {integer(b.start_offset_w, -1), text(b.start_name_w),
             static_cast<int>(integer(b.start_type_w, 0)),
             static_cast<int>(std::max<int64_t>(1, integer(b.start_count_w, 1)))};
  p.end = {integer(b.end_offset_w, -1), text(b.end_name_w),
           static_cast<int>(integer(b.end_type_w, 0)),
           static_cast<int>(std::max<int64_t>(1, integer(b.end_count_w, 1)))};
  if (p.end.offset == 0 && p.end.name.empty()) p.end.offset = -1;
  p.intern_block_count = static_cast<uint32_t>(integer(b.block_count_w, 0));
  p.block_number = static_cast<uint32_t>(integer(b.block_number_w, 0));
  p.block_number_pass = static_cast<uint32_t>(integer(b.pass_w, 1));
  p.block_nbr_prog_name = text(b.prog_name_w);
  ch.SetBlockSearch(p);
  ch.SetBlockSearchPlc(Number(b.enable) != 0, Number(b.plc_state) != 0);
  ch.SetBackward(Number(b.backward_w) != 0);
  ch.SetSuspendOutput(Number(b.suspend_w) != 0);
}

void ChannelGateway::ReadJogOfPath(channel::Channel& jog_of_path) {
  BlockSearch& b = bs_;
  const bool start = Number(b.jop_start_w) != 0, stop = Number(b.jop_stop_w) != 0;
  if (stop && !b.jop_stop) jog_of_path.Stop();
  if (start && !b.jop_start) jog_of_path.Start();
  b.jop_start = start;
  b.jop_stop = stop;
}

void ChannelGateway::WriteJogOfPath(const channel::Channel& jog_of_path) {
  SetNumber(bs_.jop_state_r, static_cast<double>(jog_of_path.state()));
  SetNumber(bs_.jop_output_r, !jog_of_path.output_suspended());
}

void ChannelGateway::WriteBlockSearch(const channel::Channel& ch) {
  const BlockSearch& b = bs_;
  if (b.state < 0 && b.type_r < 0) return;
  // The read-backs: what the running program was started with (5).
  const channel::BlockSearchParameters& p = ch.block_search_parameters();
  SetNumber(b.type_r, static_cast<double>(p.type));
  SetNumber(b.auto_return_r, p.auto_return);
  SetNumber(b.no_hold_r, p.no_hold_at_restart);
  SetNumber(b.deviation_max_r, static_cast<double>(p.deviation_max));
  SetNumber(b.breakpoint_r, p.breakpoint_position);
  SetNumber(b.distance_r, p.distance_prog_start);
  SetNumber(b.covered_r, p.covered_distance);
  SetNumber(b.start_offset_r, static_cast<double>(p.start.offset));
  SetNumber(b.start_type_r, p.start.path);
  SetNumber(b.start_count_r, p.start.count);
  SetNumber(b.end_offset_r, static_cast<double>(p.end.offset));
  SetNumber(b.end_type_r, p.end.path);
  SetNumber(b.end_count_r, p.end.count);
  SetNumber(b.block_count_r, p.intern_block_count);
  SetNumber(b.block_number_r, p.block_number);
  SetNumber(b.pass_r, p.block_number_pass);
  if (b.start_name_r >= 0) image_->SetString(b.start_name_r, p.start.name);
  if (b.end_name_r >= 0) image_->SetString(b.end_name_r, p.end.name);
  if (b.prog_name_r >= 0) image_->SetString(b.prog_name_r, p.block_nbr_prog_name);
  // 5.5, 5.6: the status, distances in 0.1 um (increments).
  const channel::BlockSearchStatus& st = ch.block_search();
  SetNumber(b.active, st.active());
  SetNumber(b.state, static_cast<double>(st.state));
  SetNumber(b.covered_distance, std::floor(st.covered_distance));
  SetNumber(b.dist_prog_start, st.dist_prog_start * 1e4);
  SetNumber(b.distance_object, st.dist_prog_start * 1e4);
  SetNumber(b.line_count, st.block_count);
  SetNumber(b.path_deviation, std::min(std::round(st.path_deviation * 1e4), 2147483647.0));
  SetNumber(b.stop_conditions, static_cast<int32_t>(st.stop_conditions));
  SetNumber(b.command, st.command);
  SetNumber(b.backward_r, ch.travelling_back());
  SetNumber(b.suspended_r, ch.output_suspended());
}

}  // namespace vmt::control::gateway
