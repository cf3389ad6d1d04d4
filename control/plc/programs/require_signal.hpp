#pragma once
// Programs resolve their signals by name when they are made; a machine without one of them
// cannot run the program, which is the scene's error, not a crash.

#include <stdexcept>
#include <string>
#include <string_view>

#include "control/gateway/signal_image.hpp"

namespace vmt::control::plc {

inline int RequireSignal(const gateway::SignalImage& image, std::string_view name) {
  const int id = image.Find(name);
  if (id < 0)
    throw std::invalid_argument("the machine has no signal " + std::string(name) +
                                ", which the PLC program needs");
  return id;
}

}  // namespace vmt::control::plc
