#pragma once
// An NC-controlled tool storage axis between NC cycles (REPOS manual 3.4, 4.2): its command,
// the jog key, and the program's traverse (a T word's indexing, MTP) with its target.

namespace vmt::control::channel {

struct ToolStorageAxis {
  bool taken = false;  ///< its command taken from the feedback at the first NC cycle
  double command = 0, previous = 0;
  int key = 0;
  double velocity = 0;
  /// A program traverse to `target` at the jogging rapid, asynchronous to the other axes:
  /// a T word's indexing, MTP (REPOS manual 4.2).
  bool positioning = false;
  /// The last traverse was the program's (T, MTP): MRY waits until the drive stands at
  /// `target`, after the command got there too. A jog since has made `target` a jog's.
  bool programmed = false;
  bool stepping = false;  ///< an increment of a jog key press: to `target`
  double target = 0;
  int blocked = 0;  ///< PathGuard stopped the jog key in this direction: until released
};

}  // namespace vmt::control::channel
