#pragma once
// What the operator station's HTTP servers do alike (cpp-httplib): JSON answers and errors, the
// token every request carries off loopback, and binding. Private to sim/station.

#include <httplib.h>

#include <string>

namespace vmt::sim::station {

void Reply(httplib::Response& res, int status, const std::string& body);
/// {"error": error} with `status`.
void Fail(httplib::Response& res, int status, const std::string& error);

/// Throws std::invalid_argument for an address other than loopback without a token.
void CheckAccess(const std::string& host, const std::string& token);
/// With a token, every request must carry it (Bearer, ?token= or the cookie ?token= sets);
/// others get 401.
void RequireToken(httplib::Server& http, const std::string& token);
/// Binds (port 0: a free one) and returns the port; throws std::runtime_error.
int Bind(httplib::Server& http, const std::string& host, int port);

}  // namespace vmt::sim::station
