#pragma once
// The PLC's scan cycle against the signal image, as a PLC runs it: at the start of a cycle the
// inputs are latched (the program sees one consistent copy, whatever changes meanwhile), the
// program runs on that copy, and at the end the signals a PLC drives are written back. Time is
// the PLC's own clock, advanced by the period each scan: nothing reads the wall clock.

#include <chrono>
#include <concepts>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "control/gateway/signal_image.hpp"
#include "control/plc/axd_wr.hpp"

namespace vmt::control::plc {

using PlcTime = std::chrono::microseconds;

/// What a program sees and writes during one scan. Reads come from the latched inputs (and the
/// program's own writes of this scan); writes are allowed only to signals a PLC drives (PLC to
/// NC, PLC to machine, shared) and reach the image at the end of the scan.
class PlcScan {
 public:
  PlcScan(gateway::SignalImage& latched, const std::vector<bool>& writable, PlcTime now,
          uint64_t cycle, const AxdWriter* axd_wr = nullptr)
      : latched_(latched), writable_(writable), now_(now), cycle_(cycle), axd_wr_(axd_wr) {}

  PlcTime now() const { return now_; }       ///< PLC time at the start of this scan
  uint64_t cycle() const { return cycle_; }  ///< scans before this one

  bool Bool(int id) const { return latched_.Bool(id); }
  int64_t Int(int id) const { return latched_.Int(id); }
  double Real(int id) const { return latched_.Real(id); }
  void SetBool(int id, bool v) { Writable(id), latched_.SetBool(id, v); }
  void SetInt(int id, int64_t v) { Writable(id), latched_.SetInt(id, v); }
  void SetReal(int id, double v) { Writable(id), latched_.SetReal(id, v); }

  /// The AXD_WR system function, null where nothing connects the PLC to the drives (a program
  /// then has no drive to write to, and says so as it sees fit).
  const AxdWriter* axd_wr() const { return axd_wr_; }

 private:
  void Writable(int id) const;

  gateway::SignalImage& latched_;
  const std::vector<bool>& writable_;
  PlcTime now_;
  uint64_t cycle_;
  const AxdWriter* axd_wr_;
};

/// What a PlcProgram holds: called once per scan, copied with the program. The program type
/// itself is excluded first: its own copy constructor copies it, and asking whether it is
/// copyable while this is worked out would never end.
template <typename Body, typename Program>
concept ScanFunction = !std::same_as<std::remove_cvref_t<Body>, Program> &&
                       std::invocable<Body&, PlcScan&> && std::copy_constructible<Body>;

/// A PLC program: called once per scan. Programs resolve their signal ids when they are made
/// (plc_programs.hpp) and keep their function block instances as members. A program is a value:
/// a copy holds its own instances (a run's in-memory snapshot copies the PLC with them), which
/// std::function, copying a shared pointer to the state, would not give.
class PlcProgram {
 public:
  PlcProgram() = default;
  template <ScanFunction<PlcProgram> Body>
  PlcProgram(Body body)  // NOLINT(google-explicit-constructor): any scan function is a program
      : body_(std::make_unique<Held<Body>>(std::move(body))) {}
  PlcProgram(const PlcProgram& other) : body_(other.body_ ? other.body_->Copy() : nullptr) {}
  PlcProgram& operator=(const PlcProgram& other) {
    if (this != &other) body_ = other.body_ ? other.body_->Copy() : nullptr;
    return *this;
  }
  PlcProgram(PlcProgram&&) noexcept = default;
  PlcProgram& operator=(PlcProgram&&) noexcept = default;

  void operator()(PlcScan& scan) { body_->Scan(scan); }
  explicit operator bool() const { return body_ != nullptr; }

 private:
  struct Body {
    virtual ~Body() = default;
    virtual void Scan(PlcScan& scan) = 0;
    virtual std::unique_ptr<Body> Copy() const = 0;
  };
  template <typename F>
  struct Held final : Body {
    explicit Held(F f) : f(std::move(f)) {}
    void Scan(PlcScan& scan) override { f(scan); }
    std::unique_ptr<Body> Copy() const override { return std::make_unique<Held>(f); }
    F f;
  };
  std::unique_ptr<Body> body_;
};

/// True for the signals a PLC may write: PLC to NC, PLC to machine, and the shared ones.
bool PlcDrives(gateway::Direction direction);

/// A PLC that halts or whose link is lost: every signal only the PLC writes (PLC to NC, PLC to
/// machine) falls back to its preset, as a PLC's outputs drop. Shared signals (events, AXD
/// idents) keep their value: the NC writes them too, and what it wrote is still true.
void DropPlcOutputs(gateway::SignalImage& image);

class PlcRuntime {
 public:
  /// `image` must outlive the runtime. The period is the scan time (DESIGN.md: 4 ms).
  PlcRuntime(gateway::SignalImage& image, PlcProgram program, PlcTime period);

  /// One scan: latch, run the program, write the outputs; then the PLC clock moves on. A
  /// stopped PLC does not scan.
  void Scan();
  /// The PLC stops (its watchdog tripped): its outputs drop (DropPlcOutputs) and no further
  /// scan runs.
  void Stop();
  bool stopped() const { return stopped_; }
  /// Connects AXD_WR (PlcScan::axd_wr) to the drives.
  void SetAxdWriter(AxdWriter writer) { axd_wr_ = std::move(writer); }

  PlcTime now() const { return now_; }
  PlcTime period() const { return period_; }
  uint64_t cycles() const { return cycles_; }

  /// What scanning changes (the latched copy, the program's instances, the clock): kept to go
  /// back to (a run's in-memory snapshot). The image itself is its owner's to keep.
  struct Saved {
    gateway::SignalImage latched;
    PlcProgram program;
    PlcTime now;
    uint64_t cycles;
    bool stopped;
  };
  Saved Save() const { return {latched_, program_, now_, cycles_, stopped_}; }
  void Restore(const Saved& saved) {
    latched_ = saved.latched;
    program_ = saved.program;
    now_ = saved.now;
    cycles_ = saved.cycles;
    stopped_ = saved.stopped;
  }

 private:
  gateway::SignalImage& image_;
  gateway::SignalImage latched_;
  PlcProgram program_;
  PlcTime period_;
  PlcTime now_{0};
  uint64_t cycles_ = 0;
  bool stopped_ = false;
  std::vector<bool> writable_;  ///< by id
  std::vector<int> outputs_;    ///< ids written back at the end of a scan
  AxdWriter axd_wr_;
};

}  // namespace vmt::control::plc
