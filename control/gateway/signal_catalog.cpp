// The signal catalog: the MTC200 process signals, operator panel and axis signals, the names
// left out, and the whole table, joined from the pieces by manual in its order.

#include "control/gateway/signal_catalog.hpp"

#include <initializer_list>
#include <vector>

#include "control/gateway/signal_catalog_parts.hpp"

namespace vmt::control::gateway {
namespace {

using enum SignalType;
using enum Direction;
using enum Scope;

// The table in pieces, in its order: the process signals named by the MTC200 manuals, then the
// block search (signal_catalog_block_search.cpp), the operator panel and axis signals, then the
// fast-measurement function block (signal_catalog_measuring.cpp).
constexpr SignalFamily kProcessFamilies[] = {
    // ---------------------------------------------------------------------------------------
    // Process signals named by the manuals (Pxx: process xx, from 00; fast-measurement 3.1
    // calls process 0 the master process, repositioning 8.2 writes P00C.REPOS).
    {"PxxC.REPOS", kProcess, kBool, kPlcToNc,
     "Repositioning: 1 = return to the interruption point (evaluated only after a program "
     "interruption, jogging off the contour and before Control-Reset)",
     REPOS "7.1; 7.4; 8.2"},
    {"PxxC.RESTA", kProcess, kBool, kPlcToNc,
     "NC-block restart: 1 = return to the start point of the interrupted block (same conditions "
     "as PxxC.REPOS)",
     REPOS "7.1; 7.4; 8.2"},
    {"PxxS.REPOS", kProcess, kBool, kNcToPlc,
     "Repositioning/NC-block restart allowed: set on every program interruption, reset when the "
     "program resumes or on Control-Reset",
     REPOS "7.2; 7.4"},
    {"PxxS.CREST", kProcess, kBool, kNcToPlc,
     "Conditions restored: every relevant axis and spindle has its state from before the "
     "interruption (updated only while PxxC.REPOS or PxxC.RESTA is 1)",
     REPOS "7.3; 7.4"},
    {"PxxC.JOGM0", kProcess, kBool, kPlcToNc,
     "Jog mode selection, bit 0 of JOGM0..JOGM2: type of jog movement of the feed axes "
     "(also rotary axis mode of a spindle)",
     REPOS "3.2; " CAXIS "4.2; 4.3", "", "PxxCJOGM0;PxxC.JOGMn"},
    {"PxxC.JOGM1", kProcess, kBool, kPlcToNc, "Jog mode selection, bit 1 of JOGM0..JOGM2",
     REPOS "3.2; " CAXIS "4.2; 4.3", "", "PxxCJOGM1;PxxC.JOGMn"},
    {"PxxC.JOGM2", kProcess, kBool, kPlcToNc, "Jog mode selection, bit 2 of JOGM0..JOGM2",
     REPOS "3.2; " CAXIS "4.2; 4.3", "", "PxxCJOGM2;PxxC.JOGMn"},
    {"PxxC.MGPOS", kProcess, kBool, kPlcToNc,
     "Jog the tool storage axis (turret) positive; also restores it during repositioning",
     REPOS "3.4"},
    {"PxxC.MGNEG", kProcess, kBool, kPlcToNc,
     "Jog the tool storage axis (turret) negative; also restores it during repositioning",
     REPOS "3.4"},
    {"PxxS.STOP", kProcess, kBool, kNcToPlc,
     "Program stopped: movements the SPS causes (changeover phase) must stop at once while 1",
     CAXIS "2.3, 3.3 Immediate Stop; " FMEAS "7.2 Typical Application", "", "PxxSSTOP"},
    {"PxxS.RUN", kProcess, kBool, kNcToPlc, "Block active (program running)",
     FMEAS "7.2 Typical Application"},
    {"PxxS.REV", kProcess, kBool, kNcToPlc, "Reverse program active",
     CAXIS "2.3, 3.3 Reverse; " FMEAS "7.2 Typical Application"},
    {"PxxC.REV", kProcess, kBool, kPlcToNc,
     "Reverse program start: run the reverse program (.HOME)",
     FMEAS "6.1; 7.2 Typical Application network 10"},

    // Events: a bit per number, set and reset by the NC program (SE n / RE n, tested with
    // BES/BEC) and by the SPS.
    {"Pxx.EV7", kProcess, kBool, kShared,
     "Event 7: probe displaced; set by the SPS while stylus monitoring is active (event 30 = 1)",
     FMEAS "4.1; 6.2; 7.2 (Touch_EV)", "", "E7;EV 7"},
    {"Pxx.EV29", kProcess, kBool, kShared,
     "Event 29: fast measurement: collision monitoring on, set by the NC program (SE 29) at the "
     "start of MOVE/PROBE, reset (RE 29) at the measuring path; repositioning example: tested "
     "by BES 29 ('tool drive connected?')",
     FMEAS "4.1; 6.2; 7.2 (Koll_EV); " REPOS "8.3", "", "E29;EV 29"},
    {"Pxx.EV30", kProcess, kBool, kShared,
     "Event 30: fast measurement: measuring path active, set by the NC program (SE 30) at the "
     "setup position; repositioning example: tested by BES 30 ('S1/C in rotary axis mode?')",
     FMEAS "4.1; 6.2; 7.2 (Mess_EV); " REPOS "8.3", "", "E30;EV 30"},

    // Q functions: the NC outputs them like auxiliary functions; the SPS reads one with the
    // standard function Q_FKT and acknowledges it with Q_FKT_Q (fast-measurement 6.1, 7.2).
    {"Pxx.Q9992", kProcess, kBool, kNcToPlc,
     "Q function 9992 output (Q_FKT): SETTING() asks the measuring FB to initialise the probe",
     FMEAS "4.1; 6.1; 7.2 (Q_Nummer)"},
    {"Pxx.Q9992_Q", kProcess, kBool, kPlcToNc,
     "Acknowledgement of Q9992 (Q_FKT_Q); later activation is not permitted as acknowledgement",
     FMEAS "6.1; 7.2"},
    {"Pxx.Q9998", kProcess, kBool, kNcToPlc,
     "Q function 9998 output (Q_FKT): dimensional difference between tolerance and correction "
     "limit ([OVERSIZE]/[UNDERSIZE]); fault category 2: process stop, continue by advance or "
     "reverse start",
     FMEAS "4.6; 6.1; 7.2"},
    {"Pxx.Q9998_Q", kProcess, kBool, kPlcToNc,
     "Acknowledgement of Q9998 (Q_FKT_Q); later activation is not permitted as acknowledgement",
     FMEAS "6.1; 7.2 Typical Application network 11"},
    {"Pxx.Q9999", kProcess, kBool, kNcToPlc,
     "Q function 9999 output (Q_FKT): upper or correction limit exceeded, test point not found or "
     "probe displaced outside the measuring path; fault category 1: process stop and advance "
     "inhibit, continue only by the reverse program",
     FMEAS "4.6; 6.1; 7.2"},
    {"Pxx.Q9999_Q", kProcess, kBool, kPlcToNc,
     "Acknowledgement of Q9999 (Q_FKT_Q), given when the reverse program becomes active",
     FMEAS "6.1; 7.2 Typical Application network 9"},

    // Messages SPS -> NC (standard functions MSG_WR, MSG_WR_N).
    {"Pxx.MSG_WR", kProcess, kInt, kPlcToNc,
     "Number of the message the SPS writes to the NC with MSG_WR / MSG_WR_N (e.g. 202..208 in "
     "the probe example); 0 = none",
     FMEAS "6.3; 7.2 Typical Application networks 13-30"},
    {"Pxx.MSG_WR_N", kProcess, kDint, kPlcToNc,
     "Numeric parameter of MSG_WR_N, shown in place of '@' in the message text",
     FMEAS "7.2 Typical Application networks 13-17"},
};

// Why vmt reads no actual gear stage bits: 4.3 asks for them only with a changeable gear drive.
constexpr std::string_view kNoGearbox =
    "vmt's machines drive their spindles through a fixed belt, with no changeable gear drive "
    "(4.3) and no per-gear parameters; a spindle with rotary axis capability has none (4.2)";

constexpr SignalFamily kPanelAndAxisFamilies[] = {
    // ---------------------------------------------------------------------------------------
    // Operator panel signals the NC needs that no manual names (source "vmt"). The manuals
    // speak of the modes (automatic, semi-automatic, MDI, manual: c-axis 2.3), the start button
    // (repositioning 2.3), Control-Reset, the process enabling signal (c-axis 2.3,
    // fast-measurement 6.1 fault categories) and the feed override, but give no mnemonics.
    {"PxxC.AUTO", kProcess, kBool, kPlcToNc, "Select automatic mode",
     "vmt (modes: " CAXIS "2.3 Changing Modes)"},
    {"PxxC.MANU", kProcess, kBool, kPlcToNc, "Select manual (jog) mode",
     "vmt (modes: " CAXIS "2.3 Changing Modes)"},
    {"PxxC.MDI", kProcess, kBool, kPlcToNc, "Select MDI mode",
     "vmt (modes: " CAXIS "2.3 Changing Modes)"},
    {"PxxC.SBL", kProcess, kBool, kPlcToNc,
     "Single block: automatic mode becomes semi-automatic (hold after every block)",
     "vmt (semi-automatic: " REPOS "2.1)"},
    {"PxxC.START", kProcess, kBool, kPlcToNc,
     "Cycle start (rising edge): start or continue the program (advance program start)",
     "vmt (start button: " REPOS "2.3; ADVANCE: " FMEAS "6.1)"},
    {"PxxC.OPSTP", kProcess, kBool, kPlcToNc,
     "Optional stop: while 1, M01 holds the program after its block like M00 (the M function "
     "still goes to the PLC)",
     "vmt (optional stop: " BSRCH "5.6 HLI_SC_M1_STOP)"},
    {"PxxC.STOP", kProcess, kBool, kPlcToNc,
     "Cycle stop (feed hold): brake on the path and interrupt the program while 1",
     "vmt (program interruption: " REPOS "2.1)"},
    {"PxxC.RESET", kProcess, kBool, kPlcToNc,
     "Control-Reset (rising edge): abort the program, clear unacknowledged functions",
     "vmt (Control-Reset: " REPOS "2.1; " CAXIS "2.3)"},
    {"PxxC.ENABL", kProcess, kBool, kPlcToNc,
     "Process enabling signal: removing it stops the program and the axes (immediate stop)",
     "vmt (process enabling signal: " CAXIS "2.3; " FMEAS "6.1 fault categories)"},
    {"PxxC.FOVR", kProcess, kInt, kPlcToNc, "Feed override", "vmt (" CAXIS "2.3 Feed Override)",
     "%", "", 100},
    {"PxxS.AUTO", kProcess, kBool, kNcToPlc, "Automatic mode active (mode acknowledgement)", "vmt"},
    {"PxxS.MANU", kProcess, kBool, kNcToPlc, "Manual (jog) mode active (mode acknowledgement)",
     "vmt"},
    {"PxxS.MDI", kProcess, kBool, kNcToPlc, "MDI mode active (mode acknowledgement)", "vmt"},
    {"PxxS.ERROR", kProcess, kBool, kNcToPlc, "Process error present (program stopped by an error)",
     "vmt"},
    {"PxxS.ERRNR", kProcess, kInt, kNcToPlc, "Number of the pending process error; 0 = none",
     "vmt"},
    // Auxiliary functions with acknowledgement: the manuals give Q functions their own
    // acknowledgement (Pxx.Qnnnn_Q) but name no strobe for M, H and T.
    {"PxxS.AUXSTB", kProcess, kBool, kNcToPlc,
     "Auxiliary functions (M, H, T) of the block output: the block waits for PxxC.AUXACK. Falls "
     "at the acknowledgement; rises for the next functions only once AUXACK is low and it has "
     "been low a PLC scan (a pulsed or a held AUXACK both work)",
     "vmt"},
    {"PxxS.MFUNC", kProcess, kInt, kNcToPlc, "M function number while PxxS.AUXSTB (-1: none)",
     "vmt", "", "", -1},
    {"PxxS.HFUNC", kProcess, kInt, kNcToPlc, "H function number while PxxS.AUXSTB (-1: none)",
     "vmt", "", "", -1},
    {"PxxS.TFUNC", kProcess, kInt, kNcToPlc, "T number (tool) while PxxS.AUXSTB (-1: none)", "vmt",
     "", "", -1},
    {"PxxC.AUXACK", kProcess, kBool, kPlcToNc,
     "Acknowledge the auxiliary functions output (rising edge while AUXSTB is high): the block "
     "goes on; pulse it for a scan or hold it until AUXSTB falls",
     "vmt"},

    // ---------------------------------------------------------------------------------------
    // Axis signals (c-axis 4.2 table "Axis Signals"; Axx: axis number xx, from 01: the
    // fast-measurement FB rejects axis numbers < 1 and > 32, 7.2 FEHLER_NR 2..7, and its
    // example wires axis 1 to A01C.QDDS). The spindle-related ones ("*") exist only on
    // spindle-capable axes.
    {"AxxC.HOMLS", kAxis, kBool, kPlcToNc, "Home switch", CAXIS "4.2", "", "", 0,
     "a digital drive has its home switch wired to the drive, not the NC (4.2); vmt's homing "
     "(G74, AxxC.HOME) goes to the reference point and its machines have no home switch"},
    {"AxxC.READY", kAxis, kBool, kPlcToNc,
     "Axis ready; with a separate C servo also switches the drive's controller enable",
     CAXIS "4.2; 4.3", "", "AxxCREADY"},
    {"AxxC.JGPOS", kAxis, kBool, kPlcToNc,
     "Positive jogging (on a spindle: selects rotary axis mode)", CAXIS "2.3; 3.3; 4.2", "",
     "AxxCJGPOS"},
    {"AxxC.JGNEG", kAxis, kBool, kPlcToNc,
     "Negative jogging (on a spindle: selects rotary axis mode)", CAXIS "2.3; 3.3; 4.2", "",
     "AxxCJGNEG"},
    {"AxxC.HOME", kAxis, kBool, kPlcToNc,
     "Homing (rising edge, manual mode): a channel axis travels to its reference point at its "
     "homing speed as G74 takes it, and is homed there; a main spindle is positioned to its "
     "reference point as M19 does, which homes it (2.3, 3.3 Homing)",
     CAXIS "2.3; 3.3; 4.2"},
    {"AxxC.ENABL", kAxis, kBool, kPlcToNc,
     "Axis enabling signal: without it the axis cannot move in manual mode (its keys start "
     "nothing, a continuous jog brakes); acts when it changes, so an axis whose PLC never "
     "writes it stays enabled",
     CAXIS "2.3; 4.2"},
    {"AxxC.STRBP", kAxis, kBool, kPlcToNc,
     "Position strobe (rising edge): the NC saves the axis' actual position into AxxS.STRBPOS",
     CAXIS "4.2"},
    {"AxxC.QDDS", kAxis, kBool, kPlcToNc,
     "Real-time command bit of the drive (QMFB1Axx enables the probe latch with it)",
     CAXIS "4.2; " FMEAS "7.2", "", "AxxCQDDS"},
    {"AxxC.OTRVL", kAxis, kBool, kPlcToNc,
     "Safety limit switch (1 = not tripped; a digital spindle's must be 1). Going from 1 to 0: "
     "immediate stop of the channel and its spindle, message 508; Control-Reset clears it",
     CAXIS "4.2"},
    {"AxxC.MTAS", kAxis, kBool, kPlcToNc,
     "Thermal protection switch (1 = not tripped; a digital spindle's must be 1). Going from 1 "
     "to 0: immediate stop of the channel and its spindle, message 509",
     CAXIS "4.2"},
    {"AxxC.MHOLD", kAxis, kBool, kPlcToNc,
     "Axis hold: inhibits the axis (probe recovery time in the example); name reconstructed from "
     "the garbled 'AM_schmierxC.MHOLD'",
     FMEAS "7.2 Typical Application network 3", "", "AM_schmierxC.MHOLD", 0,
     "the garbled name gives no meaning to build on; vmt's probe block does not write it"},
    {"AxxC.M3", kSpindle, kBool, kPlcToNc,
     "Spindle clockwise (rising edge, at the jogging speed; restores M03 in repositioning)",
     REPOS "3.3; " CAXIS "2.3; 4.2; 4.3", "", "AxxCM3"},
    {"AxxC.M4", kSpindle, kBool, kPlcToNc,
     "Spindle counter-clockwise (rising edge; restores M04 in repositioning)",
     REPOS "3.3; " CAXIS "2.3; 4.2; 4.3", "", "AxxCM4"},
    {"AxxC.M5", kSpindle, kBool, kPlcToNc, "Spindle stop (rising edge)",
     REPOS "3.3; " CAXIS "2.3; 4.2; 4.3", "", "AxxCM5"},
    {"AxxC.M19", kSpindle, kBool, kPlcToNc,
     "Spindle positioning (rising edge, to the jogging spindle position)",
     REPOS "3.3; " CAXIS "2.3; 4.2; 4.3", "", "AxxCM19"},
    {"AxxC.GEAR1", kSpindle, kBool, kPlcToNc, "Actual gear stage bit 1", CAXIS "4.2; 4.3", "", "",
     0, kNoGearbox},
    {"AxxC.GEAR2", kSpindle, kBool, kPlcToNc, "Actual gear stage bit 2", CAXIS "4.2; 4.3", "", "",
     0, kNoGearbox},
    {"AxxC.GEAR3", kSpindle, kBool, kPlcToNc, "Actual gear stage bit 3", CAXIS "4.2; 4.3", "", "",
     0, kNoGearbox},
    {"AxxC.SOVR", kSpindle, kInt, kPlcToNc,
     "Spindle override (spindle-specific; acts while M3/M4/M19 are active)",
     "vmt (" CAXIS "2.3 Feed and Spindle Override)", "%", "", 100},
    {"AxxS.RF", kAxis, kBool, kNcToPlc,
     "Controller enabling signal (status: the drive's controller enable, which the NC sends "
     "over SERCOS, is active)",
     CAXIS "4.2"},
    {"AxxS.HOMED", kAxis, kBool, kNcToPlc, "Reference: the axis is homed", CAXIS "4.2"},
    {"AxxS.MVPOS", kAxis, kBool, kNcToPlc, "Positive axis movement", CAXIS "4.2"},
    {"AxxS.MVNEG", kAxis, kBool, kNcToPlc, "Negative axis movement", CAXIS "4.2"},
    {"AxxS.BBDIG", kAxis, kBool, kNcToPlc, "Digital drive ready", CAXIS "4.2"},
    {"AxxS.STRBPOS", kAxis, kLreal, kNcToPlc,
     "The position AxxC.STRBP's rising edge saved: the axis' actual position, machine "
     "coordinates (rotary: within the turn)",
     "vmt (" CAXIS "4.2 position strobe: the manual names no place to read it)", "mm | deg"},
    {"AxxS.IDDS", kAxis, kBool, kNcToPlc,
     "Real-time status bit of the drive (set when the probe value is latched, as QMFB1Axx "
     "configures it)",
     CAXIS "4.2; " FMEAS "7.2; 7.3", "", "AxxSIDDS"},
    {"AxxS.WP0", kAxis, kBool, kNcToPlc,
     "Waypoint 0 passed: homed and the actual position at or beyond Cxx.025 (rotary: within "
     "the turn); 0 while the parameter is not set",
     CAXIS "2.2; 4.2"},
    {"AxxS.WP1", kAxis, kBool, kNcToPlc,
     "Waypoint 1 passed: homed and the actual position at or beyond Cxx.026 (rotary: within "
     "the turn); 0 while the parameter is not set",
     CAXIS "2.2; 4.2"},
    {"AxxS.WP2", kAxis, kBool, kNcToPlc,
     "Waypoint 2 passed: homed and the actual position at or beyond Cxx.027 (rotary: within "
     "the turn); 0 while the parameter is not set",
     CAXIS "2.2; 4.2"},
    {"AxxS.WP3", kAxis, kBool, kNcToPlc,
     "Waypoint 3 passed: homed and the actual position at or beyond Cxx.028 (rotary: within "
     "the turn); 0 while the parameter is not set",
     CAXIS "2.2; 4.2"},
    {"AxxS.WP4", kAxis, kBool, kNcToPlc,
     "Waypoint 4 passed: homed and the actual position at or beyond Cxx.029 (rotary: within "
     "the turn); 0 while the parameter is not set",
     CAXIS "2.2; 4.2"},
    {"AxxS.WP5", kAxis, kBool, kNcToPlc,
     "Waypoint 5 passed: homed and the actual position at or beyond Cxx.030 (rotary: within "
     "the turn); 0 while the parameter is not set",
     CAXIS "2.2; 4.2"},
    {"AxxS.WP6", kAxis, kBool, kNcToPlc,
     "Waypoint 6 passed: homed and the actual position at or beyond Cxx.031 (rotary: within "
     "the turn); 0 while the parameter is not set",
     CAXIS "2.2; 4.2"},
    {"AxxS.WP7", kAxis, kBool, kNcToPlc,
     "Waypoint 7 passed: homed and the actual position at or beyond Cxx.032 (rotary: within "
     "the turn); 0 while the parameter is not set",
     CAXIS "2.2; 4.2"},
    {"AxxS.N_NCMD", kSpindle, kBool, kNcToPlc, "Nact = Ncomm: spindle at commanded speed",
     CAXIS "4.2"},
    {"AxxS.N_NMIN", kSpindle, kBool, kNcToPlc, "Nact = 0: spindle at standstill", CAXIS "4.2"},
    {"AxxS.MD_MDX", kSpindle, kBool, kNcToPlc,
     "|Md| >= Mdx: the drive's torque at or above its threshold (SERCOS S-0-0333, drive key "
     "torque_threshold; from the torque, so 0 on the kinematic backend)",
     CAXIS "4.2"},
    {"AxxS.NC_NMAX", kSpindle, kBool, kNcToPlc,
     "|Ncomm| >= Nlimit: speed command (override applied) at the spindle's maximum speed",
     CAXIS "4.2"},
    {"AxxS.INPOS", kSpindle, kBool, kNcToPlc, "In position (spindle positioning M19 done)",
     CAXIS "4.2"},
    {"AxxS.P_PX", kSpindle, kBool, kNcToPlc,
     "|P| >= Px: the drive's mechanical power at or above its threshold (the manual's formula "
     "is cut off after '|P| >='; read as SERCOS S-0-0337, drive key power_threshold; 0 on the "
     "kinematic backend)",
     CAXIS "4.2"},
    {"AxxS.LOAD90", kSpindle, kBool, kNcToPlc,
     "90 % load: the drive's torque at or above 90 % of its torque limit (0 on the kinematic "
     "backend)",
     CAXIS "4.2"},
    {"AxxS.SYNCHRON", kSpindle, kBool, kNcToPlc, "Synchronous run", CAXIS "4.2", "", "", 0,
     "the manual does not define it further; vmt reads it as two spindles run synchronously, "
     "and its machines have one main spindle and no spindle coupling"},

    // Standard functions of the spindle <-> rotary axis changeover (AXIS input = the main
    // spindle's axis number, c-axis 4.4).
    {"Axx.ROTMOD", kSpindle, kBool, kNcToPlc,
     "ROTMOD: rotary axis mode pre-selected (the NC requests the changeover to rotary axis mode)",
     CAXIS "2.3; 4.1; 4.2; 4.4"},
    {"Axx.ROTMOD_Q", kSpindle, kBool, kPlcToNc,
     "ROTMOD_Q: rotary axis mode acknowledged; apply for as long as rotary axis mode is "
     "pre-selected, removing it during rotary operation is a process error",
     CAXIS "4.1; 4.2; 4.4", "", "ROTMODE_Q"},
    {"Axx.SPMOD", kSpindle, kBool, kNcToPlc,
     "SPMOD: spindle mode pre-selected (the NC requests the changeover to spindle mode)",
     CAXIS "2.3; 4.1; 4.2; 4.4"},
    {"Axx.SPMOD_Q", kSpindle, kBool, kPlcToNc,
     "SPMOD_Q: spindle mode acknowledged; apply for as long as spindle mode is pre-selected, "
     "removing it during spindle operation is a process error",
     CAXIS "4.1; 4.2; 4.4"},

    // AXD data channel: SERCOS parameters reserved in the axis processor for the changeover,
    // written by the NC program (AXD) or the SPS (AXD_WR); [Read/Write] in the manual.
    {"Axx.AXD.65012", kChangeover, kWord, kShared,
     "Ident 65012 (P-7-3572), spindle function during gear range selection: request bits 0 "
     "hunting, 1 positioning, 2 speed specification; bits 8..10 their acknowledgements",
     CAXIS "2.2; 3.2; 4.4"},
    {"Axx.AXD.65013", kChangeover, kDint, kShared,
     "Ident 65013 (P-7-3573): spindle speed for 'spindle speed specification' (max. 1000 rpm; may "
     "change while active)",
     CAXIS "2.2; 3.2; 4.4", "0.0001 1/min"},
    {"Axx.AXD.65014", kChangeover, kDint, kShared,
     "Ident 65014 (P-7-3574): spindle acceleration for 'spindle speed specification'",
     CAXIS "2.2; 3.2; 4.4", "rad/s^2"},
    {"Axx.AXD.65015", kChangeover, kDint, kShared,
     "Ident 65015 (P-7-3575): spindle angle for 'spindle positioning' (0..360 deg)",
     CAXIS "2.2; 3.2; 4.4", "0.0001 deg"},
};

constexpr ValueName kAxisValues[] = {
    // Ident number 65012 bits (c-axis 2.2).
    {"Axx.AXD.65012", "Bit 0", 0x0001, true, "Spindle hunting specification (KDA only)",
     CAXIS "2.2; 3.2"},
    {"Axx.AXD.65012", "Bit 1", 0x0002, true,
     "Spindle positioning specification (KDA only, angle in 65015)", CAXIS "2.2; 3.2"},
    {"Axx.AXD.65012", "Bit 2", 0x0004, true,
     "Spindle speed specification (speed in 65013, acceleration in 65014)", CAXIS "2.2; 3.2"},
    {"Axx.AXD.65012", "Bit 8", 0x0100, true, "Spindle hunting acknowledgement", CAXIS "2.2; 3.2"},
    {"Axx.AXD.65012", "Bit 9", 0x0200, true, "Spindle positioning acknowledgement",
     CAXIS "2.2; 3.2"},
    {"Axx.AXD.65012", "Bit 10", 0x0400, true, "Spindle speed specification acknowledgement",
     CAXIS "2.2; 3.2"},
};

constexpr Unrepresented kUnrepresented[] = {
    {"AXD_WR",
     "The SPS's write access to the AXD data channel (axis, ident number, four data bytes); the "
     "data it writes are the cells Axx.AXD.65012..65015, a PLC runtime can offer the block on "
     "top of them",
     CAXIS "4.4; " FMEAS "7.2"},
    {"MTD_RD",
     "Reads machine data pages (BASISMESSPAGE ...) over a process data channel: NC data pages, "
     "not gateway signals; vmt's QMFB1A00 reads the page itself",
     FMEAS "7.2"},
    {"MTD_WR", "As MTD_RD (the manual writes both names for the same channel)", FMEAS "7.2"},
    {"S-0-0169", "Drive probe parameters (S-0-0169/0170/0401.../0409...): the DriveBus telegram",
     FMEAS "7.3"},
    {"S-0-0307", "Real-time bit allocation (S-0-0301/0303/0305/0307): the drive side of QDDS/IDDS",
     FMEAS "7.3"},
    {"Rotary axis/main spindle operation", "An NC signal to the user interface, not to the SPS",
     CAXIS "2.3 Position Indication"},
    {"mAxxCM3",
     "User-interface flags of the machine keys (mAxxCM3/M4/M5/M19, mREPOS, mRESTA): the SPS "
     "maps them onto AxxC.M3 ... and PxxC.REPOS/RESTA",
     REPOS "8.1; 8.2"},
    {"HLI_SYS_CH_MAXIDX", "Array bound of gpCh[], not a signal", BSRCH "7"},
};

template <typename T>
std::vector<T> Joined(std::initializer_list<std::span<const T>> pieces) {
  std::vector<T> all;
  for (std::span<const T> piece : pieces) all.insert(all.end(), piece.begin(), piece.end());
  return all;
}

}  // namespace

std::span<const SignalFamily> SignalFamilies() {
  static const std::vector<SignalFamily> families = Joined<SignalFamily>(
      {kProcessFamilies, catalog::BlockSearchFamilies(), kPanelAndAxisFamilies,
       catalog::MeasuringFamilies()});
  return families;
}
std::span<const ValueName> SignalValues() {
  static const std::vector<ValueName> values =
      Joined<ValueName>({catalog::BlockSearchValues(), kAxisValues, catalog::MeasuringValues()});
  return values;
}
std::span<const Unrepresented> UnrepresentedNames() { return kUnrepresented; }

}  // namespace vmt::control::gateway
