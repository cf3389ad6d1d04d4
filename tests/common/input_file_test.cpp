#include "common/input_file.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>

namespace vmt::common {
namespace {

std::filesystem::path Scratch(const char* name) {
  const auto dir = std::filesystem::temp_directory_path() / "vmt_input_file_test";
  std::filesystem::create_directories(dir);
  const auto path = dir / name;
  std::filesystem::remove(path);
  return path;
}

TEST(InputFile, ReadsARegularFileWhole) {
  const auto path = Scratch("scene.yaml");
  std::ofstream(path) << "scene: x\n";
  std::string text, why;
  ASSERT_TRUE(ReadInputFile(path, text, why));
  EXPECT_EQ(text, "scene: x\n");
  EXPECT_EQ(InputFileProblem(path), "");
}

TEST(InputFile, SaysWhyAFileCannotBeRead) {
  std::string text, why;
  EXPECT_FALSE(ReadInputFile(Scratch("missing"), text, why));
  EXPECT_EQ(why, "No such file or directory");
  EXPECT_FALSE(ReadInputFile(std::filesystem::temp_directory_path(), text, why));
  EXPECT_EQ(why, "Is a directory");
  EXPECT_FALSE(ReadInputFile("", text, why));
  EXPECT_EQ(why, "no file name given");
}

TEST(InputFile, RefusesAFifoAtOnce) {
  const auto fifo = Scratch("fifo");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  std::string text, why;
  EXPECT_FALSE(ReadInputFile(fifo, text, why));  // returns at once: no writer is waited for
  EXPECT_EQ(why, "not a regular file (a FIFO, device or socket)");
  EXPECT_EQ(InputFileProblem(fifo), why);
}

TEST(InputFile, RefusesAFileAboveTheLimitBeforeReadingIt) {
  const auto path = Scratch("big");
  std::ofstream(path) << std::string(100, 'x');
  std::string text, why;
  EXPECT_FALSE(ReadInputFile(path, text, why, 99));
  EXPECT_EQ(why, "the file is 100 bytes, more than the limit of 99 bytes");
  EXPECT_TRUE(text.empty());
  EXPECT_TRUE(ReadInputFile(path, text, why, 100));
}

}  // namespace
}  // namespace vmt::common
