#pragma once
// The channel as PathGuard's client: the guard it asks and what a contact does (stop the move
// with an NC error, or only record it), the record of every check, and the continuous moves -
// jogs of the feed axes and of the turret - checked ahead every few NC cycles while they run,
// each summed up as one record. What is checked, and the error's text, are the channel's
// (channel_path_guard.cpp, channel_turret_guard.cpp, channel_fictive_jog.cpp).

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "control/channel/channel_types.hpp"
#include "control/path_guard.hpp"

namespace vmt::control::channel {

/// A move checked ahead while it runs, one record each.
enum class ContinuousMove : uint8_t { kJog, kTurretJog };

class PathGuardClient {
 public:
  /// `every`: NC cycles between the checks ahead of a continuous move.
  PathGuardClient(GuardReaction reaction, int every) : reaction_(reaction), every_(every) {}

  void SetGuard(PathGuard* guard) { guard_ = guard; }
  /// Moves are checked: there is a guard and contacts are not ignored (GuardReaction::kOff).
  bool active() const { return guard_ && reaction_ != GuardReaction::kOff; }
  PathGuard& guard() const { return *guard_; }
  /// The checks since the last call, oldest first.
  std::vector<GuardRecord> TakeRecords() { return std::exchange(records_, {}); }

  /// A whole move checked clear.
  void Clear(const std::string& move, const std::vector<double>& from,
             const std::vector<double>& to, const PathCheck& check) {
    records_.push_back({move, from, to, check, 1, false});
  }
  /// A move checked in pieces (chords), summed up as one record.
  void Add(GuardRecord record) { records_.push_back(std::move(record)); }
  /// A contact ahead of a move: recorded; true if it stops the move (GuardReaction::kStop).
  bool Contact(const std::string& move, const std::vector<double>& from,
               const std::vector<double>& to, const PathCheck& check) {
    const bool stop = reaction_ == GuardReaction::kStop;
    records_.push_back({move, from, to, check, 1, stop});
    return stop;
  }

  /// Whether the check ahead of continuous move `m` is due this NC cycle: when it starts, then
  /// every `every` cycles while it runs (`moving`). At rest its record is closed.
  bool Due(ContinuousMove m, bool moving) {
    Running& r = running_[static_cast<int>(m)];
    if (!moving) {
      Close(r);
      r.countdown = 0;
      return false;
    }
    if (r.record && --r.countdown > 0) return false;
    r.countdown = every_;
    return true;
  }
  /// Whether continuous move `m` runs with its record open (its first check ahead made).
  bool Open(ContinuousMove m) const { return running_[static_cast<int>(m)].record.has_value(); }
  /// The due check ahead of `m` (Due): clear, it is summed into the move's record; a contact
  /// closes the record and is a Contact. True if it stops the move.
  bool Ahead(ContinuousMove m, const std::string& move, const std::vector<double>& from,
             const std::vector<double>& to, const PathCheck& check) {
    Running& r = running_[static_cast<int>(m)];
    if (check.clear) {
      if (!r.record) {
        r.record = GuardRecord{move, from, to, check, 1, false};
      } else {
        r.record->to = to;
        ++r.record->checks;
        if (check.min_clearance < r.record->check.min_clearance) r.record->check = check;
      }
      return false;
    }
    Close(r);
    return Contact(move, from, to, check);
  }
  /// A due check ahead of `m` that the last query proves clear (PathGuard::Proves): counted,
  /// the record reaching on to `to`; its smallest clearance stays the queries' (what a proof
  /// reports is a bound, not a measure).
  void Proven(ContinuousMove m, const std::vector<double>& to) {
    Running& r = running_[static_cast<int>(m)];
    r.record->to = to;
    ++r.record->checks;
  }
  /// X1/Y1's jog (each check a record of its own): whether its check is due this NC cycle.
  bool FictiveDue() {
    if (--fictive_countdown_ > 0) return false;
    fictive_countdown_ = every_;
    return true;
  }

 private:
  struct Running {
    std::optional<GuardRecord> record;
    int countdown = 0;
  };
  void Close(Running& r) {
    if (r.record) records_.push_back(*r.record);
    r.record.reset();
  }

  PathGuard* guard_ = nullptr;  ///< null: no geometry to check against
  GuardReaction reaction_;
  int every_;
  std::vector<GuardRecord> records_;
  Running running_[2];
  int fictive_countdown_ = 0;
};

}  // namespace vmt::control::channel
