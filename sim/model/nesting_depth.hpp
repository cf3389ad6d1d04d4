#pragma once
// How deep a text nests, found by a cheap scan before a recursive parser sees it. urdfdom's XML
// parser and yaml-cpp recurse once per nested element: 50,000 nested elements overflow the
// stack (SIGSEGV), so a loader refuses such a text with its line instead.

#include <string_view>

namespace vmt::sim {

/// Deepest nesting a model or scene file may have (XML elements, YAML collections). The shipped
/// files nest at most 8 deep.
inline constexpr int kMaxNestingDepth = 100;

/// The line (1-based) where the element nesting of an XML text first goes deeper than `limit`,
/// or 0 if it never does. Comments, CDATA, processing instructions, declarations and
/// self-closing tags do not nest.
int XmlNestingBeyond(std::string_view text, int limit);

/// The line (1-based) where the nesting of a YAML text (block indentation, `- ` entries, flow
/// `[` and `{`) first goes deeper than `limit`, or 0 if it never does. Quoted scalars, comments
/// and block scalars (`|`, `>`) do not nest. The count can only err on the deep side of
/// indentation-only nesting, never hide flow nesting.
int YamlNestingBeyond(std::string_view text, int limit);

}  // namespace vmt::sim
