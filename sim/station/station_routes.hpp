#pragma once
// The operator station's routes on an httplib::Server, apart from binding it: StationServer
// serves them on a socket; the station's fuzz target and unit tests feed requests to them in
// memory. Private to sim/station (and its tests).

#include <httplib.h>

#include "sim/station/station_hub.hpp"
#include "sim/station/station_server.hpp"

namespace vmt::sim::station {

/// The page's files (o.web_dir, three.js, Chart.js), the JSON API, the token check and the
/// request size limit, answering from `hub`; `hub` must outlive `http`.
void RouteStation(httplib::Server& http, StationHub& hub, const StationServerOptions& o);

}  // namespace vmt::sim::station
