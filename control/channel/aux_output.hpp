#pragma once
// The auxiliary functions (M, H, Q, T) of the block in work that wait for the PLC's
// acknowledgement, and the strobe that counts each new output of them.

#include <cstdint>
#include <vector>

#include "control/nc/interpreter.hpp"

namespace vmt::control::channel {

struct AuxOutput {
  std::vector<nc::AuxFunction> functions;
  uint32_t strobe = 0;
};

}  // namespace vmt::control::channel
