#pragma once
// Per channel axis, what lies between the program's coordinates and the axis' (the zero
// offset, tool length and G92 shift as one translation, the G92 shift on its own) and whether
// the axis has its reference.

#include <vector>

namespace vmt::control::channel {

struct ProgramFrames {
  std::vector<double> translation;  ///< axis = program + translation
  std::vector<double> shift;        ///< G92's part of it
  std::vector<bool> homed;
};

}  // namespace vmt::control::channel
