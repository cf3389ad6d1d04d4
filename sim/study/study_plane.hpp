#pragma once
// The XZ plane of a study's report (inline SVG): Z to the right, X up, one scale for both, in
// machine coordinates (the axes' positions, mm) with ticks on both axes. The program's tool
// path from the reference run (the contour as turned), the chuck's parts as the envelopes they
// sweep, every case's approach path coloured by its class, a dot where the tool stood at a
// first contact and a cross at the contact point.

#include <string>
#include <vector>

#include "sim/study/case_runner.hpp"
#include "sim/study/reference_run.hpp"

namespace vmt::sim::study {

/// The colour of a class (ClassOf) in the report.
const char* ClassColour(const std::string& cls);

/// A "nice" tick step (1, 2 or 5 times a power of ten) for about `ticks` ticks over `span`.
double TickStep(double span, int ticks);

/// `reference` may be null. `href`: the link of a case's path (its replay), by case id.
std::string PlaneSvg(const std::vector<const CaseResult*>& cases, const Reference* reference,
                     std::string (*href)(const std::string& case_id));

/// Text as HTML (< > & " escaped).
std::string Esc(const std::string& s);

}  // namespace vmt::sim::study
