// The station's JSON API against request bodies of the wrong type or out of range, answered in
// memory (in_memory_http.hpp): a 400 naming what is expected, nothing queued; never an exception
// (httplib would answer 500 with the exception's raw text) nor undefined behaviour.

#include "sim/station/station_routes.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "tests/sim/station/in_memory_http.hpp"

namespace vmt::sim::station {
namespace {

struct Answer {
  int status = 0;
  std::string body;
};

class StationRoutesTest : public ::testing::Test {
 protected:
  StationRoutesTest() {
    StationServerOptions o;
    o.web_dir = VMT_SOURCE_DIR "/web";
    o.handwheel_axes = {"X"};
    o.seekable = true;
    RouteStation(http_, hub_, o);
  }

  // The answer to one POST of `body` to `path`.
  Answer Post(const std::string& path, const std::string& body) {
    const std::string raw =
        http_.Answer("POST " + path + " HTTP/1.1\r\nHost: localhost\r\nContent-Length: " +
                     std::to_string(body.size()) + "\r\n\r\n" + body);
    Answer a;
    const size_t space = raw.find(' ');
    if (space != std::string::npos) a.status = std::stoi(raw.substr(space + 1, 3));
    const size_t blank = raw.find("\r\n\r\n");
    if (blank != std::string::npos) a.body = raw.substr(blank + 4);
    EXPECT_EQ(raw.find("EXCEPTION_WHAT"), std::string::npos) << raw;
    return a;
  }

  StationHub hub_;
  testing::InMemoryHttp http_;
};

TEST_F(StationRoutesTest, ARunActionThatIsNotTextIsABadRequest) {
  for (const char* body : {R"({"action": 1})", R"({"action": null})", R"({"action": ["run"]})",
                           R"({"action": {"run": true}})"}) {
    const Answer a = Post("/api/run", body);
    EXPECT_EQ(a.status, 400) << body;
    EXPECT_NE(a.body.find("expected {\\\"action\\\""), std::string::npos) << a.body;
  }
  EXPECT_TRUE(hub_.TakeInputs().empty());
  EXPECT_EQ(Post("/api/run", R"({"action": "pause"})").status, 200);
}

TEST_F(StationRoutesTest, HandwheelCountsBeyondTheRangeAreABadRequest) {
  // Whole numbers past int64 (which wrapped to -1) and int64's minimum (whose magnitude
  // overflowed) are out of range as much as 10001 is.
  for (const char* counts : {"18446744073709551615", "9223372036854775808", "-9223372036854775808",
                             "10001", "-10001", "0", "1.5"}) {
    const Answer a =
        Post("/api/handwheel", std::string(R"({"axis": "X", "counts": )") + counts + "}");
    EXPECT_EQ(a.status, 400) << counts;
    EXPECT_NE(a.body.find("-10000..10000"), std::string::npos) << a.body;
  }
  EXPECT_TRUE(hub_.TakeInputs().empty());
  for (const char* counts : {"10000", "-10000", "1"}) {
    EXPECT_EQ(
        Post("/api/handwheel", std::string(R"({"axis": "X", "counts": )") + counts + "}").status,
        200)
        << counts;
  }
  EXPECT_EQ(hub_.TakeInputs().size(), 3u);
}

}  // namespace
}  // namespace vmt::sim::station
