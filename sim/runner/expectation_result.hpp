#pragma once
// One of the scene's expectations as the run found it.

#include <string>

namespace vmt::sim {

struct ExpectationResult {
  std::string text;
  bool passed = false;
  std::string detail;  ///< "got 249.9876"
};

}  // namespace vmt::sim
