#pragma once
// The Q functions fast measurement issues to the PLC and the NC messages that come with them
// (mtc200-fast-measurement.md 6.1; 4.6 Upper limit, Correction limit, Tolerance limit): numbers,
// fault categories and texts as data, spelled as in the manual.

namespace vmt::control::measure {

/// 6.1 Q9992: issued by SETTING( ); the PLC's measuring block initialises the probe.
inline constexpr int kQ9992 = 9992;
/// 6.1 Q9998: dimensional difference between tolerance limit and correction limit.
inline constexpr int kQ9998 = 9998;
/// 6.1 Q9999: upper or correction limit exceeded, or a test point not found.
inline constexpr int kQ9999 = 9999;

/// How the PLC program integrates a Q function (6.1: "has been defined as follows, and should
/// be integrated into the SPS program according to the definition").
struct QFunctionDefinition {
  int number = 0;
  int fault_category = 0;  ///< 1 or 2 (6.1)
  const char* message_text = "";
  const char* additional_text = "";
  /// Fault category 2: after acknowledging, a new advance program start continues the program.
  /// Fault category 1: the advance program stays inhibited; only the reverse program (or manual
  /// mode) remains.
  bool advance_continuable = false;
  /// The message the PLC writes to the NC (MSG_WR) while the fault stands: 7.2 typical
  /// application, network 19 (204, type 2) and network 18 (205, type 1).
  int plc_message = 0;
};

inline constexpr QFunctionDefinition kQ9998Definition = {
    kQ9998, 2, "CNC software fault message of TYPE 2",
    "The fault has been triggered by programming Q9998 in the NC program. The NC program was "
    "stopped for safety reasons. Please note the additional comments that were issued by the NC "
    "program. Acknowledging the fault by pressing the key provided for this purpose permits the "
    "interrupted advance program to be continued after a new advance program start or the home "
    "position to be approached by a reverse program start.",
    true, 204};

inline constexpr QFunctionDefinition kQ9999Definition = {
    kQ9999, 1, "CNC software fault message of TYPE 1",
    "The fault has been triggered by programming Q9999 in the NC program. For safety reasons, "
    "the NC program can no longer be executed. Please note the additional comments that were "
    "issued by the NC program. Acknowledging the fault by pressing the key provided for this "
    "purpose permits machining to be continued after a reverse program has been triggered by "
    "pressing a reverse program start key.",
    false, 205};

/// An NC message of fast measurement and the Q function issued with it.
struct MeasuringMessage {
  int q_function = 0;  ///< kQ9998 or kQ9999
  const char* text = "";

  /// The fault category of the Q function: 2 for Q9998, 1 for Q9999.
  constexpr int fault_category() const { return q_function == kQ9998 ? 2 : 1; }
  /// Q9998 may be continued by the advance program; after Q9999 only the reverse program runs.
  constexpr bool advance_continuable() const { return q_function == kQ9998; }
};

/// 4.6 Dimensional accuracy 1: dimensional difference > 0 beyond the tolerance limit.
inline constexpr MeasuringMessage kOversize = {kQ9998, "OVERSIZE"};
/// 4.6 Dimensional accuracy 2: dimensional difference < 0 beyond the tolerance limit.
inline constexpr MeasuringMessage kUndersize = {kQ9998, "UNDERSIZE"};
/// 6.1: the probe did not switch on the measuring path, or was displaced outside it.
inline constexpr MeasuringMessage kTestPointNotFound = {kQ9999, "TEST POINT NOT FOUND"};
/// 6.1: the probe displaced outside the measuring path. 6.1 names this case in the same
/// sentence as a test point not found and lists no message of its own for it, so vmt issues
/// TEST POINT NOT FOUND and says which of the two it was.
inline constexpr MeasuringMessage kProbeDisplacedOutsidePath = {
    kQ9999, "TEST POINT NOT FOUND (probe displaced outside the measuring path)"};
/// 4.6 Upper limit exceeded: a gross error in the parameters or the stylus.
inline constexpr MeasuringMessage kIllegallyHighDimensionalDeviation = {
    kQ9999, "ILLEGALLY HIGH DIMENSIONAL DEVIATION"};
/// 4.6 Correction limit exceeded: excessive tool wear, likely.
inline constexpr MeasuringMessage kCheckTool = {kQ9999, "CHECK TOOL"};

/// The definition of Q function `number` (9998, 9999); nullptr for others (Q9992 has no message).
constexpr const QFunctionDefinition* QFunction(int number) {
  if (number == kQ9998) return &kQ9998Definition;
  if (number == kQ9999) return &kQ9999Definition;
  return nullptr;
}

}  // namespace vmt::control::measure
