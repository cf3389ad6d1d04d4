#pragma once
// The NC channel's events in a scene's trace (events.jsonl): PathGuard checks and the REPOS
// screen (repositioning manual 2.2), as the operator and the PLC engineer read them; and the
// stylus crashing into the part, the run-time counterpart of a PathGuard contact.

#include <nlohmann/json.hpp>

#include "control/channel/channel_types.hpp"
#include "control/channel/repositioning.hpp"
#include "sim/backend/stylus_contacts.hpp"
#include "sim/model/machine_model.hpp"

namespace vmt::sim {

/// A PathGuard check: the move, the answer (the first contact: parts, point, distance along the
/// path, where the moving drives would stand; or clear) and the smallest clearance on the way.
nlohmann::ordered_json GuardEvent(double t, const control::channel::GuardRecord& r,
                                  const MachineModel& m);

/// A stylus deflected beyond its over-travel: a crash of the stylus into the part, with the
/// sphere (1..5, as TASTWERKZEUGPAGE numbers them), the two parts and the point on the part
/// (world, mm).
nlohmann::ordered_json StylusOverTravelEvent(const StylusOverTravel& o);

/// A drive latched a probe input's edge (fast-measurement 7.3): the drive and the axis' name,
/// PIN4 / PIN5, the edge, the measured value (S-0-0130..0133: the position of the sampling tick)
/// beside the exact position at the switch's change and their difference, the sampling error
/// (up to feed x 250 µs), in mm to the nanometre.
nlohmann::ordered_json ProbeLatchEvent(double t, const std::string& drive, int pin, bool positive,
                                       const control::ProbeEdgeLatch& latch);

/// The REPOS screen: the function and its status signals, per feed axis final value, command
/// value and distance to go with its adjust symbol, the spindle, F, T, M and G state.
nlohmann::ordered_json ReposEvent(double t, const control::channel::ReposStatus& s);

/// What of the REPOS screen is worth an event when it changes: the function, the status
/// signals and the adjust symbols (not every cycle's command values).
/// Written into `key` (its storage kept from cycle to cycle).
void ReposEventKey(const control::channel::ReposStatus& s, std::string& key);

/// Block search (twincat-cnc-block-search-de.md 5.6): a change of its state HLI_BS_*, with the
/// status the PLC reads then (line count, distance from program start, the continue position
/// per channel axis and the actual's deviation from it); `warning` for a warning of the search.
nlohmann::ordered_json BlockSearchEvent(double t, const control::channel::Channel& channel,
                                        const std::string& warning = {});

}  // namespace vmt::sim
