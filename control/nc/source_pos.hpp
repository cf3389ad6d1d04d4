#pragma once
// Where a thing stands in an NC program file, and the errors that point there.

#include <cstdint>
#include <string>
#include <vector>

namespace vmt::control::nc {

struct SourcePos {
  uint32_t file = 0;    ///< index into Program::files
  uint32_t line = 0;    ///< 1-based
  uint32_t column = 0;  ///< 1-based, in bytes
  uint32_t offset = 0;  ///< byte offset of the position in the file (block search type 1)
};

/// An error in an NC program, printed `file:line:column: error: message`.
struct Diagnostic {
  SourcePos pos;
  std::string message;
};

std::string Format(const Diagnostic& d, const std::vector<std::string>& files);

}  // namespace vmt::control::nc
