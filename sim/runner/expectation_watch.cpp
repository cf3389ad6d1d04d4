#include "sim/runner/expectation_watch.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace vmt::sim {
namespace {

std::string Seconds(double t_s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g s", t_s);
  return buf;
}

double Measured(const Expectation& e, const ExpectationInputs& in) {
  using Q = Expectation::Quantity;
  switch (e.quantity) {
    case Q::kSignal:
      return in.image ? in.image->Number(e.index) : std::nan("");
    case Q::kPosition:
      return in.at.feedback[e.index].position;
    case Q::kVelocity:
      return in.at.feedback[e.index].velocity;
    case Q::kRpm:
      return in.at.feedback[e.index].velocity / 6.0;
    case Q::kFollowingError:
      return in.at.feedback[e.index].following_error;
    case Q::kParameterSet:
      return in.at.feedback[e.index].parameter_set;
    case Q::kInput:
      return in.at.inputs[e.index];
    case Q::kClutch:
      return static_cast<double>(in.clutches[e.index]);
    case Q::kNc:
    case Q::kDriveTrip:
      return 0;  // a state, compared in CheckValue; the trips so far, in CheckTrip
  }
  return 0;
}

// `{drive:, trip:}`: has the drive tripped, for one of the causes meant, by now?
ExpectationResult CheckTrip(const Expectation& e, const std::vector<DriveTrip>& trips,
                            const MachineModel& m) {
  for (const DriveTrip& trip : trips)
    if (trip.drive == e.index && (trip.faults & e.trip))
      return {e.text, true, "tripped: " + TripCauses(trip.faults) + " at " + Seconds(trip.t_s)};
  return {e.text, false, "drive " + m.drives[e.index].info.name + " has not tripped"};
}

ExpectationResult CheckValue(const Expectation& e, const ExpectationInputs& in) {
  ExpectationResult r{e.text, false, ""};
  const double got = Measured(e, in);
  if (e.quantity == Expectation::Quantity::kNc) {
    r.passed = in.channel && in.channel->state() == e.nc;
    r.detail = std::string("got ") + (in.channel ? ToString(in.channel->state()) : "no channel");
    if (in.channel && !in.channel->error().empty()) r.detail += ": " + in.channel->error();
  } else if (e.quantity == Expectation::Quantity::kClutch) {
    r.passed = in.clutches[e.index] == e.clutch;
    r.detail = std::string("got ") + ToString(in.clutches[e.index]);
  } else {
    r.passed = std::abs(got - e.value) <= e.tolerance;
    char buf[64];
    std::snprintf(buf, sizeof buf, "got %.6f", got);
    r.detail = buf;
  }
  return r;
}

}  // namespace

ExpectationWatch::ExpectationWatch(const std::vector<Expectation>& expectations,
                                   const MachineModel& m)
    : expectations_(&expectations),
      m_(&m),
      checked_(expectations.size(), false),
      results_(expectations.size()) {}

void ExpectationWatch::Check(double t, bool last_tick, const ExpectationInputs& in,
                             RunRecorder& recorder) {
  if (!Due(t, last_tick)) return;
  next_s_ = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < expectations_->size(); ++i) {
    const Expectation& e = (*expectations_)[i];
    const bool due = e.at_s < 0 ? last_tick : t >= e.at_s - 1e-9;
    if (!checked_[i] && !due && e.at_s >= 0) next_s_ = std::min(next_s_, e.at_s);
    if (checked_[i] || !due) continue;
    checked_[i] = true;
    results_[i] = e.quantity == Expectation::Quantity::kDriveTrip ? CheckTrip(e, in.trips, *m_)
                                                                  : CheckValue(e, in);
    recorder.Event({{"t", t},
                    {"event", "expectation"},
                    {"text", e.text},
                    {"passed", results_[i].passed},
                    {"detail", results_[i].detail}});
  }
}

const std::vector<ExpectationResult>& ExpectationWatch::Close() {
  for (size_t i = 0; i < results_.size(); ++i)
    if (!checked_[i])
      results_[i] = {(*expectations_)[i].text, false, "not reached: the run ended first"};
  return results_;
}

std::vector<std::string> ExpectationWatch::NotHeld() const {
  std::vector<std::string> failures;
  for (const ExpectationResult& r : results_)
    if (!r.passed) failures.push_back(r.text + " (" + r.detail + ")");
  return failures;
}

std::vector<std::string> ExpectationWatch::Unexpected(const std::vector<DriveTrip>& trips,
                                                      const std::string& channel_error) const {
  std::vector<std::string> failures;
  if (!channel_error.empty()) {
    bool expected = false;
    for (const Expectation& e : *expectations_)
      expected = expected || (e.quantity == Expectation::Quantity::kNc &&
                              e.nc == control::channel::ChannelState::kError);
    if (!expected) failures.push_back("NC error: " + channel_error);
  }
  for (const DriveTrip& trip : trips) {
    uint32_t expected = 0;
    for (const Expectation& e : *expectations_)
      if (e.quantity == Expectation::Quantity::kDriveTrip && e.index == trip.drive)
        expected |= e.trip;
    if (const uint32_t unexpected = trip.faults & ~expected) {
      const std::string& name = m_->drives[trip.drive].info.name;
      failures.push_back("drive " + name + " tripped on " + TripCauses(unexpected) + " at " +
                         Seconds(trip.t_s) +
                         ", which the scene does not expect (expect: {drive: " + name +
                         ", trip: " + TripCauses(unexpected & (0u - unexpected)) + "})");
    }
  }
  return failures;
}

}  // namespace vmt::sim
