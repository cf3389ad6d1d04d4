#pragma once
// Per channel axis, what lies between the program's coordinates and the axis' (the zero
// offset, tool length and G92 shift as one translation, the G92 shift on its own) and whether
// the axis has its reference.

#include <vector>

#include "control/axes/tool_table.hpp"
#include "control/axes/zero_offsets.hpp"
#include "control/nc/interpreter.hpp"

namespace vmt::control::channel {

struct ChannelConfig;

struct ProgramFrames {
  std::vector<double> translation;  ///< axis = program + translation
  std::vector<double> shift;        ///< G92's part of it
  std::vector<bool> homed;
};

/// The tool edge whose lengths `modal` applies (G47 none; T0 / D0 none); null also for one
/// the tool list does not hold.
const axes::ToolEdge* ActiveEdge(const axes::ToolTable& tools, const nc::ModalState& modal);

/// Into `translation` (one per channel axis of `config`), the translation program -> axis of
/// `modal` with the zero offsets `zero_offsets` as they are now, the G92 shift `shift` and `edge`'s
/// lengths (ActiveEdge): the zero offset, plus the shift, less the length (G48 adds the edge's
/// lengths to the tool's reach, G49 subtracts them). Written in place: a block's start sets it
/// without allocating.
void TranslationOf(const ChannelConfig& config, const axes::ZeroOffsetTable& zero_offsets,
                   const std::vector<double>& shift, const nc::ModalState& modal,
                   const axes::ToolEdge* edge, std::vector<double>& translation);

}  // namespace vmt::control::channel
