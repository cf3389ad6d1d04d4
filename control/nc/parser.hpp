#pragma once
// NC program text -> Program (blocks with source positions) + errors. Lex and parse per line in
// the dialect's front end, then check the whole: labels, branch targets, $-structures.

#include <string>
#include <string_view>

#include "control/nc/program.hpp"

namespace vmt::control::nc {

/// The dialect a file is written in: by extension (.mtc | .isg), else by its first block
/// (% header, $ or # statements -> ISG; @ variables, .LABELs, 4-digit N numbers -> MTC200).
Dialect DetectDialect(std::string_view text, std::string_view file_name);

/// Parses a whole program. Never throws on bad input: every fault is a Diagnostic, and parsing
/// goes on with the next block so that one run reports all of them.
ParseResult ParseProgram(std::string_view text, const std::string& file_name, Dialect dialect);

/// Reads a file; an unreadable file is a diagnostic at 0:0.
ParseResult ParseFile(const std::string& path, Dialect dialect);

}  // namespace vmt::control::nc
