#pragma once
// Shared by the block search tests: the steps an operator takes to search and return, on any
// test rig that has `channel`, `t` and `Tick()` (the Mill of the manual's milling examples, the
// Lathe of the turning ones).

#include <gtest/gtest.h>

#include <functional>

#include "control/channel/channel.hpp"

namespace vmt::control::channel::testing {

/// Block search type 4: pass `pass` of block N`number`, continuing `per_mille` of the way into
/// it, with the automatic return to the contour.
inline BlockSearchParameters BlockNumberSearch(uint32_t number, double per_mille = 0,
                                               uint32_t pass = 1) {
  BlockSearchParameters p;
  p.type = BlockSearchType::kBlockNumber;
  p.block_number = number;
  p.block_number_pass = pass;
  p.covered_distance = per_mille;
  p.auto_return = true;
  return p;
}

template <class Rig>
struct BlockSearchSteps : Rig {
  using Rig::Rig;

  /// Ticks until `done` or `limit` seconds more; whether `done`.
  bool RunUntil(const std::function<bool()>& done, double limit = 60) {
    const double end = this->t + limit;
    while (!done() && this->t < end) this->Tick();
    return done();
  }
  BlockSearchState State() const { return this->channel->block_search().state; }
  bool Ended() const { return this->channel->state() == ChannelState::kEnded; }
  /// Until the search state is `s`, or the channel ends or fails on the way.
  bool Waits(BlockSearchState s) {
    return RunUntil(
        [&] { return State() == s || this->channel->state() == ChannelState::kError || Ended(); });
  }
  void Search(const BlockSearchParameters& p) {
    std::string error;
    EXPECT_TRUE(this->channel->SetBlockSearch(p, &error)) << error;
    this->channel->Start();
  }
  /// Start, the search, the automatic return, the hold at the contour: true when the channel
  /// stands in HLI_BS_WAIT_FOR_CONTINUE_CONTOUR.
  bool ToContour() {
    if (!Waits(BlockSearchState::kWaitReturnToContour)) return false;
    this->channel->Start();
    return Waits(BlockSearchState::kWaitForContinueContour);
  }
};

}  // namespace vmt::control::channel::testing
