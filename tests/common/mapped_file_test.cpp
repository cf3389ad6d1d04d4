#include "common/mapped_file.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

namespace vmt::common {
namespace {

std::filesystem::path Scratch(const char* name) {
  const auto dir = std::filesystem::temp_directory_path() / "vmt_mapped_file_test";
  std::filesystem::create_directories(dir);
  const auto path = dir / name;
  std::filesystem::remove(path);
  return path;
}

TEST(MappedFile, ReadsTheWholeFile) {
  const auto path = Scratch("text");
  std::ofstream(path) << "N10 G1 X1\nN20 M30\n";
  const std::optional<MappedFile> file = MappedFile::Read(path);
  ASSERT_TRUE(file);
  EXPECT_EQ(file->text(), "N10 G1 X1\nN20 M30\n");
}

TEST(MappedFile, AnEmptyFileIsEmptyText) {
  const auto path = Scratch("empty");
  std::ofstream{path};
  const std::optional<MappedFile> file = MappedFile::Read(path);
  ASSERT_TRUE(file);
  EXPECT_TRUE(file->text().empty());
}

TEST(MappedFile, RefusesWhatIsNoRegularFile) {
  EXPECT_FALSE(MappedFile::Read(Scratch("missing")));
  EXPECT_FALSE(MappedFile::Read(std::filesystem::temp_directory_path()));
  const auto fifo = Scratch("fifo");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_FALSE(MappedFile::Read(fifo));  // returns at once: no writer is waited for
}

}  // namespace
}  // namespace vmt::common
