#pragma once
// Writing JSON whose strings come from outside (file and scene names, NC and PLC message texts,
// command-line values): a byte that is not UTF-8 is written as U+FFFD instead of throwing in
// the middle of writing a file, after the work is done.

#include <nlohmann/json.hpp>

namespace vmt::common {

inline constexpr auto kReplaceBadUtf8 = nlohmann::json::error_handler_t::replace;

}  // namespace vmt::common
