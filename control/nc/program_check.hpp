#pragma once
// Whole-program checks after parsing: label definitions and branch/call targets (MTC200),
// matching $IF/$ELSEIF/$ELSE/$ENDIF, $FOR/$ENDFOR, $WHILE/$ENDWHILE (ISG). Resolves
// Statement::jump so that execution needs no searching.

#include <vector>

#include "control/nc/program.hpp"

namespace vmt::control::nc {

void CheckProgram(Program& program, std::vector<Diagnostic>& errors);

}  // namespace vmt::control::nc
