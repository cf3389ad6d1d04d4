#pragma once
// The signal catalog (signal_catalog.hpp) in pieces by manual, for the catalog's own .cpp files:
// the manual files its sources name, and the pieces signal_catalog.cpp joins in the table's order
// (the order gives the signals their addresses).

#include <span>

#include "control/gateway/signal_catalog.hpp"

// Manual files; string-literal macros so that "file section" concatenates at compile time.
#define REPOS "mtc200-repositioning-and-nc-block-restart.md "
#define CAXIS "mtc200-c-axis.md "
#define FMEAS "mtc200-fast-measurement.md "
#define BSRCH "twincat-cnc-block-search-de.md "

namespace vmt::control::gateway::catalog {

/// Block search of the ISG kernel (signal_catalog_block_search.cpp): CNC objects and HLI elements.
std::span<const SignalFamily> BlockSearchFamilies();
/// Their block search states, stop conditions and block search types.
std::span<const ValueName> BlockSearchValues();

/// The fast-measurement function block QMFB1Axx (signal_catalog_measuring.cpp): its pins.
std::span<const SignalFamily> MeasuringFamilies();
/// Its error numbers.
std::span<const ValueName> MeasuringValues();

}  // namespace vmt::control::gateway::catalog
