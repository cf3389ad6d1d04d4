#include "common/output_file.hpp"

#include <gtest/gtest.h>
#include <sys/resource.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace vmt::common {
namespace {

std::filesystem::path Scratch() {
  const auto dir = std::filesystem::temp_directory_path() / "vmt_output_file_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

std::string Text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

size_t Entries(const std::filesystem::path& dir) {
  return static_cast<size_t>(std::distance(std::filesystem::directory_iterator(dir), {}));
}

// A file size limit makes writes beyond it fail (EFBIG) as a full disk does (ENOSPC), in any
// container; restored when the test ends.
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    ::getrlimit(RLIMIT_FSIZE, &old_);
    old_handler_ = std::signal(SIGXFSZ, SIG_IGN);
    rlimit limit = old_;
    limit.rlim_cur = bytes;
    ::setrlimit(RLIMIT_FSIZE, &limit);
  }
  ~FileSizeLimit() {
    ::setrlimit(RLIMIT_FSIZE, &old_);
    std::signal(SIGXFSZ, old_handler_);
  }

 private:
  rlimit old_{};
  void (*old_handler_)(int) = nullptr;
};

TEST(OutputFile, CommitReplacesTheFileWhole) {
  const auto dir = Scratch();
  std::ofstream(dir / "summary.json") << "old";
  OutputFile file((dir / "summary.json").string());
  file.Write("{\"new\": ");
  EXPECT_EQ(Text(dir / "summary.json"), "old");  // a reader sees the old file until Commit
  file.Write("1}\n");
  file.Commit();
  EXPECT_EQ(Text(dir / "summary.json"), "{\"new\": 1}\n");
  EXPECT_EQ(Entries(dir), 1u);  // no temporary left beside it
}

TEST(OutputFile, AnUnfinishedFileLeavesNothingBehind) {
  const auto dir = Scratch();
  std::ofstream(dir / "old.csv") << "old";
  {
    OutputFile fresh((dir / "fresh.csv").string());
    OutputFile replacing((dir / "old.csv").string());
    fresh.Write("a,b\n");
    replacing.Write("a,b\n");
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "fresh.csv"));
  EXPECT_EQ(Text(dir / "old.csv"), "old");
  EXPECT_EQ(Entries(dir), 1u);
}

TEST(OutputFile, AFullDeviceIsAnErrorNamingTheFile) {
  OutputFile file("/dev/full", OutputFile::Mode::kStream);
  file.Write("{\"t\": 0}\n");
  EXPECT_EQ(file.error(), 0);  // buffered
  try {
    file.Flush();
    FAIL() << "no error";
  } catch (const WriteError& e) {
    EXPECT_STREQ(e.what(), "cannot write /dev/full: No space left on device");
    EXPECT_EQ(e.path(), "/dev/full");
  }
  EXPECT_THROW(file.Commit(), WriteError);
}

TEST(OutputFile, AFailedFileIsRemovedAndTheOldOneKept) {
  const auto dir = Scratch();
  std::ofstream(dir / "trace.csv") << "old";
  const std::string row(1000, 'x');
  FileSizeLimit limit(100 * 1000);
  OutputFile file((dir / "trace.csv").string());
  for (int i = 0; i < 1000; ++i) file.Write(row);  // cheap: no throw per row
  EXPECT_NE(file.error(), 0);
  EXPECT_FALSE(file.open());  // its space freed at once
  EXPECT_THROW(file.Commit(), WriteError);
  EXPECT_EQ(Text(dir / "trace.csv"), "old");
  EXPECT_EQ(Entries(dir), 1u);
}

TEST(OutputFile, AFailedStreamKeepsWholeLinesOnly) {
  const auto dir = Scratch();
  const std::string line = std::string(99, 'e') + "\n";
  FileSizeLimit limit(1050);
  OutputFile file((dir / "events.jsonl").string(), OutputFile::Mode::kStream);
  for (int i = 0; i < 10; ++i) {
    file.Write(line);
    file.Flush();
  }
  file.Write(line);  // would pass the limit half-way
  EXPECT_THROW(file.Flush(), WriteError);
  file.Discard();
  EXPECT_EQ(Text(dir / "events.jsonl").size(), 1000u);
}

TEST(OutputFile, WriteFileAtomicallyWritesOrThrows) {
  const auto dir = Scratch();
  WriteFileAtomically((dir / "report.html").string(), "<html>");
  EXPECT_EQ(Text(dir / "report.html"), "<html>");
  EXPECT_THROW(WriteFileAtomically((dir / "no-such-folder" / "x").string(), "x"), WriteError);
  try {
    WriteFileAtomically((dir / "no-such-folder" / "x").string(), "x");
  } catch (const WriteError& e) {
    EXPECT_NE(std::string(e.what()).find("no-such-folder/x: No such file or directory"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace vmt::common
