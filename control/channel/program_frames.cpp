#include "control/channel/program_frames.hpp"

#include "control/channel/channel_config.hpp"

namespace vmt::control::channel {

std::optional<axes::ToolEdge> ActiveEdge(const ChannelConfig& config, const nc::ModalState& modal) {
  if (modal.tool_length == nc::ToolLength::kOff || modal.correction == 0) return std::nullopt;
  return config.tools.Find(modal.tool, modal.correction);
}

std::vector<double> TranslationOf(const ChannelConfig& config, const std::vector<double>& shift,
                                  const nc::ModalState& modal,
                                  const std::optional<axes::ToolEdge>& edge) {
  const double sign = modal.tool_length == nc::ToolLength::kSubtract ? -1 : 1;
  std::vector<double> t(config.axes.size());
  for (size_t a = 0; a < t.size(); ++a) {
    const double length = edge ? edge->Length(a, config.axes[a].name) : 0;
    t[a] = config.zero_offsets.Offset(modal.zero_offset, a) + shift[a] - sign * length;
  }
  return t;
}

}  // namespace vmt::control::channel
