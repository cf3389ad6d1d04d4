#pragma once
// The JogOfPath channel (twincat-cnc-block-search-de.md 4.2.1, "Manuelles Wiederanfahren während
// Satzvorlauf"): a second channel on the block search channel's feed axes runs the manual
// return to the contour as an NC program of its own ("über eine beliebige Strategie") while the
// block search decodes, "bei bereits gestartetem Satzvorlauf". The PLC lends it the axes with
// HLI.channel.SuspendAxisOutput and takes them back before it releases the automatic return,
// which then moves only the rest of the way. The axes change hands at standstill only.

#include "control/channel/channel.hpp"

namespace vmt::control::channel {

/// The JogOfPath channel's configuration: the block search channel's feed axes (its limits,
/// offsets, tools and PathGuard reaction) without the rotary axis of a headstock, which rides on
/// the spindle; no spindle and no tool storage axis of its own. Its auxiliary functions count as
/// acknowledged at once: the PLC handshake is the block search channel's. Its moves are approach
/// moves: PathGuard checks each before it starts.
ChannelConfig JogOfPathConfig(const ChannelConfig& block_search_channel);

/// The axes are with one channel at a time. The JogOfPath channel takes them while the PLC
/// suspends the block search channel's output and that channel has let them go; the block
/// search channel gets them back once the JogOfPath channel has let them go (standing, after
/// the PLC's request). The channel without them follows where the other commands them. Once
/// per NC cycle, before both channels tick.
void HandOverAxes(Channel& block_search_channel, Channel& jog_of_path);

}  // namespace vmt::control::channel
