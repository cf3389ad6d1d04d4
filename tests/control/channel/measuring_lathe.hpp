#pragma once
// An ideal lathe whose X drive latches the stylus' contact (fast-measurement 7.3), with a
// stand-in for the PLC's measuring block QMFB1Axx on the events (6.2): it acknowledges event 30
// by resetting event 29, and reports the contact with event 7.

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "control/measure/measuring_pages.hpp"
#include "tests/control/channel/channel_test_support.hpp"

namespace vmt::control::channel::testing {

constexpr double kSphereRadius = 3;

/// The lathe with the stylus T3 (sphere 1: r 3, tool lengths 0) and a part whose surface is at
/// radius `surface` in X: the X drive latches where the sphere meets it.
struct MeasuringLathe {
  MeasuringLathe(const std::string& program, double surface, double x = 50, double z = 5,
                 const std::function<void(ChannelConfig&)>& configure = {})
      : m(program, x, z,
          [&](ChannelConfig& c) {
            c.tools.edges = {{1, 1, {0, 0}, 0.8, 3}, {3, 1, {0, 0}, kSphereRadius, 0}};
            c.aux_handshake = true;
            if (configure) configure(c);
          }),
        surface(surface) {
    pages.stylus[0].tool_number = 3;
    pages.stylus[0].sphere_radius[0] = kSphereRadius;
    m.channel->SetMeasuringPages(&pages);
    m.channel->SetEventSource([this](int n) { return events[n]; });
    m.channel->SetEventSink([this](int n, bool set) {
      events[n] = set;
      if (set) raised.push_back(n);
    });
  }

  /// One drive tick, with the PLC's part: acknowledge Q functions, event 30 -> reset event 29,
  /// and the X drive's latch armed while event 30 is set.
  void Tick() {
    if (!m.channel->aux_output().empty()) {
      for (const nc::AuxFunction& f : m.channel->aux_output()) q_functions.push_back(f.value);
      m.channel->AcknowledgeAux();
    }
    if (events[30] && events[29]) events[29] = false;
    if (!events[30]) m.at.feedback[0].probe = {};
    if (probe_level) m.at.feedback[0].probe.probe1.level = *probe_level;
    const double x_before = m.X();
    m.Tick();
    ProbeEdgeLatch& latch = m.at.feedback[0].probe.probe1.positive;
    const double touch = surface + kSphereRadius;
    if (events[30] && !latch.latched && x_before > touch && m.X() <= touch) {
      latch.latched = true;
      latch.measured_value = touch;  // an exact latch: the sampling error is the drive's test
      latch.exact_position = touch;
    }
    // Event 7: the contact on the measuring path, reported while event 30 is set; cleared
    // with the next measurement's event 30.
    if (events[30] && latch.latched) events[7] = true;
    if (events[30] && !events_30_before) events[7] = false;
    events_30_before = events[30];
  }
  void RunUntilStopped(double limit = 30) {
    while (m.channel->state() == ChannelState::kRunning && m.t < limit) Tick();
  }

  Machine m;
  double surface;
  measure::MeasuringPages pages;
  std::map<int, bool> events;
  std::vector<int> raised;
  std::vector<double> q_functions;
  bool events_30_before = false;
  /// The X drive's S-0-0401 'Probe-1' as the test sets it (none: as the latch leaves it).
  std::optional<bool> probe_level;
};

}  // namespace vmt::control::channel::testing
