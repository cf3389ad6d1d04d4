#include "sim/station/station_hub.hpp"

namespace vmt::sim::station {

using Clock = std::chrono::steady_clock;

void StationHub::PublishState(std::string json) {
  auto frame = std::make_shared<const std::string>(std::move(json));
  std::lock_guard lock(mutex_);
  state_ = std::move(frame);
}

void StationHub::PublishSignals(std::string json) {
  auto frame = std::make_shared<const std::string>(std::move(json));
  std::lock_guard lock(mutex_);
  signals_ = std::move(frame);
}

void StationHub::PublishStock(std::string json) {
  auto frame = std::make_shared<const std::string>(std::move(json));
  std::lock_guard lock(mutex_);
  stock_ = std::move(frame);
}

std::string StationHub::Stock() const {
  std::shared_ptr<const std::string> frame;
  {
    std::lock_guard lock(mutex_);
    frame = stock_;
  }
  return frame ? *frame : std::string(R"({"version":0,"link":"","cylinders":[]})");
}

bool StationHub::StateWanted() const {
  std::lock_guard lock(mutex_);
  return Clock::now() - state_asked_ < std::chrono::seconds(2);
}

bool StationHub::SignalsWanted() const {
  std::lock_guard lock(mutex_);
  return Clock::now() - signals_asked_ < std::chrono::seconds(2);
}

void StationHub::AddEvent(std::string json) {
  std::lock_guard lock(mutex_);
  events_.push_back(std::move(json));
  if (events_.size() > kMaxEvents) {
    events_.pop_front();
    ++events_dropped_;
  }
}

std::vector<StationInput> StationHub::TakeInputs() {
  std::lock_guard lock(mutex_);
  std::vector<StationInput> taken(std::make_move_iterator(inputs_.begin()),
                                  std::make_move_iterator(inputs_.end()));
  inputs_.clear();
  return taken;
}

void StationHub::WaitForInput(std::chrono::milliseconds timeout) {
  std::unique_lock lock(mutex_);
  input_queued_.wait_for(lock, timeout, [this] { return !inputs_.empty(); });
}

std::string StationHub::State() const {
  std::shared_ptr<const std::string> frame;
  {
    std::lock_guard lock(mutex_);
    state_asked_ = Clock::now();
    frame = state_;
  }
  return frame ? *frame : std::string("{}");
}

std::string StationHub::Signals() {
  std::shared_ptr<const std::string> frame;
  {
    std::lock_guard lock(mutex_);
    signals_asked_ = Clock::now();
    frame = signals_;
  }
  return frame ? *frame : std::string(R"({"signals":[]})");
}

std::string StationHub::Events(size_t from) const {
  std::lock_guard lock(mutex_);
  const size_t total = events_dropped_ + events_.size();
  const size_t begin = std::max(from, events_dropped_);
  std::string out = "{\"total\":" + std::to_string(total) +
                    ",\"first\":" + std::to_string(events_dropped_) + ",\"events\":[";
  for (size_t i = begin, n = 0; i < total && n < kMaxEventsPerAnswer; ++i, ++n) {
    if (n) out += ',';
    out += events_[i - events_dropped_];
  }
  out += "]}";
  return out;
}

bool StationHub::Push(StationInput input) {
  {
    std::lock_guard lock(mutex_);
    if (inputs_.size() >= kMaxInputs) return false;
    inputs_.push_back(std::move(input));
  }
  input_queued_.notify_one();
  return true;
}

}  // namespace vmt::sim::station
