#pragma once
// What the two dialect front ends share: each reads one line into one block (or none, for an
// empty or comment-only line).

#include <string_view>
#include <vector>

#include "control/nc/expression_parser.hpp"
#include "control/nc/program.hpp"

namespace vmt::control::nc {

/// Returns false when the line holds no block (blank or comment only). `expr` holds the program
/// and its errors; one serves all lines of a program.
bool ParseMtc200Line(std::string_view line, SourcePos start, ExpressionParser& expr, Block& block);
bool ParseIsgLine(std::string_view line, SourcePos start, ExpressionParser& expr, Block& block);

/// The start of a block: '/' (block skip) and an N number, both optional.
void ReadBlockStart(LineScanner& s, Block& block);

/// Reads an address word's value after its letters (and index) at the scanner into `word`: a
/// number (kept in word.number), or '=' expression, a variable, a bracketed expression (into
/// word.value). False after an error.
bool ParseWordValue(LineScanner& s, ExpressionParser& expr, const std::string& address,
                    SourcePos address_pos, Word& word);
bool MoreExpression(LineScanner s);

}  // namespace vmt::control::nc
