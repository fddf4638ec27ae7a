// Atomic outputs: a killed or failing writer leaves the old files and nothing else, a failed
// write no temporary; outputs that are inputs; text that must be UTF-8.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/memory_limit.h"
#include "common/same_file.h"
#include "common/utf8.h"

#include "temp_dir.h"
#include "wait_until.h"

namespace phongcl {
namespace {

namespace fs = std::filesystem;

using testing::TempDir;

std::string content(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::set<std::string> names_in(const fs::path& directory) {
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(directory)) names.insert(entry.path().filename().string());
  return names;
}

void write_text(const fs::path& file, const std::string& text) { std::ofstream(file, std::ios::binary) << text; }

// Runs body in a child process that SIGKILLs itself where body says; true if it died that way.
bool killed_in_child(const std::function<void()>& body) {
  const pid_t child = ::fork();
  if (child == 0) {
    body();
    ::_exit(0);  // not killed: the parent sees exit status 0
  }
  // Nothing where it still ran at the deadline (wait_for_child kills it then): not the death body chose.
  const std::optional<int> status = testing::wait_for_child(child);
  return status && WIFSIGNALED(*status) && WTERMSIG(*status) == SIGKILL;
}

void write_then_die(const fs::path& temp) {
  write_text(temp, std::string(1 << 20, 'n'));  // a megabyte of new content, then killed mid-run
  ::kill(::getpid(), SIGKILL);
}

// A writer killed mid-write (SIGKILL: no handler runs) leaves the old file and no hidden
// .NAME.tmpPID temporary beside it.
TEST(AtomicFile, KilledWriterLeavesOnlyTheOldFile) {
  TempDir dir;
  write_text(dir / "lit.exr", "old");
  ASSERT_TRUE(killed_in_child([&] { write_atomically(dir / "lit.exr", write_then_die); }));
  EXPECT_EQ(names_in(dir.path), std::set<std::string>{"lit.exr"});
  EXPECT_EQ(content(dir / "lit.exr"), "old");
}

// Where a temporary does get a name (no O_TMPFILE, or a kill between naming and renaming), the
// next write of that destination removes it once its process is gone, and only then.
TEST(AtomicFile, NextWriteRemovesTemporariesOfDeadProcesses) {
  TempDir dir;
  const pid_t dead = ::fork();
  if (dead == 0) ::_exit(0);
  ASSERT_TRUE(testing::wait_for_child(dead));
  const std::string stale = ".lit.tmp" + std::to_string(dead) + ".exr";
  const std::string live = ".lit.tmp" + std::to_string(::getppid()) + ".exr";  // a process that exists
  for (const std::string& name : {stale, live, std::string(".other.tmp") + std::to_string(dead) + ".exr"})
    write_text(dir / name, "leftover");
  write_atomically(dir / "lit.exr", [](const fs::path& temp) { write_text(temp, "new"); });
  EXPECT_EQ(names_in(dir.path), (std::set<std::string>{"lit.exr", live, ".other.tmp" + std::to_string(dead) + ".exr"}));
  EXPECT_EQ(content(dir / "lit.exr"), "new");
}

// A kill between the PNG and the EXR of one run leaves both old files, not a new PNG beside an old EXR.
TEST(AtomicBatch, KillBeforeCommitLeavesAllOldFiles) {
  TempDir dir;
  write_text(dir / "lit.png", "old png");
  write_text(dir / "lit.exr", "old exr");
  ASSERT_TRUE(killed_in_child([&] {
    AtomicBatch batch;
    write_atomically(dir / "lit.png", [](const fs::path& temp) { write_text(temp, "new png"); });
    write_atomically(dir / "lit.exr", write_then_die);
    batch.commit();
  }));
  EXPECT_EQ(names_in(dir.path), (std::set<std::string>{"lit.exr", "lit.png"}));
  EXPECT_EQ(content(dir / "lit.png"), "old png");
  EXPECT_EQ(content(dir / "lit.exr"), "old exr");
}

TEST(AtomicBatch, FailedWriteLeavesAllOldFiles) {
  TempDir dir;
  write_text(dir / "lit.png", "old png");
  EXPECT_THROW(
      {
        AtomicBatch batch;
        write_atomically(dir / "lit.png", [](const fs::path& temp) { write_text(temp, "new png"); });
        write_atomically(dir / "lit.exr", [](const fs::path&) { throw std::runtime_error("disk full"); });
        batch.commit();
      },
      std::runtime_error);
  EXPECT_EQ(names_in(dir.path), std::set<std::string>{"lit.png"});
  EXPECT_EQ(content(dir / "lit.png"), "old png");
}

TEST(AtomicBatch, CommitReplacesEveryFile) {
  TempDir dir;
  write_text(dir / "lit.png", "old png");
  {
    AtomicBatch batch;
    write_atomically(dir / "lit.png", [](const fs::path& temp) { write_text(temp, "new png"); });
    write_atomically(dir / "lit.exr", [](const fs::path& temp) { write_text(temp, "new exr"); });
    EXPECT_EQ(content(dir / "lit.png"), "old png");  // nothing visible before the commit
    EXPECT_FALSE(fs::exists(dir / "lit.exr"));
    batch.commit();
  }
  EXPECT_EQ(names_in(dir.path), (std::set<std::string>{"lit.exr", "lit.png"}));
  EXPECT_EQ(content(dir / "lit.png"), "new png");
  EXPECT_EQ(content(dir / "lit.exr"), "new exr");
}

// Output names of 245-255 bytes failed after shading ("File name too long"): the temporary's name
// is longer than the output's. It now fits wherever the output's does, and two long names with one
// beginning keep their temporaries apart.
TEST(AtomicFile, TheLongestNameTheFileSystemTakesIsWritten) {
  TempDir dir;
  const std::string stem(251, 'n');
  write_atomically(dir / (stem + ".exr"), [](const fs::path& temp) { write_text(temp, "new"); });
  EXPECT_EQ(content(dir / (stem + ".exr")), "new");
  {
    AtomicBatch batch;
    write_atomically(dir / (stem.substr(0, 250) + "a.exr"), [](const fs::path& temp) { write_text(temp, "a"); });
    write_atomically(dir / (stem.substr(0, 250) + "b.exr"), [](const fs::path& temp) { write_text(temp, "b"); });
    batch.commit();
  }
  EXPECT_EQ(content(dir / (stem.substr(0, 250) + "a.exr")), "a");
  EXPECT_EQ(content(dir / (stem.substr(0, 250) + "b.exr")), "b");
  EXPECT_EQ(names_in(dir.path).size(), 3u) << "no temporary left";
}

// A full disk was reported as "/proc/self/fd/5: ...": writers name the temporary they were given.
TEST(AtomicFile, AFailedWriteNamesTheDestination) {
  TempDir dir;
  std::string temp_name;
  try {
    write_atomically(dir / "lit.exr", [&](const fs::path& temp) {
      temp_name = temp.string();
      throw std::runtime_error("cannot write " + temp.string() + ": No space left on device");
    });
    FAIL() << "the write should fail";
  } catch (const std::exception& error) {
    EXPECT_EQ(std::string(error.what()), "cannot write " + (dir / "lit.exr").string() + ": No space left on device");
  }
  EXPECT_FALSE(temp_name.empty());
  EXPECT_TRUE(names_in(dir.path).empty());
}

TEST(Utf8, FirstInvalidByteIsFound) {
  EXPECT_EQ(first_invalid_utf8("plain ASCII"), std::nullopt);
  EXPECT_EQ(first_invalid_utf8("\xc3\xa9t\xc3\xa9 \xe2\x82\xac \xf0\x9f\x98\x80"), std::nullopt);  // été € 😀
  EXPECT_EQ(first_invalid_utf8("ab\xff"), 2u);
  EXPECT_EQ(first_invalid_utf8("a\xc0\xaf"), 1u);           // an overlong '/'
  EXPECT_EQ(first_invalid_utf8("a\xed\xa0\x80"), 1u);       // a UTF-16 surrogate
  EXPECT_EQ(first_invalid_utf8("\xf4\x90\x80\x80"), 0u);    // above U+10FFFF
  EXPECT_EQ(first_invalid_utf8("\xe2\x82"), 0u);            // cut short
  EXPECT_EQ(first_invalid_utf8("x\x80"), 1u);               // a continuation byte alone
  EXPECT_EQ(first_invalid_utf8(std::string("a\0b", 3)), std::nullopt);
}

// Any two outputs, or an output and an input, naming one file are refused; inputs may share.
TEST(SameFile, OutputsOverInputsOrOutputsAreRefused) {
  TempDir dir;
  write_text(dir / "g.exr", "gbuffer");
  fs::create_directories(dir / "sub");
  fs::create_hard_link(dir / "g.exr", dir / "hard.exr");
  fs::create_symlink(dir / "g.exr", dir / "soft.exr");
  fs::create_symlink(dir / "sub", dir / "linked_dir");
  const auto refused = [&](const std::vector<NamedFile>& files) {
    try {
      refuse_shared_files(files);
    } catch (const std::invalid_argument& error) {
      return std::string(error.what());
    }
    return std::string();
  };
  const NamedFile input{"--gbuffer", dir / "g.exr"};
  for (const fs::path& same : {dir / "g.exr", dir / "sub/../g.exr", dir / "hard.exr", dir / "soft.exr", dir / "./g.exr"}) {
    SCOPED_TRACE(same);
    EXPECT_EQ(refused({input, {"--out", same, true}}),
              "--out '" + same.string() + "' and --gbuffer '" + (dir / "g.exr").string() +
                  "' are the same file: an output cannot replace an input");
  }
  // Files that do not exist yet: compared by resolved name, through linked directories too.
  EXPECT_NE(refused({{"--out", dir / "sub/new.exr", true}, {"--aov", dir / "linked_dir/new.exr", true}}).find(
                "two outputs cannot share a file"),
            std::string::npos);
  EXPECT_NE(refused({{"--out", dir / "x.####.exr", true, "x.####.exr"}, {"--gbuffer", dir / "x.####.exr", false}}).find(
                "--out 'x.####.exr' ("),
            std::string::npos);
  EXPECT_EQ(refused({input, {"--scene", dir / "hard.exr"}, {"--out", dir / "other.exr", true}}), "") << "inputs may share";
  EXPECT_EQ(refused({{"--out", dir / "a.exr", true}, {"--out", dir / "a.exr", true}}), "") << "a frame listed twice";
}

TEST(AtomicWrite, ReplacesTheDestinationOnSuccess) {
  TempDir dir;
  std::ofstream(dir / "out.txt") << "old";
  write_atomically(dir / "out.txt", [](const fs::path& temp) { std::ofstream(temp) << "new"; });
  EXPECT_EQ(content(dir / "out.txt"), "new");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path), fs::directory_iterator()), 1);
}

TEST(AtomicWrite, ThrowingWriterLeavesDestinationIntactAndNoTemporary) {
  TempDir dir;
  std::ofstream(dir / "out.txt") << "old";
  EXPECT_THROW(write_atomically(dir / "out.txt",
                                [](const fs::path& temp) {
                                  std::ofstream(temp) << "half writ";
                                  throw std::runtime_error("disk full");
                                }),
               std::runtime_error);
  EXPECT_EQ(content(dir / "out.txt"), "old");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path), fs::directory_iterator()), 1);
}

TEST(AtomicWrite, MissingDirectoryFailsWithoutLeftovers) {
  TempDir dir;
  // The writer "succeeds" without creating anything; the rename then fails.
  EXPECT_THROW(write_atomically(dir / "missing" / "out.txt", [](const fs::path&) {}), InputError);
  EXPECT_TRUE(fs::is_empty(dir.path));
}

TEST(MemoryLimit, TheLargestNeedIsNamedWhenTheirSumIsOverTheLimit) {
  const MemoryLimit limit{3'000'000'000, "what the address-space limit (ulimit -v) leaves"};
  const std::vector<MemoryNeed> needs = {{"the image", 1.2e9}, {"the shadow geometry", 1.5e9}, {"the groups", 0.2e9}};
  EXPECT_NO_THROW(check_memory("shading this frame", needs, limit));
  std::vector<MemoryNeed> more = needs;
  more.push_back({"the terms", 0.2e9});
  try {
    check_memory("shading this frame", more, limit);
    ADD_FAILURE() << "3.1 GB of needs passed a 3.0 GB limit";
  } catch (const std::runtime_error& error) {
    EXPECT_STREQ(error.what(), "shading this frame needs about 3.1 GB, 1.5 GB of it for the shadow geometry: more than "
                               "the 3.0 GB of what the address-space limit (ulimit -v) leaves");
  }
}

TEST(MemoryLimit, TheMachinesAvailableMemoryBoundsIt) {
  const MemoryLimit limit = memory_limit();
  EXPECT_GT(limit.bytes, 0u);
  std::ifstream meminfo("/proc/meminfo");
  std::uint64_t total_kb = 0;
  for (std::string line; std::getline(meminfo, line);)
    if (line.starts_with("MemTotal:")) total_kb = std::stoull(line.substr(9));
  if (total_kb > 0) {
    EXPECT_LE(limit.bytes, total_kb * 1024);
  }
}

}  // namespace
}  // namespace phongcl
