#pragma once
// #CAX TRACK (ISG; its block search side is twincat-cnc-block-search-de.md 4.2.2): while on, the
// C axis follows the tangent of the path in the working plane, so that a tool such as a cutting
// wheel stays aligned with the contour. The channel applies it to each motion block as the
// block starts (channel_cax_track.cpp), in a run and in block search alike, so that the search
// knows where C stands at the continue position and the return aligns C to the tangent there.
//
// Readings vmt takes where the block search manual only shows the example:
// - The angle is that of the direction of travel in the plane (G17: from X towards Y, G18: from
//   Z towards X, G19: from Y towards Z), in degrees, plus OFFSET; C takes it on the shortest way
//   round, so C counts on past 360 degrees rather than jumping back.
// - ANGLIMIT: a block whose start tangent differs from where C stands by more than the limit
//   gets a C-only move before it, the path standing meanwhile (the manual's example at N40).
//   Within the limit, C turns along with the block. Without ANGLIMIT the
//   limit is 0: every corner turns C first.
// - The first block after ON aligns C the same way (C is not kept at an offset to the tangent).
// - While on, C belongs to the tracking: a block that programs C is an error, and so is any
//   option vmt does not run (OPTALIGN, ROTMODE, SCALEFACT, AX, AXNR, START_STROKE, ANGPOS).

#include <optional>
#include <string>
#include <string_view>

#include "control/channel/block_motion.hpp"

namespace vmt::control::channel {

/// One #CAX TRACK command: ON with its options, or OFF.
struct CaxTrackCommand {
  bool on = false;
  double anglimit_deg = 0;  ///< ANGLIMIT: the largest turn C makes along with a block
  double offset_deg = 0;    ///< OFFSET: C's angle to the tangent
};

/// The command in `text` (an ISG #-command without its '#': "CAXTRACK ON [ANGLIMIT 3, OFFSET
/// 0]", both spellings "CAX TRACK" and "CAXTRACK", options as "NAME value" or "NAME=value").
/// Nothing if `text` is not #CAX TRACK; an option vmt does not know or a bad value: `error` set.
/// #CAX TRACK in a channel: on with its options, and a C-only move of a turn beyond ANGLIMIT
/// under way before the block.
struct CaxTrackState {
  std::optional<CaxTrackCommand> command;
  bool aligning = false;
};

std::optional<CaxTrackCommand> ParseCaxTrack(std::string_view text, std::string* error);

/// What tracking makes of one block's motion.
struct CaxTrackStep {
  bool in_plane = false;  ///< the block moves in the plane: C follows it
  bool align = false;     ///< C turns alone to `start_deg` before the block (beyond ANGLIMIT)
  double start_deg = 0;   ///< C at the block's start tangent (program coordinates)
  double end_deg = 0;     ///< C at the block's end tangent (program coordinates)
};

/// C for `motion` (planned without C) when C stands at `c_deg` (program coordinates); `p0`,
/// `p1`: the channel axes of the plane, first and second.
CaxTrackStep TrackStep(const BlockMotion& motion, int p0, int p1, double c_deg,
                       const CaxTrackCommand& track);

}  // namespace vmt::control::channel
