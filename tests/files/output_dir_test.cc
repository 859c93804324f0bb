// Output files: checked writes (a full disk or a missing folder is an error naming the file) and
// RFC 4180 quoting of CSV fields.
#include "files/output_dir.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include "temp_dir.h"

namespace sortcell::files {
namespace {

std::string ReadText(const std::filesystem::path& file) {
  std::ifstream in(file);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// The message of the std::runtime_error that `f` throws, or "no exception".
template <typename F>
std::string RuntimeErrorOf(F f) {
  try {
    f();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "no exception";
}

TEST(WriteTextFile, WritesAndReplacesTheFile) {
  const sortcell_test::TempDir dir("output_dir");
  WriteTextFile(dir / "a.md", "first version, longer\n");
  WriteTextFile(dir / "a.md", "second\n");
  EXPECT_EQ(ReadText(dir / "a.md"), "second\n");
  WriteJson(dir / "a.json", {{"k", 1}});
  EXPECT_EQ(ReadText(dir / "a.json"), "{\n  \"k\": 1\n}\n");
}

TEST(WriteTextFile, AFullDiskIsAnErrorNamingTheFile) {
  // /dev/full accepts the open and fails every write with ENOSPC, as a full disk does.
  ASSERT_TRUE(std::filesystem::exists("/dev/full"));
  EXPECT_EQ(RuntimeErrorOf([] { WriteTextFile("/dev/full", std::string(100000, 'x')); }),
            "cannot write '/dev/full': No space left on device");
  EXPECT_EQ(RuntimeErrorOf([] { WriteTextFile("/dev/full", "short"); }),
            "cannot write '/dev/full': No space left on device")
      << "a short text fails at close, not at <<";
  EXPECT_EQ(RuntimeErrorOf([] {
              WriteJson("/dev/full", {{"k", 1}});
            }),
            "cannot write '/dev/full': No space left on device");
}

TEST(WriteTextFile, AMissingFolderIsAnErrorNamingTheFile) {
  const sortcell_test::TempDir dir("output_dir");
  const std::filesystem::path file = dir / "gone" / "tables.md";
  EXPECT_EQ(RuntimeErrorOf([&] { WriteTextFile(file, "x"); }),
            "cannot write '" + file.string() + "': No such file or directory");
}

// The pid of a process that has ended (and been reaped): what a SIGKILLed writer leaves behind.
pid_t PidOfAnEndedProcess() {
  const pid_t child = fork();
  if (child == 0) _exit(0);
  waitpid(child, nullptr, 0);
  return child;
}

TEST(RemoveStalePartialFiles, RemovesOnlyWhatAnEndedWriterLeft) {
  const sortcell_test::TempDir dir("output_dir");
  const std::string dead = std::to_string(PidOfAnEndedProcess());
  const std::string alive = std::to_string(::getpid());
  for (const std::string& name : std::vector<std::string>{"summary.json.partial" + dead, "spec.yaml.partial" + alive,
                                                          "notes.partial", "notes.partialx1", "keep.json"}) {
    std::ofstream(dir / name) << "x";
  }
  std::filesystem::create_directories(dir / "episodes");
  std::ofstream(dir / "episodes" / ("metrics.json.partial" + dead)) << "x";
  RemoveStalePartialFiles(dir.path());
  EXPECT_FALSE(std::filesystem::exists(dir / ("summary.json.partial" + dead)));
  EXPECT_TRUE(std::filesystem::exists(dir / ("spec.yaml.partial" + alive))) << "its writer may still rename it";
  EXPECT_TRUE(std::filesystem::exists(dir / "notes.partial"));
  EXPECT_TRUE(std::filesystem::exists(dir / "notes.partialx1"));
  EXPECT_TRUE(std::filesystem::exists(dir / "keep.json"));
  EXPECT_TRUE(std::filesystem::exists(dir / "episodes" / ("metrics.json.partial" + dead))) << "only the folder itself";
  RemoveStalePartialFiles(dir / "episodes");
  EXPECT_FALSE(std::filesystem::exists(dir / "episodes" / ("metrics.json.partial" + dead)));
}

TEST(ReadTextFile, ReadsBytesAndNamesAFileItCannotRead) {
  const sortcell_test::TempDir dir("output_dir");
  const std::string bytes = std::string("a\0b\r\n", 5) + std::string(200000, 'x');  // Over one read's chunk.
  std::ofstream(dir / "f.bin", std::ios::binary) << bytes;
  EXPECT_EQ(ReadTextFile(dir / "f.bin"), bytes);
  std::ofstream(dir / "empty.txt").close();
  EXPECT_EQ(ReadTextFile(dir / "empty.txt"), "");
  EXPECT_EQ(RuntimeErrorOf([&] { ReadTextFile(dir / "gone.txt"); }),
            "cannot read '" + (dir / "gone.txt").string() + "': No such file or directory");
  EXPECT_EQ(RuntimeErrorOf([&] { ReadTextFile(dir.path()); }), "cannot read '" + dir.str() + "': Is a directory");
}

TEST(CloseChecked, ReportsAStreamThatFailed) {
  std::ofstream out("/dev/full");
  out << "x";
  EXPECT_EQ(RuntimeErrorOf([&] { CloseChecked(out, "/dev/full"); }).find("cannot write '/dev/full'"), 0u);
  const sortcell_test::TempDir dir("output_dir");
  std::ofstream good(dir / "ok.csv");
  good << "a,b\n";
  EXPECT_NO_THROW(CloseChecked(good, dir / "ok.csv"));
  EXPECT_EQ(ReadText(dir / "ok.csv"), "a,b\n");
}

TEST(CsvField, QuotesOnlyWhatRfc4180Requires) {
  EXPECT_EQ(CsvField("apple"), "apple");
  EXPECT_EQ(CsvField(""), "");
  EXPECT_EQ(CsvField("a b;c"), "a b;c");
  EXPECT_EQ(CsvField("apple, red"), "\"apple, red\"");
  EXPECT_EQ(CsvField("say \"cheese\""), "\"say \"\"cheese\"\"\"");
  EXPECT_EQ(CsvField("two\nlines"), "\"two\nlines\"");
  EXPECT_EQ(CsvField("cr\r"), "\"cr\r\"");
}

}  // namespace
}  // namespace sortcell::files
