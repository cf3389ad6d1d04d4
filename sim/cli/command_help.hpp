#pragma once
// What the vmt command says beyond its options: one example per subcommand at the end of its
// --help, and the nearest subcommand when a name is mistyped.

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace vmt::sim {

/// Appends "Example:" with a command line to the help of each subcommand of `app` (nested ones
/// too) that has one.
void AddExamples(CLI::App& app);

/// The subcommand path a command line names ("study", "repos"), stopping at the first word that
/// is an option or not a subcommand. When that word is a mistyped subcommand, `unknown` gets it
/// and `suggestion` the nearest name (empty when none is near).
struct CommandWords {
  std::vector<std::string> path;
  std::string unknown;
  std::string suggestion;
};
CommandWords ReadCommandWords(CLI::App& app, const std::vector<std::string>& args);

/// Edit distance (insertions, deletions, substitutions, transpositions of neighbours).
int EditDistance(const std::string& a, const std::string& b);

}  // namespace vmt::sim
