// Setting up the Modbus TCP server: errors that name the problem (port in use, an address not
// of this machine, bad options), and a moved server that keeps serving.

#include <gtest/gtest.h>
#include <modbus.h>

#include "control/plc/modbus_server.hpp"
#include "modbus_server_test_support.hpp"

namespace vmt::control::plc {
namespace {

using namespace testing;  // vmt::control::plc::testing

TEST(ModbusServerSetupTest, ErrorsNameTheProblem) {
  SignalImage image = MakeImage();
  ModbusServer first(image, {});
  ModbusServer::Options o;
  o.port = first.port();
  try {
    ModbusServer second(image, o);
    ADD_FAILURE() << "a second server on the same port";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("127.0.0.1:" + std::to_string(first.port())), std::string::npos) << what;
    EXPECT_NE(what.find(std::strerror(EADDRINUSE)), std::string::npos) << what;
  }
  o = {};
  o.host = "192.0.2.1";  // TEST-NET-1: not an address of this machine
  EXPECT_THROW(ModbusServer(image, o).Poll(0), std::runtime_error);
  o = {};
  o.cycle_register = At(image, "P00C.FOVR").address;
  EXPECT_THROW(ModbusServer(image, o).Poll(0), std::invalid_argument);
  o.cycle_register = 65536;
  EXPECT_THROW(ModbusServer(image, o).Poll(0), std::invalid_argument);
  o = {};
  o.port = 70000;
  EXPECT_THROW(ModbusServer(image, o).Poll(0), std::invalid_argument);
  o = {};
  o.max_clients = 0;
  EXPECT_THROW(ModbusServer(image, o).Poll(0), std::invalid_argument);
  // Poll with nothing to do returns after its timeout; a moved server keeps serving.
  first.Poll(0);
  ModbusServer moved = std::move(first);
  WhilePolling(moved, [&] {
    Client c(moved.port());
    uint16_t r;
    EXPECT_EQ(modbus_read_registers(c.ctx, 0, 1, &r), 1);
  });
}

}  // namespace
}  // namespace vmt::control::plc
