#include "control/gateway/channel_gateway.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <span>

#include "control/channel/channel.hpp"

namespace vmt::control::gateway {
bool ChannelGateway::Edge::Rising(const SignalImage& image) {
  if (id < 0) return false;
  const bool now = image.Bool(id);
  const bool rising = now && !last;
  last = now;
  return rising;
}

void ChannelGateway::Bind(int number,
                          std::initializer_list<std::pair<std::string_view, int*>> table) {
  for (const auto& [pattern, id] : table) {
    *id = image_->Find(InstanceName(pattern, number));
    bindings_.push_back({std::string(pattern), number, *id});
  }
}

void ChannelGateway::BindProcess(int process) {
  Bind(process,
       {
           // Operator panel and process signals (repositioning 7, c-axis 2.3 and 4.2, vmt's panel).
           {"PxxC.AUTO", &auto_.id},     {"PxxC.MANU", &manu_.id},     {"PxxC.MDI", &mdi_.id},
           {"PxxC.START", &start_.id},   {"PxxC.RESET", &reset_.id},   {"PxxC.REV", &rev_.id},
           {"PxxC.AUXACK", &auxack_.id}, {"PxxC.STOP", &stop_},        {"PxxC.SBL", &sbl_},
           {"PxxC.OPSTP", &opstp_},      {"PxxC.FOVR", &fovr_},        {"PxxC.ENABL", &enabl_},
           {"PxxC.JOGM0", &jogm_[0]},    {"PxxC.JOGM1", &jogm_[1]},    {"PxxC.JOGM2", &jogm_[2]},
           {"PxxC.REPOS", &repos_},      {"PxxC.RESTA", &resta_},      {"PxxC.MGPOS", &mgpos_},
           {"PxxC.MGNEG", &mgneg_},      {"PxxS.AUTO", &s_auto_},      {"PxxS.MANU", &s_manu_},
           {"PxxS.MDI", &s_mdi_},        {"PxxS.RUN", &s_run_},        {"PxxS.STOP", &s_stop_},
           {"PxxS.REPOS", &s_repos_},    {"PxxS.CREST", &s_crest_},    {"PxxS.REV", &s_rev_},
           {"PxxS.ERROR", &s_error_},    {"PxxS.ERRNR", &s_errnr_},    {"PxxS.AUXSTB", &s_auxstb_},
           {"PxxS.MFUNC", &s_mfunc_},    {"PxxS.HFUNC", &s_hfunc_},    {"PxxS.TFUNC", &s_tfunc_},
           {"Pxx.MSG_WR", &msg_wr_},     {"Pxx.MSG_WR_N", &msg_wr_n_},
       });
}

void ChannelGateway::BindBlockSearch(int process) {
  Bind(process,
       {
           // Block search of the ISG kernel (block search 5, 7): the CNC objects, the HLI status,
           // the on/off handshake, and vmt's objects of backward travel and JogOfPath.
           {"Pxx.mc_cmd_bs_type_w", &bs_.type_w},
           {"Pxx.mc_cmd_bs_auto_return_w", &bs_.auto_return_w},
           {"Pxx.mc_cmd_bs_no_hold_at_restart_w", &bs_.no_hold_w},
           {"Pxx.mc_cmd_bs_deviation_max_w", &bs_.deviation_max_w},
           {"Pxx.mc_cmd_bs_breakpoint_position_w", &bs_.breakpoint_w},
           {"Pxx.mc_cmd_bs_distance_prog_start_w", &bs_.distance_w},
           {"Pxx.mc_cmd_bs_covered_distance_w", &bs_.covered_w},
           {"Pxx.mc_cmd_bs_pos_start_offset_w", &bs_.start_offset_w},
           {"Pxx.mc_cmd_bs_pos_start_name_w", &bs_.start_name_w},
           {"Pxx.mc_cmd_bs_pos_start_type_w", &bs_.start_type_w},
           {"Pxx.mc_cmd_bs_pos_start_count_w", &bs_.start_count_w},
           {"Pxx.mc_cmd_bs_pos_end_offset_w", &bs_.end_offset_w},
           {"Pxx.mc_cmd_bs_pos_end_name_w", &bs_.end_name_w},
           {"Pxx.mc_cmd_bs_pos_end_type_w", &bs_.end_type_w},
           {"Pxx.mc_cmd_bs_pos_end_count_w", &bs_.end_count_w},
           {"Pxx.mc_cmd_bs_intern_block_count_w", &bs_.block_count_w},
           {"Pxx.mc_cmd_bs_block_number_w", &bs_.block_number_w},
           {"Pxx.mc_cmd_bs_block_number_pass_w", &bs_.pass_w},
           {"Pxx.mc_cmd_bs_block_nbr_prog_name_w", &bs_.prog_name_w},
           {"Pxx.mc_cmd_bs_type_r", &bs_.type_r},
           {"Pxx.mc_cmd_bs_auto_return_r", &bs_.auto_return_r},
           {"Pxx.mc_cmd_bs_no_hold_at_restart_r", &bs_.no_hold_r},
           {"Pxx.mc_cmd_bs_deviation_max_r", &bs_.deviation_max_r},
           {"Pxx.mc_cmd_bs_breakpoint_position_r", &bs_.breakpoint_r},
           {"Pxx.mc_cmd_bs_distance_prog_start_r", &bs_.distance_r},
           {"Pxx.mc_cmd_bs_covered_distance_r", &bs_.covered_r},
           {"Pxx.mc_cmd_bs_pos_start_offset_r", &bs_.start_offset_r},
           {"Pxx.mc_cmd_bs_pos_start_name_r", &bs_.start_name_r},
           {"Pxx.mc_cmd_bs_pos_start_type_r", &bs_.start_type_r},
           {"Pxx.mc_cmd_bs_pos_start_count_r", &bs_.start_count_r},
           {"Pxx.mc_cmd_bs_pos_end_offset_r", &bs_.end_offset_r},
           {"Pxx.mc_cmd_bs_pos_end_name_r", &bs_.end_name_r},
           {"Pxx.mc_cmd_bs_pos_end_type_r", &bs_.end_type_r},
           {"Pxx.mc_cmd_bs_pos_end_count_r", &bs_.end_count_r},
           {"Pxx.mc_cmd_bs_intern_block_count_r", &bs_.block_count_r},
           {"Pxx.mc_cmd_bs_block_number_r", &bs_.block_number_r},
           {"Pxx.mc_cmd_bs_block_number_pass_r", &bs_.pass_r},
           {"Pxx.mc_cmd_bs_block_nbr_prog_name_r", &bs_.prog_name_r},
           {"Pxx.mc_command_file_offset_w", &bs_.file_offset_w},
           {"Pxx.bahn_state.block_search_active_r", &bs_.active},
           {"Pxx.bahn_state.block_search_state_r", &bs_.state},
           {"Pxx.bahn_state.covered_distance_r", &bs_.covered_distance},
           {"Pxx.bahn_state.dist_prog_start", &bs_.dist_prog_start},
           {"Pxx.bahn_state.block_count_r", &bs_.line_count},
           {"Pxx.bahn_state.block_search_path_deviation_r", &bs_.path_deviation},
           {"Pxx.bahn_state.stop_conditions_r", &bs_.stop_conditions},
           {"Pxx.distance_from_program_start", &bs_.distance_object},
           {"Pxx.bahn_lc_control.block_search.command_r", &bs_.command},
           {"Pxx.bahn_lc_control.block_search.state_r", &bs_.plc_state},
           {"Pxx.bahn_lc_control.block_search.enable_w", &bs_.enable},
           {"Pxx.backward_motion_w", &bs_.backward_w},
           {"Pxx.bahn_state.backward_motion_r", &bs_.backward_r},
           {"Pxx.suspend_axis_output_w", &bs_.suspend_w},
           {"Pxx.bahn_state.axis_output_suspended_r", &bs_.suspended_r},
           {"Pxx.jog_of_path.start_w", &bs_.jop_start_w},
           {"Pxx.jog_of_path.stop_w", &bs_.jop_stop_w},
           {"Pxx.jog_of_path.state_r", &bs_.jop_state_r},
           {"Pxx.jog_of_path.axis_output_r", &bs_.jop_output_r},
       });
}

void ChannelGateway::BindAxes(const std::vector<int>& axis_numbers) {
  axes_.resize(axis_numbers.size());
  for (size_t k = 0; k < axis_numbers.size(); ++k) {
    AxisSignals& sig = axes_[k];
    Bind(axis_numbers[k], {
                              {"AxxC.JGPOS", &sig.jgpos},
                              {"AxxC.JGNEG", &sig.jgneg},
                              {"AxxS.MVPOS", &sig.mvpos},
                              {"AxxS.MVNEG", &sig.mvneg},
                              {"AxxS.HOMED", &sig.homed},
                              {"AxxC.ENABL", &sig.enabl},
                              {"AxxS.RF", &sig.rf},
                              {"AxxS.BBDIG", &sig.bbdig},
                              {"AxxC.HOME", &sig.home.id},
                          });
    if (sig.enabl >= 0) sig.last_enabl = image_->Bool(sig.enabl);
    if (sig.home.id >= 0) sig.home.last = image_->Bool(sig.home.id);
  }
}

void ChannelGateway::BindSpindle(int spindle_number, const std::vector<int>& axis_numbers) {
  Bind(spindle_number, {
                           {"AxxC.M3", &spindle_m_[0].id},
                           {"AxxC.M4", &spindle_m_[1].id},
                           {"AxxC.M5", &spindle_m_[2].id},
                           {"AxxC.M19", &spindle_m_[3].id},
                           {"AxxC.JGPOS", &spindle_jgpos_},
                           {"AxxC.JGNEG", &spindle_jgneg_},
                           {"AxxC.ENABL", &spindle_enabl_},
                           {"AxxC.SOVR", &sovr_},
                           {"AxxS.RF", &spindle_rf_},
                           {"AxxS.BBDIG", &spindle_bbdig_},
                           {"AxxS.NC_NMAX", &nc_nmax_},
                           {"AxxS.HOMED", &spindle_homed_},
                           {"AxxS.N_NCMD", &n_ncmd_},
                           {"AxxS.N_NMIN", &n_nmin_},
                           {"AxxS.INPOS", &inpos_},
                           {"AxxS.MD_MDX", &md_mdx_},
                           {"AxxS.P_PX", &p_px_},
                           {"AxxS.LOAD90", &load90_},
                       });
  // One axis with rotary axis capability (c-axis 2): its HOME is the rotary axis' key.
  if (std::find(axis_numbers.begin(), axis_numbers.end(), spindle_number) == axis_numbers.end())
    Bind(spindle_number, {{"AxxC.HOME", &spindle_home_.id}});
  if (spindle_enabl_ >= 0) last_spindle_enabl_ = image_->Bool(spindle_enabl_);
  if (sovr_ >= 0) last_sovr_ = image_->Int(sovr_);
}

void ChannelGateway::BindHeadstock(int spindle_number, int rotary_number) {
  Headstock& h = headstock_;
  Bind(spindle_number, {
                           {"Axx.ROTMOD", &h.rotmod},
                           {"Axx.SPMOD", &h.spmod},
                           {"Axx.ROTMOD_Q", &h.rotmod_q},
                           {"Axx.SPMOD_Q", &h.spmod_q},
                           {"AxxC.READY", &h.spindle_ready},
                           {"Axx.AXD.65012", &h.spindle_axd[0]},
                           {"Axx.AXD.65013", &h.spindle_axd[1]},
                           {"Axx.AXD.65014", &h.spindle_axd[2]},
                           {"Axx.AXD.65015", &h.spindle_axd[3]},
                       });
  Bind(rotary_number, {
                          {"AxxC.READY", &h.rotary_ready},
                          {"Axx.AXD.65012", &h.rotary_axd[0]},
                          {"Axx.AXD.65013", &h.rotary_axd[1]},
                          {"Axx.AXD.65014", &h.rotary_axd[2]},
                          {"Axx.AXD.65015", &h.rotary_axd[3]},
                      });
}

void ChannelGateway::FindQFunctions() {
  // Q functions the table knows: Pxx.Qnnnn out, Pxx.Qnnnn_Q acknowledgement.
  const std::string q = prefix_ + ".Q";
  for (int id = 0; id < image_->size(); ++id) {
    const std::string& name = image_->table()[id].name;
    if (name.rfind(q, 0) != 0 || name.find('_') != std::string::npos) continue;
    const int ack = Id(name + "_Q");
    if (ack >= 0) q_.push_back({std::atoi(name.c_str() + q.size()), id, ack});
  }
}

ChannelGateway::ChannelGateway(SignalImage& image, int process,
                               const std::vector<int>& axis_numbers, int spindle_number,
                               int spindle_drive, int rotary_number)
    : image_(&image),
      spindle_drive_(spindle_drive),
      axis_monitor_(image, axis_numbers, spindle_number) {
  prefix_ = InstanceName("Pxx", process);
  BindProcess(process);
  BindBlockSearch(process);
  // Only changes of these levels act (ReadControls): the preset is the last value seen.
  if (fovr_ >= 0) last_fovr_ = image.Int(fovr_);
  if (enabl_ >= 0) last_enabl_ = image.Bool(enabl_);
  BindAxes(axis_numbers);
  if (spindle_number > 0) BindSpindle(spindle_number, axis_numbers);
  if (spindle_number > 0 && rotary_number > 0) BindHeadstock(spindle_number, rotary_number);
  FindQFunctions();
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
  ReadProcessControls(ch);
  // C-axis manual 4.2: a safety limit or thermal protection switch that opens stops all first.
  axis_monitor_.ReadControls(ch);
  ReadEnablesAndKeys(ch);
  ReadAuxAcknowledge(ch);
  // Fast-measurement 6.3: the PLC's messages to the NC go to its message list.
  if (msg_wr_ >= 0)
    ch.SetPlcMessage(
        {static_cast<int>(image_->Int(msg_wr_)), msg_wr_n_ >= 0 ? image_->Int(msg_wr_n_) : 0});
  if (ch.headstock()) ReadHeadstock(ch);
}

void ChannelGateway::ReadProcessControls(channel::Channel& ch) {
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
}

void ChannelGateway::ReadEnablesAndKeys(channel::Channel& ch) {
  SignalImage& im = *image_;
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
}

void ChannelGateway::ReadAuxAcknowledge(channel::Channel& ch) {
  const SignalImage& im = *image_;
  // Acknowledgement of the auxiliary functions: AUXACK's edge while the strobe is out, or every
  // pending Q function acknowledged on its own signal.
  bool ack = auxack_.Rising(im) && aux_strobe_;
  if (ack) aux_strobe_ = false, aux_low_cycles_ = 0;
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
}

void ChannelGateway::ReadHeadstock(channel::Channel& ch) {
  const SignalImage& im = *image_;
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
  // The strobe is for M, H and T; a Q function has its own signal and acknowledgement. It rises
  // for the next block's functions once the last handshake is over: AUXACK low, and the strobe
  // low for a whole PLC scan.
  const auto& aux = ch.aux_output();
  bool pending = false;
  for (const nc::AuxFunction& f : aux) pending = pending || f.letter != 'Q';
  if (!pending && aux_strobe_) aux_strobe_ = false, aux_low_cycles_ = 0;  // Control-Reset
  const bool ack_low = auxack_.id < 0 || !im.Bool(auxack_.id);
  if (pending && !aux_strobe_ && ack_low && aux_low_cycles_ >= plc_scan_nc_cycles_)
    aux_strobe_ = true;
  if (!aux_strobe_ && aux_low_cycles_ < (1 << 20)) ++aux_low_cycles_;
  set(s_auxstb_, aux_strobe_);
  int64_t m = -1, h = -1, t = -1;
  for (const nc::AuxFunction& f : aux) {
    if (!aux_strobe_) break;  // the functions show with their strobe
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

// Whether a parameter signal was written since the last read: their cells, and the texts (a
// STRING's cell is its slot). A PLC writes the parameters once per search; building them reads
// twenty signals and copies three texts, which every NC cycle was a few per cent of a run.
bool ChannelGateway::BlockSearchWritten() {
  const BlockSearch& b = bs_;
  const std::array<int, 20> ids = {
      b.type_w,       b.auto_return_w, b.no_hold_w,      b.deviation_max_w, b.file_offset_w,
      b.breakpoint_w, b.distance_w,    b.covered_w,      b.start_offset_w,  b.start_name_w,
      b.start_type_w, b.start_count_w, b.end_offset_w,   b.end_name_w,      b.end_type_w,
      b.end_count_w,  b.block_count_w, b.block_number_w, b.pass_w,          b.prog_name_w};
  const std::span<const int64_t> cells = image_->cells();
  bool written = bs_cells_.empty();
  bs_cells_.resize(ids.size());
  for (size_t k = 0; k < ids.size(); ++k) {
    const int64_t cell = ids[k] >= 0 ? cells[ids[k]] : 0;
    written = written || cell != bs_cells_[k];
    bs_cells_[k] = cell;
  }
  const auto same_text = [&](int id, const std::string& last) {
    return id < 0 || image_->String(id) == last;
  };
  return written || !same_text(b.start_name_w, bs_parameters_.start.name) ||
         !same_text(b.end_name_w, bs_parameters_.end.name) ||
         !same_text(b.prog_name_w, bs_parameters_.block_nbr_prog_name);
}

void ChannelGateway::ReadBlockSearch(channel::Channel& ch) {
  const BlockSearch& b = bs_;
  if (b.type_w < 0) return;  // a machine without the block search objects
  if (BlockSearchWritten()) ReadBlockSearchParameters(ch);
  ch.SetBlockSearchPlc(Number(b.enable) != 0, Number(b.plc_state) != 0);
  ch.SetBackward(Number(b.backward_w) != 0);
  ch.SetSuspendOutput(Number(b.suspend_w) != 0);
}

void ChannelGateway::ReadBlockSearchParameters(channel::Channel& ch) {
  const BlockSearch& b = bs_;
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
  // Handed over as they change: the channel checks them on each hand-over.
  if (p != bs_parameters_) ch.SetBlockSearch(bs_parameters_ = p);
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
  if (const channel::BlockSearchParameters& p = ch.block_search_parameters();
      !bs_read_back_ || p != *bs_read_back_) {
    WriteBlockSearchReadBacks(p);
    bs_read_back_ = p;
  }
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

void ChannelGateway::WriteBlockSearchReadBacks(const channel::BlockSearchParameters& p) {
  const BlockSearch& b = bs_;
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
}

}  // namespace vmt::control::gateway
