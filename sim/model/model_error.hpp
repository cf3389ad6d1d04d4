#pragma once
#include <stdexcept>
#include <string>

namespace vmt::sim {

/// Bad model or scene input: the message names the file and the YAML path (or URDF element).
class ModelError : public std::runtime_error {
 public:
  ModelError(const std::string& file, const std::string& where, const std::string& what)
      : std::runtime_error(file + ": " + (where.empty() ? "" : where + ": ") + what) {}
  /// A message that already names its place.
  explicit ModelError(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace vmt::sim
