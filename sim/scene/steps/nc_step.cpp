// `nc: ...`: the operator at the NC's panel: start, stop, reset, reverse, the mode, the feed
// override, single block, optional stop, jog mode and increment, MDI blocks, program selection,
// and the edits of zero offsets and tool lengths while a program is interrupted.
#include <filesystem>

#include "control/channel/channel.hpp"
#include "sim/model/yaml_reader.hpp"
#include "sim/scene/scene_steps.hpp"
#include "sim/scene/steps/step_kind.hpp"

namespace vmt::sim {
namespace {

void Read(const StepSource& src, TimelineStep& s, std::ostringstream& text) {
  const NcSetup& nc = src.nc;
  const YamlNode a = src.n["nc"];
  if (!nc.present) a.Fail("the scene has no nc: section");
  if (a.IsMap() && a.Has("mode")) {
    a.AllowKeys({"mode"});
    s.kind = TimelineStep::Kind::kNcMode;
    const std::string mode = a["mode"].String();
    using control::channel::ChannelMode;
    if (mode == "manual")
      s.code = static_cast<int>(ChannelMode::kManual);
    else if (mode == "automatic")
      s.code = static_cast<int>(ChannelMode::kAutomatic);
    else if (mode == "mdi")
      s.code = static_cast<int>(ChannelMode::kMdi);
    else
      a["mode"].Fail("expected automatic, manual or mdi");
    text << "mode " << mode;
  } else if (a.IsMap() && a.Has("jog_mode")) {
    // PxxC.JOGM0..2 as a code 0..7 (control/channel/channel.hpp JogMode).
    a.AllowKeys({"jog_mode"});
    s.kind = TimelineStep::Kind::kNcJogMode;
    s.code = a["jog_mode"].Int();
    if (s.code < 0 || s.code > 7) a["jog_mode"].Fail("must be 0..7 (JOGM0..2)");
    text << "jog mode " << s.code;
  } else if (a.IsMap() && a.Has("mdi")) {
    a.AllowKeys({"mdi"});
    s.kind = TimelineStep::Kind::kNcMdi;
    s.mdi = a["mdi"].String();
    text << "MDI " << s.mdi;
  } else if (a.IsMap() && a.Has("select")) {
    // Program selection by name, as the operator picks a program from the NC's store: the
    // file name, with or without its extension, of the scene's program or subprograms.
    a.AllowKeys({"select"});
    s.kind = TimelineStep::Kind::kNcSelect;
    const std::string name = a["select"].String();
    s.code = -1;
    for (size_t k = 0; k < nc.programs.size(); ++k) {
      const std::filesystem::path file(nc.programs[k]->program.files.at(0));
      if (file.filename() != name && file.stem() != name) continue;
      if (s.code >= 0) a["select"].Fail("names more than one of the scene's NC programs");
      s.code = static_cast<int>(k);
    }
    if (s.code < 0)
      a["select"].Fail("is none of the scene's NC programs (nc: program, subprograms)");
    text << "select " << name;
  } else if (a.IsMap() && a.Has("jog_increment")) {
    a.AllowKeys({"jog_increment"});
    s.kind = TimelineStep::Kind::kNcJogIncrement;
    s.target = a["jog_increment"].Double();
    if (s.target < 0) a["jog_increment"].Fail("must be >= 0 (0: continuous)");
    text << "jog increment " << Fmt(s.target);
  } else if (a.IsMap() && (a.Has("zero_offset") || a.Has("tool_length"))) {
    // The operator's edits while a program is interrupted (repositioning manual 2.5).
    const bool offset = a.Has("zero_offset");
    a.AllowKeys({offset ? "zero_offset" : "tool_length"});
    const YamlNode e = a[offset ? "zero_offset" : "tool_length"];
    if (offset)
      e.AllowKeys({"G", "axis", "value"});
    else
      e.AllowKeys({"T", "D", "axis", "value"});
    s.kind = offset ? TimelineStep::Kind::kNcZeroOffset : TimelineStep::Kind::kNcToolLength;
    s.axis = RequireChannelAxis(src.m, nc, e["axis"]);
    s.target = e["value"].Double();
    if (offset) {
      s.code = e["G"].Int();
      if (s.code < 54 || s.code > 59) e["G"].Fail("expected 54..59");
      text << "zero offset G" << s.code << " " << e["axis"].String() << " = " << Fmt(s.target);
    } else {
      s.code = e["T"].Int();
      s.edge = e.Has("D") ? e["D"].Int() : 1;
      text << "tool T" << s.code << " D" << s.edge << " length " << e["axis"].String() << " = "
           << Fmt(s.target);
    }
  } else if (a.IsMap() && a.Has("single_block")) {
    a.AllowKeys({"single_block"});
    s.kind = TimelineStep::Kind::kNcSingleBlock;
    s.level = a["single_block"].Bool();
    text << "single block " << (s.level ? "on" : "off");
  } else if (a.IsMap() && a.Has("optional_stop")) {
    a.AllowKeys({"optional_stop"});
    s.kind = TimelineStep::Kind::kNcOptionalStop;
    s.level = a["optional_stop"].Bool();
    text << "optional stop " << (s.level ? "on" : "off");
  } else if (a.IsMap()) {
    a.AllowKeys({"override"});
    s.kind = TimelineStep::Kind::kNcOverride;
    s.target = a["override"].Double() / 100;
    if (s.target < 0 || s.target > 2) a["override"].Fail("must be 0..200 (percent)");
    text << "feed override " << Fmt(s.target * 100) << " %";
  } else {
    const std::string cmd = a.String();
    if (cmd == "start")
      s.kind = TimelineStep::Kind::kNcStart;
    else if (cmd == "stop")
      s.kind = TimelineStep::Kind::kNcStop;
    else if (cmd == "reset")
      s.kind = TimelineStep::Kind::kNcReset;
    else if (cmd == "reverse")
      s.kind = TimelineStep::Kind::kNcReverse;
    else
      a.Fail(
          "expected start, stop, reset, reverse, {mode: ..}, {override: percent}, "
          "{single_block: bool}, {optional_stop: bool}, {jog_increment: mm}, {jog_mode: 0..7} or {mdi: blocks}");
    text << "NC " << cmd;
  }
}

// A request the channel refuses is a failure of the run (`failure` appended to the step's
// text), shown as a "refused" event; the run goes on.
void Refused(const TimelineStep& s, const StepTick& tick, TimelinePlay& play,
             const std::string& failure) {
  play.failures.push_back(s.text + failure);
  tick.events.push_back({tick.t_s, "refused", s.text});
}

bool Play(const TimelineStep& s, const StepTick& tick, TimelinePlay& play) {
  control::channel::Channel* channel = play.channel;
  if (!channel) return true;
  using Kind = TimelineStep::Kind;
  switch (s.kind) {
    case Kind::kNcStart:
      channel->Start();
      break;
    case Kind::kNcStop:
      channel->Stop();
      break;
    case Kind::kNcReset:
      channel->Reset();
      break;
    case Kind::kNcOverride:
      channel->SetFeedOverride(s.target);
      break;
    case Kind::kNcSingleBlock:
      channel->SetSingleBlock(s.level);
      break;
    case Kind::kNcOptionalStop:
      channel->SetOptionalStop(s.level);
      break;
    case Kind::kNcMode:
      if (!channel->SetMode(static_cast<control::channel::ChannelMode>(s.code)))
        Refused(s, tick, play, ": refused while the program runs");
      break;
    case Kind::kNcJogIncrement:
      channel->SetJogIncrement(s.target);
      break;
    case Kind::kNcJogMode:
      channel->SetJogMode(s.code);
      break;
    case Kind::kNcMdi:
      if (!channel->Mdi(s.mdi)) tick.events.push_back({tick.t_s, "refused", s.text});
      break;
    case Kind::kNcSelect:
      if (!channel->SelectProgram(static_cast<size_t>(s.code)))
        Refused(s, tick, play, ": refused while a program is active");
      break;
    case Kind::kNcReverse:
      if (!channel->Reverse())
        Refused(s, tick, play,
                ": refused (" +
                    (channel->error().empty() ? "not interrupted" : channel->error()) + ")");
      break;
    case Kind::kNcZeroOffset:
      if (!channel->SetZeroOffset(s.code, s.axis, s.target))
        Refused(s, tick, play, ": the tool list has no such edge");
      break;
    case Kind::kNcToolLength:
      if (!channel->SetToolLength(s.code, s.edge, s.axis, s.target))
        Refused(s, tick, play, ": the tool list has no such edge");
      break;
    default:
      break;
  }
  return true;
}

}  // namespace

const StepKind kNcStep{"nc", Read, Play};

}  // namespace vmt::sim
