// Outputs that cannot be lost or mixed: CSV rows streamed to a partial file as they are made and
// moved over the old file at the end (a refused run leaves it whole), an output directory held
// by one process at a time (a lock left by a dead process taken over), and file sets that appear
// whole or not at all. Devices, pipes and links: tests/test_output_targets.cpp.
#include <doctest/doctest.h>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "engine/core/error.h"
#include "engine/io/csv_stream.h"
#include "engine/io/output_lock.h"
#include "engine/io/staged_files.h"
#include "engine/util/json_writer.h"
#include "tests/temp_dir.h"

using namespace masav;
namespace fs = std::filesystem;

namespace {

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// A fresh directory of this process, removed at the end of the test.

size_t entries(const fs::path& dir) {
  size_t n = 0;
  for (const auto& e : fs::directory_iterator(dir)) (void)e, ++n;
  return n;
}

}  // namespace

TEST_CASE("CSV stream: every row is in the partial file as soon as it is written") {
  test::TempDir dir("masav_test_csv_stream");
  const fs::path file = dir.path / "d.csv";
  CsvStream csv(file.string(), {"step", "energy"}, "--csv");
  const fs::path partial = csv.partial_path();
  CHECK(partial.parent_path() == dir.path);
  CHECK(slurp(partial) == "step,energy\n");  // the header before any row
  csv.row({1, 0.5});
  CHECK(slurp(partial) == "step,energy\n1,0.5\n");  // not held back in a buffer
  CHECK_FALSE(fs::exists(file));                     // the file itself only on commit
  csv.commit();
  CHECK(slurp(file) == "step,energy\n1,0.5\n");
  CHECK_FALSE(fs::exists(partial));
  csv.row({2, 0.25});  // later rows go on into the file
  CHECK(slurp(file) == "step,energy\n1,0.5\n2,0.25\n");
  CHECK(csv.rows() == 2);
  CHECK_THROWS_WITH_AS(csv.row({3}), doctest::Contains("row of 1 cells for 2 columns"), Error);
}

TEST_CASE("CSV stream: an existing file stays whole until the rows replace it") {
  test::TempDir dir("masav_test_csv_keep");
  const fs::path file = dir.path / "good.csv";
  write_file_atomic(file.string(), "a\n1\n2\n");
  {
    CsvStream refused(file.string(), {"a"}, "--csv");  // a run refused before it commits
    refused.row({9});
    CHECK(slurp(file) == "a\n1\n2\n");
  }
  CHECK(slurp(file) == "a\n1\n2\n");
  CHECK(entries(dir.path) == 1);  // its partial removed
  CsvStream kept(file.string(), {"a"}, "--csv");
  kept.row({3});
  kept.commit();
  CHECK(slurp(file) == "a\n3\n");
}

TEST_CASE("CSV stream: a file that cannot be written fails at the header, naming it") {
  CHECK_THROWS_WITH_AS(CsvStream("/proc/masav/x.csv", {"a"}, "--csv"),
                       doctest::Contains("cannot create '/proc/masav/x.csv'"), Error);
  test::TempDir dir("masav_test_csv_dir");
  CHECK_THROWS_WITH_AS(CsvStream(dir.path.string(), {"a"}, "--csv"),
                       doctest::Contains("is a directory"), Error);
}

TEST_CASE("CSV stream: a second writer of the same file is refused and leaves it intact") {
  test::TempDir dir("masav_test_csv_twice");
  const fs::path file = dir.path / "d.csv";
  CsvStream first(file.string(), {"a"}, "--csv");
  first.row({1});
  CHECK_THROWS_WITH_AS(CsvStream(file.string(), {"a"}, "--csv"),
                       doctest::Contains("is being written by another process"), Error);
  CHECK(slurp(first.partial_path()) == "a\n1\n");
}

TEST_CASE("output lock: one holder at a time, released on exit, a dead holder's file taken over") {
  test::TempDir dir("masav_test_lock");
  const fs::path lock_file = dir.path / OutputLock::kFileName;
  {
    OutputLock held(dir.path.string(), "--out");
    CHECK(fs::exists(lock_file));
    CHECK(slurp(lock_file) == std::to_string(::getpid()) + "\n");
    // flock belongs to the open file, so a second lock in this process conflicts like another
    // process's would.
    const std::string busy =
        "is in use by another masav process (pid " + std::to_string(::getpid()) + ")";
    CHECK_THROWS_WITH_AS(OutputLock(dir.path.string(), "--out"), doctest::Contains(busy.c_str()),
                         Error);
  }
  CHECK_FALSE(fs::exists(lock_file));  // released and removed
  // A lock file left by a process that died (no flock held on it) is taken over.
  write_file_atomic(lock_file.string(), "999999999\n");
  {
    OutputLock taken(dir.path.string(), "--out");
    CHECK(slurp(lock_file) == std::to_string(::getpid()) + "\n");
  }
  // Another process holding the lock: refused while it lives.
  int ready[2];
  REQUIRE(::pipe(ready) == 0);
  const pid_t child = ::fork();
  if (child == 0) {
    const int fd = ::open(lock_file.c_str(), O_RDWR | O_CREAT, 0644);
    ::flock(fd, LOCK_EX);
    (void)!::write(ready[1], "x", 1);
    ::pause();  // killed by the parent
    ::_exit(0);
  }
  char byte = 0;
  REQUIRE(::read(ready[0], &byte, 1) == 1);
  CHECK_THROWS_WITH_AS(OutputLock(dir.path.string(), "--out"),
                       doctest::Contains("is in use by another masav process"), Error);
  ::kill(child, SIGKILL);
  ::waitpid(child, nullptr, 0);
  ::close(ready[0]);
  ::close(ready[1]);
  CHECK_NOTHROW(OutputLock(dir.path.string(), "--out"));  // the dead child's lock is gone
}

TEST_CASE("staged files appear together on commit, and not at all on a failure") {
  test::TempDir dir("masav_test_staged");
  write_file_atomic((dir.path / "a.txt").string(), "old a\n");
  write_file_atomic((dir.path / "b.txt").string(), "old b\n");
  {
    StagedFiles set(dir.path.string());
    write_file_atomic(set.stage("a.txt"), "new a\n");
    CHECK(slurp(dir.path / "a.txt") == "old a\n");  // nothing replaced before the commit
    (void)set.stage("b.txt");  // never written: the set is dropped (as if its writer failed)
  }
  CHECK(slurp(dir.path / "a.txt") == "old a\n");
  CHECK(slurp(dir.path / "b.txt") == "old b\n");
  CHECK(entries(dir.path) == 2);  // no temporary file left behind
  {
    StagedFiles set(dir.path.string());
    write_file_atomic(set.stage("a.txt"), "new a\n");
    (void)set.stage("b.txt");
    CHECK_THROWS_WITH_AS(set.commit(), doctest::Contains("b.txt' was never written"), Error);
  }
  CHECK(slurp(dir.path / "a.txt") == "old a\n");
  CHECK(entries(dir.path) == 2);
  StagedFiles set(dir.path.string());
  write_file_atomic(set.stage("a.txt"), "new a\n");
  write_file_atomic(set.stage("b.txt"), "new b\n");
  set.commit();
  CHECK(slurp(dir.path / "a.txt") == "new a\n");
  CHECK(slurp(dir.path / "b.txt") == "new b\n");
  CHECK(entries(dir.path) == 2);
}
