// An external PLC's view of vmt over Modbus TCP on loopback: the round trip of a read, of a
// write, and of a lockstep PLC cycle (write the cycle register; vmt runs 4 ms of the lathe scene
// on the kinematic backend, then answers). The server runs in its own thread here only so that
// one process can measure both ends; vmt serve polls it in its simulation loop.

#include <benchmark/benchmark.h>
#include <modbus.h>

#include <atomic>
#include <stdexcept>
#include <thread>

#include "control/gateway/signal_table.hpp"
#include "control/plc/modbus_server.hpp"
#include "sim/runner/runner.hpp"

namespace {

using namespace vmt;

class ServerThread {
 public:
  ServerThread(control::gateway::SignalImage& image, control::plc::ModbusServerOptions options)
      : server_(image, std::move(options)), thread_([this] {
          while (!stop_) server_.Poll(10);
        }) {}
  ~ServerThread() {
    stop_ = true;
    thread_.join();
  }
  int port() const { return server_.port(); }

 private:
  control::plc::ModbusServer server_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

modbus_t* Connect(int port) {
  modbus_t* ctx = modbus_new_tcp("127.0.0.1", port);
  if (!ctx || modbus_connect(ctx) != 0) throw std::runtime_error("cannot connect");
  return ctx;
}

control::gateway::SignalImage LatheImage() {
  control::gateway::GatewayLayout layout;
  layout.processes = {0};
  layout.axes = {{1, "X", false, false}, {2, "Z", false, false}, {3, "S1", true, false}};
  return control::gateway::SignalImage(control::gateway::BuildSignalTable(layout));
}

void BM_ModbusReadDiscreteInputs(benchmark::State& state) {
  auto image = LatheImage();
  ServerThread server(image, {});
  modbus_t* ctx = Connect(server.port());
  uint8_t bits[64];
  for (auto _ : state)
    if (modbus_read_input_bits(ctx, 0, 64, bits) != 64) state.SkipWithError("read failed");
  state.counters["round_trip_us"] = benchmark::Counter(
      double(state.iterations()) * 1e-6, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  modbus_close(ctx);
  modbus_free(ctx);
}

void BM_ModbusWriteCoils(benchmark::State& state) {
  auto image = LatheImage();
  ServerThread server(image, {});
  modbus_t* ctx = Connect(server.port());
  uint8_t bits[8] = {1, 0, 1, 0, 0, 0, 0, 0};
  for (auto _ : state)
    if (modbus_write_bits(ctx, 0, 8, bits) != 8) state.SkipWithError("write failed");
  state.counters["round_trip_us"] = benchmark::Counter(
      double(state.iterations()) * 1e-6, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  modbus_close(ctx);
  modbus_free(ctx);
}

void BM_LockstepPlcCycle(benchmark::State& state) {
  // The repositioning keys scene, its PLC outside: each write runs one 4 ms PLC cycle.
  const sim::Scene scene = sim::LoadScene(VMT_SOURCE_DIR "/scenes/repos-machine-keys.yaml");
  sim::RunOptions options;
  options.external_plc = true;
  options.until_s = 1e6;  // longer than the benchmark runs
  sim::SceneRun run(scene, options);
  control::plc::ModbusServerOptions mb;
  mb.cycle_register = control::gateway::LockstepCycleRegister(run.image()->table());
  mb.on_cycle = [&](uint32_t) {
    for (int64_t k = 0; k < run.ticks_per_plc_cycle(); ++k) run.Step();
  };
  ServerThread server(*run.image(), mb);
  modbus_t* ctx = Connect(server.port());
  uint16_t cycle = 0;
  for (auto _ : state)
    if (modbus_write_register(ctx, *mb.cycle_register, ++cycle) != 1)
      state.SkipWithError("cycle write failed");
  state.counters["round_trip_us"] = benchmark::Counter(
      double(state.iterations()) * 1e-6, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["real_time_factor"] =
      benchmark::Counter(double(state.iterations()) * 0.004, benchmark::Counter::kIsRate);
  modbus_close(ctx);
  modbus_free(ctx);
}

BENCHMARK(BM_ModbusReadDiscreteInputs)->UseRealTime();
BENCHMARK(BM_ModbusWriteCoils)->UseRealTime();
BENCHMARK(BM_LockstepPlcCycle)->UseRealTime();

}  // namespace
