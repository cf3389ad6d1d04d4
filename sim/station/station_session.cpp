#include "sim/station/station_session.hpp"

#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "common/json_text.hpp"
#include "control/channel/channel.hpp"

namespace vmt::sim::station {

using Clock = std::chrono::steady_clock;

void StationSession::Event(const nlohmann::ordered_json& event) {
  marks_.Note(event);
  ++events_;
  hub_.AddEvent(event.dump(-1, ' ', false, common::kReplaceBadUtf8));
}

void StationSession::Open(SceneRun& run, StationServerOptions options, const std::string& pace,
                          const std::string& run_control_refused) {
  options.model_json = ModelJson(run, pace);
  for (const control::IoInfo& io : run.scene().model->io)
    if (io.key && !io.selector())
      options.keys.push_back(io.name);  // a selector is set, not pressed
  if (options.operate_refused.empty()) {
    options.check_signal = [&run](const std::string& signal, double value) {
      return run.OperateError(signal, value);
    };
  } else {
    options.check_signal = [refused = options.operate_refused](const std::string&, double) {
      return refused;
    };
  }
  options.run_control_refused = run_control_refused;
  if (const control::channel::Channel* ch = run.channel()) {
    for (size_t a = 0; a < ch->config().axes.size(); ++a)
      options.handwheel_axes.push_back(ch->AxisName(a));
    options.handwheel_axes.insert(options.handwheel_axes.end(), {"X1", "Y1"});
  }
  server_ = std::make_unique<StationServer>(hub_, std::move(options));
  Publish(run, control_.running ? "running" : "paused", true);
}

void StationSession::TakeInputs(SceneRun& run) {
  for (StationInput& in : hub_.TakeInputs()) waiting_.push_back(std::move(in));
  if (run.tick() != changed_tick_) {
    changed_.clear();
    changed_tick_ = run.tick();
  }
  // Run control acts at once; keys and signals keep their order among themselves, so once one
  // waits for the next cycle, those after it wait too.
  std::deque<StationInput> later;
  for (StationInput& in : waiting_) {
    switch (in.kind) {
      case StationInput::Kind::kSignal:
        if (!later.empty() ||
            std::find(changed_.begin(), changed_.end(), in.signal) != changed_.end()) {
          later.push_back(std::move(in));
          break;
        }
        changed_.push_back(in.signal);
        if (const std::string error = run.Operate(in.signal, in.value); !error.empty())
          std::fprintf(stderr, "vmt serve: %.4f s: station: %s\n", run.time_s(), error.c_str());
        break;
      case StationInput::Kind::kHandwheel:
        if (!later.empty()) {
          later.push_back(std::move(in));
          break;
        }
        if (const std::string error = run.OperateHandwheel(in.signal, static_cast<int>(in.value));
            !error.empty())
          std::fprintf(stderr, "vmt serve: %.4f s: station: %s\n", run.time_s(), error.c_str());
        break;
      case StationInput::Kind::kRun:
        control_.changed = control_.changed || !control_.running || control_.speed != in.value;
        control_.running = true;
        control_.speed = in.value;
        break;
      case StationInput::Kind::kPause:
        control_.changed = control_.changed || control_.running;
        control_.running = false;
        break;
      case StationInput::Kind::kStep:
        control_.running = false;
        ++control_.steps;
        break;
      case StationInput::Kind::kSeek:  // a replay goes to the time and holds there
        control_.seek = in.value;
        control_.running = false;
        control_.steps = 0;
        control_.changed = true;
        break;
    }
  }
  waiting_ = std::move(later);
}

bool StationSession::CycleDue(SceneRun& run) {
  TakeInputs(run);
  if (control_.changed) {
    control_.changed = false;
    anchor_ = Clock::now();
    anchor_tick_ = run.tick();
  }
  if (!control_.running && control_.steps == 0) {
    Publish(run, "paused");
    Wait(std::chrono::milliseconds(20));
    return false;
  }
  if (control_.running && control_.speed > 0) {
    const std::chrono::duration<double> period(run.ticks_per_plc_cycle() * 250e-6);
    const double cycles =
        static_cast<double>(run.tick() - anchor_tick_) / run.ticks_per_plc_cycle();
    const auto due =
        anchor_ + std::chrono::duration_cast<Clock::duration>(period * (cycles / control_.speed));
    const auto now = Clock::now();
    if (now < due) {
      Publish(run, "running");
      Wait(std::min(std::chrono::duration_cast<std::chrono::milliseconds>(due - now),
                    std::chrono::milliseconds(20)));
      if (Clock::now() < due) return false;
    }
  }
  if (!control_.running) --control_.steps;
  return true;
}

void StationSession::Published(SceneRun& run) {
  Publish(run, control_.running ? "running" : "paused", !control_.running);
}

void StationSession::Publish(SceneRun& run, const std::string& state, bool force) {
  if (!server_) return;
  const auto now = Clock::now();
  // No page asking: no frame to build (the next request gets the last one, then fresh ones).
  if (!force && (now - published_ < std::chrono::microseconds(16667) || !hub_.StateWanted()))
    return;
  published_ = now;
  const int64_t cycle = run.tick() / std::max<int64_t>(1, run.ticks_per_plc_cycle());
  // The turned stock first, so that a page seeing a new version in the state finds it.
  if ((run.stock_cuts() != stock_published_ &&
       (force || now - stock_at_ >= std::chrono::milliseconds(200))) ||
      stock_published_ < 0) {
    stock_at_ = now;
    stock_published_ = run.stock_cuts();
    hub_.PublishStock(StockJson(run));
  }
  hub_.PublishState(StateJson(run, cycle, state, events_, marks_));
  if (hub_.SignalsWanted() && now - signals_published_ >= std::chrono::milliseconds(200)) {
    signals_published_ = now;
    hub_.PublishSignals(SignalsJson(run));
  }
}

}  // namespace vmt::sim::station
