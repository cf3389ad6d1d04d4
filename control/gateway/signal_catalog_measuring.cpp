// The signal catalog's fast-measurement function block QMFB1Axx (mtc200-fast-measurement.md
// 7.2): its pins and its error numbers (figure 7-28).

#include "control/gateway/signal_catalog_parts.hpp"

namespace vmt::control::gateway::catalog {
namespace {

using enum SignalType;
using enum Direction;
using enum Scope;

constexpr SignalFamily kFamilies[] = {
    // ---------------------------------------------------------------------------------------
    // Fast-measurement function block QMFB1Axx (7.2): the control vendor supplies it to the SPS
    // program; vmt offers one instance, QMFB1A00 (the name the manual's figure 7-26 and its
    // example use; "xx" is not an axis number: the block serves the axes ACHS_NR_1..3).
    // The block runs in the SPS: its inputs and its outputs are both SPS variables, written by
    // the SPS (an external PLC that runs the block writes both over Modbus).
    {"QMFB1A00.ENABLE", kGlobal, kBool, kPlcToNc,
     "0 = FB not processed, pending errors cleared, FB reset; 1 = FB processed", FMEAS "7.2"},
    {"QMFB1A00.RESET", kGlobal, kBool, kPlcToNc, "Clear errors and reset the measuring sequence",
     FMEAS "7.2"},
    {"QMFB1A00.Q_Nummer", kGlobal, kInt, kPlcToNc,
     "Number of the Q function that triggers reading the initialisation values from the machine "
     "data (preset 9992)",
     FMEAS "7.2", "", "", 9992},
    {"QMFB1A00.Koll_EV", kGlobal, kInt, kPlcToNc,
     "Number of the 'switch on collision monitoring' event (preset 29)", FMEAS "7.2", "", "", 29},
    {"QMFB1A00.Mess_EV", kGlobal, kInt, kPlcToNc,
     "Number of the 'NC block measuring path active' event (preset 30)", FMEAS "7.2", "", "", 30},
    {"QMFB1A00.Touch_EV", kGlobal, kInt, kPlcToNc,
     "Number of the 'probe is displaced' event (preset 7)", FMEAS "7.2", "", "", 7},
    {"QMFB1A00.BasisPage", kGlobal, kInt, kPlcToNc,
     "Number of the base measurement page with the initialisation values (preset 90)",
     FMEAS "3.1; 7.2", "", "", 90},
    {"QMFB1A00.MessProc", kGlobal, kInt, kPlcToNc, "Number of the NC process used for measurement",
     FMEAS "7.2"},
    {"QMFB1A00.ACHS_NR_1", kGlobal, kInt, kPlcToNc,
     "Axis number of the 1st measuring axis; 0 = axis does not exist", FMEAS "7.2"},
    {"QMFB1A00.ACHS_NR_2", kGlobal, kInt, kPlcToNc,
     "Axis number of the 2nd measuring axis; 0 = axis does not exist", FMEAS "7.2"},
    {"QMFB1A00.ACHS_NR_3", kGlobal, kInt, kPlcToNc,
     "Axis number of the 3rd measuring axis; 0 = axis does not exist", FMEAS "7.2"},
    {"QMFB1A00.I_MT_OK1", kGlobal, kBool, kPlcToNc, "Probe 1 ready message", FMEAS "7.2"},
    {"QMFB1A00.I_MTast1", kGlobal, kBool, kPlcToNc,
     "Probe 1 measuring contact (same contact logic as at the drive)", FMEAS "7.2"},
    {"QMFB1A00.I_MT_OK2", kGlobal, kBool, kPlcToNc, "Probe 2 ready message", FMEAS "7.2"},
    {"QMFB1A00.I_MTast2", kGlobal, kBool, kPlcToNc,
     "Probe 2 measuring contact (same contact logic as at the drive)", FMEAS "7.2"},
    {"QMFB1A00.IDDS_1", kGlobal, kBool, kPlcToNc,
     "Axis 1 real-time status bit (AxxS.IDDS): TRUE when the drive accepted the measured value",
     FMEAS "7.2"},
    {"QMFB1A00.IDDS_2", kGlobal, kBool, kPlcToNc,
     "Axis 2 real-time status bit (AxxS.IDDS): TRUE when the drive accepted the measured value",
     FMEAS "7.2"},
    {"QMFB1A00.IDDS_3", kGlobal, kBool, kPlcToNc,
     "Axis 3 real-time status bit (AxxS.IDDS): TRUE when the drive accepted the measured value",
     FMEAS "7.2"},
    {"QMFB1A00.AXDdisabl", kGlobal, kBool, kPlcToNc,
     "Disable communication via the AXD channel (AXD_WR initialises the drives)", FMEAS "7.2"},
    {"QMFB1A00.MTDdisabl", kGlobal, kBool, kPlcToNc,
     "Disable communication via MTD (reading the probe data from the base measurement page)",
     FMEAS "7.2"},
    {"QMFB1A00.Init_OK_1", kGlobal, kBool, kPlcToNc, "1st measuring axis prepared for measurement",
     FMEAS "7.2"},
    {"QMFB1A00.Init_OK_2", kGlobal, kBool, kPlcToNc, "2nd measuring axis prepared for measurement",
     FMEAS "7.2"},
    {"QMFB1A00.Init_OK_3", kGlobal, kBool, kPlcToNc, "3rd measuring axis prepared for measurement",
     FMEAS "7.2"},
    {"QMFB1A00.QDDS_1", kGlobal, kBool, kPlcToNc,
     "Real-time control bit of the 1st measuring axis: wire to AxxC.QDDS to enable the latch",
     FMEAS "7.2"},
    {"QMFB1A00.QDDS_2", kGlobal, kBool, kPlcToNc,
     "Real-time control bit of the 2nd measuring axis: wire to AxxC.QDDS to enable the latch",
     FMEAS "7.2"},
    {"QMFB1A00.QDDS_3", kGlobal, kBool, kPlcToNc,
     "Real-time control bit of the 3rd measuring axis: wire to AxxC.QDDS to enable the latch",
     FMEAS "7.2"},
    {"QMFB1A00.Q_MTst1", kGlobal, kBool, kPlcToNc,
     "Activate probe 1: the measuring program requests probe 1", FMEAS "7.2"},
    {"QMFB1A00.Q_MTst2", kGlobal, kBool, kPlcToNc,
     "Activate probe 2: the measuring program requests probe 2", FMEAS "7.2"},
    {"QMFB1A00.Q_MTstOK", kGlobal, kBool, kPlcToNc,
     "The probe the measuring program requested is ready for measurement", FMEAS "7.2"},
    {"QMFB1A00.Q_MTstKol", kGlobal, kBool, kPlcToNc,
     "Probe collision: the requested probe was displaced during the approach to the measuring "
     "path (trigger an NC stop, suppress advance start)",
     FMEAS "7.2", "", "Q_MTstKOl"},
    {"QMFB1A00.Q_MTstKmp", kGlobal, kBool, kPlcToNc,
     "Test point not found: probe not displaced up to the end of the measuring path block "
     "(trigger an NC stop, suppress advance start)",
     FMEAS "7.2", "", "Q_MTstKMp"},
    {"QMFB1A00.Q_MTst", kGlobal, kBool, kPlcToNc, "Selected probe has been displaced", FMEAS "7.2"},
    {"QMFB1A00.FEHLER", kGlobal, kBool, kPlcToNc,
     "Error detected (trigger an NC stop, suppress advance start, show FEHLER_NR)", FMEAS "7.2"},
    {"QMFB1A00.FEHLER_NR", kGlobal, kInt, kPlcToNc, "Error number (figure 7-28)", FMEAS "7.2"},
    {"QMFB1A00.AXDaktiv", kGlobal, kBool, kPlcToNc,
     "Transfer via the AXD channel active (AXD_WR writes drive data)", FMEAS "7.2"},
    {"QMFB1A00.MTDaktiv", kGlobal, kBool, kPlcToNc,
     "Transfer via MTD active (MTD_RD reads machine data pages over a process data channel)",
     FMEAS "7.2"},
    {"QMFB1A00.P_Dat_ovr", kGlobal, kBool, kPlcToNc,
     "Process data channel overflow: all eight process data channels to the NC process are "
     "occupied",
     FMEAS "7.2"},
};

constexpr ValueName kValues[] = {
    // Error numbers of the measuring function block (fast-measurement figure 7-28).
    {"QMFB1A00.FEHLER_NR", "", 1, false,
     "Parameter error at the FB: no axis specified (ACHS_NR_1..3 all 0)", FMEAS "7.2"},
    {"QMFB1A00.FEHLER_NR", "", 2, false, "Parameter error at the FB: ACHS_NR_1 > 32", FMEAS "7.2"},
    {"QMFB1A00.FEHLER_NR", "", 3, false, "Parameter error at the FB: ACHS_NR_2 > 32", FMEAS "7.2"},
    {"QMFB1A00.FEHLER_NR", "", 4, false, "Parameter error at the FB: ACHS_NR_3 > 32", FMEAS "7.2"},
    {"QMFB1A00.FEHLER_NR", "", 5, false, "Parameter error at the FB: ACHS_NR_1 < 1", FMEAS "7.2"},
    {"QMFB1A00.FEHLER_NR", "", 6, false, "Parameter error at the FB: ACHS_NR_2 < 1", FMEAS "7.2"},
    {"QMFB1A00.FEHLER_NR", "", 7, false, "Parameter error at the FB: ACHS_NR_3 < 1", FMEAS "7.2"},
    {"QMFB1A00.FEHLER_NR", "", 10, false,
     "Execution error in the NC program: probe not initialised (Q9992)", FMEAS "7.2"},
    {"QMFB1A00.FEHLER_NR", "", 11, false,
     "Parameter error in the measuring pages: no axis requested for measurement", FMEAS "7.2"},
    {"QMFB1A00.FEHLER_NR", "", 12, false, "Execution error in the NC program: no EV29 before EV30",
     FMEAS "7.2"},
    {"QMFB1A00.FEHLER_NR", "", 13, false,
     "Execution error in the NC program: measuring path event set before the collision "
     "monitoring event",
     FMEAS "7.2"},
    {"QMFB1A00.FEHLER_NR", "", 20, false,
     "Parameter error in the measuring pages: 1st axis requested but ACHS_NR_1 = 0", FMEAS "7.2"},
    {"QMFB1A00.FEHLER_NR", "", 21, false,
     "Parameter error in the measuring pages: 2nd axis requested but ACHS_NR_2 = 0", FMEAS "7.2"},
    {"QMFB1A00.FEHLER_NR", "", 22, false,
     "Parameter error in the measuring pages: 3rd axis requested but ACHS_NR_3 = 0", FMEAS "7.2"},
    {"QMFB1A00.FEHLER_NR", "", 23, false,
     "NC/SPS communication: reading the probe selection from the base measurement page failed",
     FMEAS "7.2"},
    {"QMFB1A00.FEHLER_NR", "", 24, false,
     "NC/SPS communication: reading the probe logic from the base measurement page failed",
     FMEAS "7.2"},
    {"QMFB1A00.FEHLER_NR", "", 25, false,
     "NC/SPS communication: reading 'measuring with axis 1' from the base measurement page failed",
     FMEAS "7.2"},
    {"QMFB1A00.FEHLER_NR", "", 26, false,
     "NC/SPS communication: reading 'measuring with axis 2' from the base measurement page failed",
     FMEAS "7.2"},
    {"QMFB1A00.FEHLER_NR", "", 27, false,
     "NC/SPS communication: reading 'measuring with axis 3' from the base measurement page failed",
     FMEAS "7.2"},
    {"QMFB1A00.FEHLER_NR", "", 28, false,
     "NC/SPS communication: error writing SERCOS data item S_0_303 axis 1", FMEAS "7.2"},
    {"QMFB1A00.FEHLER_NR", "", 29, false,
     "NC/SPS communication: error writing SERCOS data item S_0_303 axis 2", FMEAS "7.2"},
    {"QMFB1A00.FEHLER_NR", "", 30, false,
     "NC/SPS communication: error writing SERCOS data item S_0_303 axis 3", FMEAS "7.2"},
    {"QMFB1A00.FEHLER_NR", "", 31, false,
     "NC/SPS communication: error writing SERCOS data item S_0_307 axis 1", FMEAS "7.2"},
    {"QMFB1A00.FEHLER_NR", "", 32, false,
     "NC/SPS communication: error writing SERCOS data item S_0_307 axis 2", FMEAS "7.2"},
    {"QMFB1A00.FEHLER_NR", "", 33, false,
     "NC/SPS communication: error writing SERCOS data item S_0_307 axis 3", FMEAS "7.2"},
    {"QMFB1A00.FEHLER_NR", "", 34, false,
     "NC/SPS communication: error writing SERCOS data item S_0_169 axis 1", FMEAS "7.2"},
    {"QMFB1A00.FEHLER_NR", "", 35, false,
     "NC/SPS communication: error writing SERCOS data item S_0_169 axis 2", FMEAS "7.2"},
    {"QMFB1A00.FEHLER_NR", "", 36, false,
     "NC/SPS communication: error writing SERCOS data item S_0_169 axis 3", FMEAS "7.2"},
    {"QMFB1A00.FEHLER_NR", "", 37, false,
     "NC/SPS communication: error writing SERCOS data item S_0_170 axis 1", FMEAS "7.2"},
    {"QMFB1A00.FEHLER_NR", "", 38, false,
     "NC/SPS communication: error writing SERCOS data item S_0_170 axis 2", FMEAS "7.2"},
    {"QMFB1A00.FEHLER_NR", "", 40, false,
     "Parameter error in the measuring pages or SPS: axis designation parameters, or parameters "
     "of a non-existent axis",
     FMEAS "7.2"},
};

}  // namespace

std::span<const SignalFamily> MeasuringFamilies() { return kFamilies; }
std::span<const ValueName> MeasuringValues() { return kValues; }

}  // namespace vmt::control::gateway::catalog
