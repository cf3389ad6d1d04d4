#pragma once
// The gateway between one NC channel (process Pxx) and the PLC's signal image: every NC cycle
// the channel takes the control signals the PLC wrote (mode selection, cycle start/stop,
// Control-Reset, single block, overrides, jog keys and jog mode, acknowledgements) and writes
// its status signals (mode, RUN, STOP, REV, error, auxiliary function output, axis movement and
// reference, spindle status), as the MTC200's NC/PLC interface does.

#include <cstdint>
#include <initializer_list>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "control/channel/block_search.hpp"
#include "control/channel/channel_types.hpp"
#include "control/drive_bus.hpp"
#include "control/gateway/axis_monitor.hpp"
#include "control/gateway/signal_image.hpp"

namespace vmt::control::gateway {

/// A signal the gateway reads or writes: a signal catalog family (SignalFamily::pattern) for
/// process or axis `number`, and its id in the image (-1: the machine lacks it).
struct SignalBinding {
  std::string pattern;
  int number;
  int id;
};

class ChannelGateway {
 public:
  /// `axis_numbers`: Axx number per channel axis; `spindle_number`: Axx of the main spindle
  /// (-1 if none) and its drive. Signals the image lacks are skipped (a machine without them).
  /// `rotary_number`: Axx of the rotary axis of the spindle's rotary axis mode (C-axis manual
  /// 3: a separate servo; the spindle's own number for a spindle with rotary axis capability;
  /// -1 if the spindle has no rotary mode).
  ChannelGateway(SignalImage& image, int process, const std::vector<int>& axis_numbers,
                 int spindle_number, int spindle_drive, int rotary_number = -1);

  /// PLC -> NC: acts on the channel (edges for commands, levels for states).
  void ReadControls(channel::Channel& channel);
  /// NC -> PLC: the channel's and the drives' state into the image.
  void WriteStatus(const channel::Channel& channel, const AmplifierTelegram& at);
  /// The PLC's scan in NC cycles (rounded up), for the auxiliary functions' handshake: each of
  /// its phases lasts at least one scan, so that a PLC sees every edge.
  void SetPlcScan(int nc_cycles) { plc_scan_nc_cycles_ = nc_cycles < 1 ? 1 : nc_cycles; }
  /// The JogOfPath channel (block search 4.2.1) beside `channel`: Pxx.jog_of_path.* start and
  /// hold its program, and report its state and whether it holds the axes.
  void ReadJogOfPath(channel::Channel& jog_of_path);
  void WriteJogOfPath(const channel::Channel& jog_of_path);

  /// Event n (Pxx.EVn): set by the PLC or by the program's SE/RE, tested by BES/BEC. Events the
  /// table does not list live here only (the PLC cannot see them).
  bool Event(int n) const;
  void SetEvent(int n, bool value);

  /// Every catalog signal the gateway serves, in binding order (the Q functions and events it
  /// finds by number are not among them).
  const std::vector<SignalBinding>& bindings() const { return bindings_; }

 private:
  struct Edge {
    int id = -1;
    bool last = false;
    bool Rising(const SignalImage& image);
  };
  int Id(const std::string& name) const { return image_->Find(name); }
  /// Each pattern's instance for process or axis `number` into its id field: the binding
  /// table, in the catalog's spelling.
  void Bind(int number, std::initializer_list<std::pair<std::string_view, int*>> table);
  // The constructor's bindings, part by part: the process' panel and status signals, the block
  // search objects, each axis', the spindle's, the headstock's (a spindle with rotary axis
  // capability), and the Q functions the signal table holds.
  void BindProcess(int process);
  void BindBlockSearch(int process);
  void BindAxes(const std::vector<int>& axis_numbers);
  void BindSpindle(int spindle_number, const std::vector<int>& axis_numbers);
  void BindHeadstock(int spindle_number, int rotary_number);
  void FindQFunctions();

  SignalImage* image_;
  Edge auto_, manu_, mdi_, start_, reset_, rev_, auxack_;
  /// The handshake of M, H and T: PxxS.AUXSTB rises only once AUXACK is low and the strobe has
  /// been low for a PLC scan, so that a PLC that holds AUXACK until the strobe falls (four
  /// phases) and one that pulses it both see each edge.
  bool aux_strobe_ = false;
  int aux_low_cycles_ = 1 << 20;  ///< NC cycles since the strobe fell
  int plc_scan_nc_cycles_ = 1;
  int stop_ = -1, sbl_ = -1, opstp_ = -1, fovr_ = -1, jogm_[3] = {-1, -1, -1};
  int repos_ = -1, resta_ = -1;  ///< PxxC.REPOS, PxxC.RESTA
  /// PxxC.MGPOS / PxxC.MGNEG: the tool storage axis' jog keys (REPOS manual 3.4).
  int mgpos_ = -1, mgneg_ = -1, last_mg_key_ = 0;
  int64_t last_fovr_ = -1;
  /// PxxC.ENABL, the process enabling signal: acts when it changes (C-axis manual 2.3).
  int enabl_ = -1;
  bool last_enabl_ = true;
  /// The main spindle's keys AxxC.M3 / M4 / M5 / M19 (rising edges), its override AxxC.SOVR
  /// (acts when it changes) and its reference AxxS.HOMED (C-axis manual 4.2).
  Edge spindle_m_[4];
  Edge spindle_home_;  ///< AxxC.HOME of a main spindle that is no channel axis
  int spindle_jgpos_ = -1, spindle_jgneg_ = -1, last_spindle_key_ = 0;  ///< AxxC.JGPOS/JGNEG
  int spindle_enabl_ = -1, spindle_rf_ = -1, spindle_bbdig_ = -1, nc_nmax_ = -1;
  bool last_spindle_enabl_ = false;  ///< the spindle's AxxC.ENABL as last seen
  bool spindle_enabled_ = true;      ///< what the channel was last told of it
  bool spindle_key_enabled_ = true;  ///< spindle_enabled_ when its jog key was last read
  int sovr_ = -1, spindle_homed_ = -1;
  int64_t last_sovr_ = -1;
  bool last_sbl_ = false, last_opstp_ = false;
  int last_jogm_ = -1;
  struct AxisSignals {
    int jgpos = -1, jgneg = -1, mvpos = -1, mvneg = -1, homed = -1;
    int enabl = -1, rf = -1, bbdig = -1;  ///< AxxC.ENABL, AxxS.RF, AxxS.BBDIG
    Edge home;                            ///< AxxC.HOME
    bool last_enabl = false;              ///< ENABL acts when it changes
    int last_key = 0;
  };
  std::vector<AxisSignals> axes_;
  int s_auto_ = -1, s_manu_ = -1, s_mdi_ = -1, s_run_ = -1, s_stop_ = -1, s_rev_ = -1;
  int s_repos_ = -1, s_crest_ = -1;
  int s_error_ = -1, s_errnr_ = -1, s_auxstb_ = -1, s_mfunc_ = -1, s_hfunc_ = -1, s_tfunc_ = -1;
  int msg_wr_ = -1, msg_wr_n_ = -1;  ///< Pxx.MSG_WR / MSG_WR_N: the PLC's message
  int spindle_drive_ = -1, n_ncmd_ = -1, n_nmin_ = -1, inpos_ = -1;
  int md_mdx_ = -1, p_px_ = -1, load90_ = -1;  ///< the spindle drive's threshold status
  /// Waypoints, position strobe, safety limit and thermal switches of every axis (4.2).
  AxisMonitor axis_monitor_;
  /// The headstock changeover (C-axis manual 4.1-4.3): ROTMOD/SPMOD out, their
  /// acknowledgements, the drives' enables (AxxC.READY) and AXD idents 65012..65015 in.
  struct Headstock {
    int rotmod = -1, spmod = -1, rotmod_q = -1, spmod_q = -1;
    int spindle_ready = -1, rotary_ready = -1;
    int spindle_axd[4] = {-1, -1, -1, -1}, rotary_axd[4] = {-1, -1, -1, -1};
  } headstock_;
  /// Block search of the ISG kernel (twincat-cnc-block-search-de.md 5, 7): the CNC objects
  /// mc_cmd_bs_*_w / _r, the HLI status and the on/off handshake. -1 where the image lacks one.
  struct BlockSearch {
    int type_w = -1, auto_return_w = -1, no_hold_w = -1, deviation_max_w = -1, file_offset_w = -1,
        breakpoint_w = -1, distance_w = -1, covered_w = -1, start_offset_w = -1, start_name_w = -1,
        start_type_w = -1, start_count_w = -1, end_offset_w = -1, end_name_w = -1, end_type_w = -1,
        end_count_w = -1, block_count_w = -1, block_number_w = -1, pass_w = -1, prog_name_w = -1;
    int type_r = -1, auto_return_r = -1, no_hold_r = -1, deviation_max_r = -1, breakpoint_r = -1,
        distance_r = -1, covered_r = -1, start_offset_r = -1, start_name_r = -1, start_type_r = -1,
        start_count_r = -1, end_offset_r = -1, end_name_r = -1, end_type_r = -1, end_count_r = -1,
        block_count_r = -1, block_number_r = -1, pass_r = -1, prog_name_r = -1;
    int active = -1, state = -1, covered_distance = -1, dist_prog_start = -1, line_count = -1,
        path_deviation = -1, stop_conditions = -1, distance_object = -1;
    int command = -1, plc_state = -1, enable = -1;
    int backward_w = -1, backward_r = -1;  ///< backward travel (4.3), vmt's names
    int suspend_w = -1, suspended_r = -1;  ///< HLI.channel.SuspendAxisOutput (4.2.1)
    int jop_start_w = -1, jop_stop_w = -1, jop_state_r = -1, jop_output_r = -1;  ///< vmt's
    bool jop_start = false, jop_stop = false;  ///< the levels last seen, for their edges
  } bs_;
  channel::BlockSearchParameters bs_parameters_;  ///< as last handed to the channel
  std::vector<int64_t> bs_cells_;                 ///< the parameter signals' cells as last read
  /// The read-backs as last written: the NC is their only writer, so they are written again
  /// only when the channel's parameters change.
  std::optional<channel::BlockSearchParameters> bs_read_back_;
  /// Any signal as a number (BOOL 0/1, integers, REAL/LREAL); 0 for a missing one.
  double Number(int id) const { return id >= 0 ? image_->Number(id) : 0; }
  void SetNumber(int id, double value) {
    if (id >= 0) image_->SetNumber(id, value);
  }
  // ReadControls' parts, in their order: mode, reset, block search, start/stop, overrides;
  // the axes' and spindle's enabling signals and keys; the auxiliary functions'
  // acknowledgement; the headstock's PLC signals.
  void ReadProcessControls(channel::Channel& ch);
  void ReadEnablesAndKeys(channel::Channel& ch);
  void ReadAuxAcknowledge(channel::Channel& ch);
  void ReadHeadstock(channel::Channel& ch);
  void ReadBlockSearch(channel::Channel& ch);
  bool BlockSearchWritten();
  void ReadBlockSearchParameters(channel::Channel& ch);
  void WriteBlockSearch(const channel::Channel& ch);
  void WriteBlockSearchReadBacks(const channel::BlockSearchParameters& p);
  /// Q functions with their own signal and acknowledgement (Pxx.Qnnnn / Pxx.Qnnnn_Q).
  struct QSignal {
    int number, out, ack;
  };
  std::vector<QSignal> q_;
  std::string prefix_;  ///< "P00"
  std::vector<SignalBinding> bindings_;
  std::map<int, bool> hidden_events_;
};

}  // namespace vmt::control::gateway
