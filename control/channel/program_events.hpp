#pragma once
// The program's events (BES / BEC read them, SE n / RE n set them): where they come from (the
// gateway's Pxx.EVn), where the program's own go, and the ones it set itself.

#include <functional>
#include <map>

namespace vmt::control::channel {

struct ProgramEvents {
  std::function<bool(int)> source;      ///< none: the events the program set itself
  std::function<void(int, bool)> sink;  ///< SE n / RE n
  std::map<int, bool> own;
};

}  // namespace vmt::control::channel
