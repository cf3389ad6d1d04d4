#pragma once
// What a run did, told in a few sentences for whoever started it: the NC program's course,
// what the operator did, repositioning, what PLC and NC reported, what PathGuard checked and
// refused, and drive trips. Read from the run's events (events.jsonl),
// so that a finished run's folder tells the same story.

#include <istream>
#include <string>
#include <vector>

namespace vmt::sim {

/// One line per thing that happened, in plain words; empty for a run with nothing to tell.
/// Lines that are not JSON objects are skipped.
std::vector<std::string> RunStory(std::istream& events_jsonl);

}  // namespace vmt::sim
