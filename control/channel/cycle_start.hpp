#pragma once
// What a cycle start does: Channel::StartCase decides it from the channel's state before
// anything changes, and Channel::Start acts on the decision.

#include <cstdint>

namespace vmt::control::channel {

/// The cases of a cycle start in the order the channel asks (Channel::StartCase): the first
/// that applies.
enum class CycleStart : uint8_t {
  kRefused,          ///< manual mode, no process enable, MDI without blocks, running, an error
  kDeferred,         ///< a jog left for this mode still brakes: taken once the axes rest
  kReplay,           ///< held on backward travel's path: a leg goes on, or the next one starts
  kBlockSearchHold,  ///< held at the breakpoint or during the search: it goes on
  kReposRerun,       ///< the REPOS subroutine, left for manual mode, runs again from .REPOS
  kReposContinue,    ///< the held REPOS subroutine goes on
  kReposCall,        ///< repositioning or NC-block restart selected: the REPOS subroutine runs
  kContinue,         ///< the held program goes on, if its axes stand on the contour
  kReposAfterError,  ///< an error that interrupts the REPOS subroutine: it runs again
  kRun,              ///< the program runs from its first block (again, after its end)
};

/// A start not yet taken: the program's (positions are taken from the feedback at the next
/// tick), or one waiting for a jog left for this mode to brake to rest.
struct PendingStart {
  bool program = false;
  bool deferred = false;
};

}  // namespace vmt::control::channel
