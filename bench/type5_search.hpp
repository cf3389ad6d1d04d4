#pragma once
// Block search type 5 (twincat-cnc-block-search-de.md 3.4: decode to the program end, no
// interpolation) through a bare three-axis channel, as block_search_bench and search_program
// run it: no machine, no PLC, so what is timed is the search itself.

#include <string>
#include <vector>

#include "control/channel/channel.hpp"
#include "control/nc/parser.hpp"

namespace vmt::bench {

struct Type5Result {
  std::string error;           ///< empty when the search reached the program end
  uint64_t decoder_lines = 0;  ///< block_count_r at the end: loop and subprogram lines each pass
};

inline control::channel::ChannelAxis Type5Axis(const std::string& name, int drive) {
  control::channel::ChannelAxis a;
  a.name = name;
  a.number = drive + 1;
  a.drive = drive;
  a.rapid_per_s = 500;
  a.acceleration = 4000;
  return a;
}

/// Runs one type-5 search over `programs` (the first is the main program) to the program end.
inline Type5Result RunType5Search(const std::vector<const control::nc::Program*>& programs) {
  using namespace vmt::control;
  channel::ChannelConfig config;
  config.axes = {Type5Axis("X", 0), Type5Axis("Y", 1), Type5Axis("Z", 2)};
  channel::BlockSearchParameters p;
  p.type = channel::BlockSearchType::kProgramEnd;
  channel::Channel ch(config, programs);
  AmplifierTelegram at;
  MasterTelegram mdt;
  at.feedback.resize(3);
  for (DriveFeedback& f : at.feedback) f.status = drive_status::kReady;
  mdt.setpoints.resize(3);
  ch.SetBlockSearch(p);
  ch.Start();
  while (ch.state() != channel::ChannelState::kEnded && ch.state() != channel::ChannelState::kError)
    ch.Tick(at, mdt);
  Type5Result r;
  if (ch.state() == channel::ChannelState::kError) r.error = ch.error();
  r.decoder_lines = ch.block_search().block_count;
  return r;
}

}  // namespace vmt::bench
