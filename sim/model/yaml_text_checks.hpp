#pragma once
// Checks of a scene or machine file that yaml-cpp does not make: the text is UTF-8, every map
// key is a plain name given once, and yaml-cpp's own error texts read as the reason for a user.

#include <yaml-cpp/yaml.h>

#include <string>

namespace vmt::sim {

/// Throws ModelError `file:line:col: not UTF-8 text ...` at the first byte that is not UTF-8.
void CheckUtf8Text(const std::string& file, const std::string& text);

/// Throws ModelError at the first key that is not a plain name (a list, a map, null) or that
/// its map repeats; the message names both places of a repeated key.
void CheckMapKeys(const std::string& file, const YAML::Node& root);

/// A yaml-cpp parser exception as `file:line:col: YAML syntax error: reason`.
std::string YamlSyntaxError(const std::string& file, const YAML::Exception& e);

}  // namespace vmt::sim
