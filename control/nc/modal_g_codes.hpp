#pragma once
// The G codes that only select a modal state (a plane, a zero offset, radius or diameter
// programming, ...), in one place: the interpreter applies them to a block, and a channel's
// start-up state (the scene's `nc: initial:`) is written in the same words.

#include <string>
#include <string_view>
#include <vector>

#include "control/nc/interpreter.hpp"

namespace vmt::control::nc {

/// Sets the modal group that G`g` selects and returns true, or returns false when `g` is not a
/// purely modal code (a motion, a transformation that needs the axes' positions, a one-block
/// function like G04 or G92, or no G code at all).
bool SetModalG(int g, ModalState& m);

/// Applies one start-up word to `m`: a purely modal G code (G53..G59, G47..G49, G15/G16,
/// G90/G91, G94/G95, G05/G06, G17..G19, G30, G40) or a tool (Tn) or correction (Dn) number.
/// Returns why the word cannot start a channel, or empty. A start-up state has no block to
/// move in, so tool radius compensation (G41/G42) and the transformations that need an axis
/// position are refused rather than set half-way.
std::string ApplyInitialWord(std::string_view word, ModalState& m);

/// The G codes in force, one per modal group as the operator is shown them: motion (G00..G03,
/// G33, G63, G64), plane, tool radius compensation, tool length, zero offset, G90/G91,
/// G94/G95, and G31/G32 while a transformation is on.
std::vector<int> ActiveGCodes(const ModalState& m);

}  // namespace vmt::control::nc
