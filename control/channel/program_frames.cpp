#include "control/channel/program_frames.hpp"

#include "control/channel/channel_config.hpp"

namespace vmt::control::channel {

const axes::ToolEdge* ActiveEdge(const axes::ToolTable& tools, const nc::ModalState& modal) {
  if (modal.tool_length == nc::ToolLength::kOff || modal.correction == 0) return nullptr;
  return tools.Edge(modal.tool, modal.correction);
}

void TranslationOf(const ChannelConfig& config, const axes::ZeroOffsetTable& zero_offsets,
                   const std::vector<double>& shift, const nc::ModalState& modal,
                   const axes::ToolEdge* edge, std::vector<double>& translation) {
  const double sign = modal.tool_length == nc::ToolLength::kSubtract ? -1 : 1;
  translation.resize(config.axes.size());
  for (size_t a = 0; a < translation.size(); ++a) {
    const double length = edge ? edge->Length(a, config.axes[a].name) : 0;
    translation[a] = zero_offsets.Offset(modal.zero_offset, a) + shift[a] - sign * length;
  }
}

}  // namespace vmt::control::channel
