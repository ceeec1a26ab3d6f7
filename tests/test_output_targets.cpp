// What a write to a path does to what the path names (engine/util/output_file.h): a regular file
// is replaced atomically, a link's file is replaced through the link (the link stays), a device
// or a pipe is written in place (it stays a device or a pipe; a write error there is an error),
// a directory is refused. Tested on private device nodes, pipes and links in a temporary
// directory, never on the machine's own.
#include <doctest/doctest.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "engine/core/error.h"
#include "engine/io/csv_stream.h"
#include "engine/io/staged_files.h"
#include "engine/util/output_file.h"
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

// A private character device node (major, minor) at `path`, or false where this process may
// not make one (not root, or a container without the capability): the caller skips, saying so.
bool make_device(const fs::path& path, unsigned major, unsigned minor) {
  return ::mknod(path.c_str(), S_IFCHR | 0666, makedev(major, minor)) == 0;
}

bool is_char_device(const fs::path& p) {
  struct stat st {};
  return ::lstat(p.c_str(), &st) == 0 && S_ISCHR(st.st_mode);
}

}  // namespace

TEST_CASE("an output through a symbolic link replaces the file it names; the link stays") {
  test::TempDir dir("masav_test_out_link");
  const fs::path target = dir.path / "real.json", link = dir.path / "link.json";
  write_output(target.string(), "old\n");
  fs::create_symlink("real.json", link);
  write_output(link.string(), "new\n", "--json");
  CHECK(fs::is_symlink(fs::symlink_status(link)));
  CHECK(slurp(target) == "new\n");
  // A link to a file not there yet creates it; a link to a directory is refused.
  const fs::path dangling = dir.path / "dangling.csv";
  fs::create_symlink("later.csv", dangling);
  write_output(dangling.string(), "x\n");
  CHECK(fs::is_symlink(fs::symlink_status(dangling)));
  CHECK(slurp(dir.path / "later.csv") == "x\n");
  fs::create_directory(dir.path / "sub");
  fs::create_symlink("sub", dir.path / "to_dir");
  CHECK_THROWS_WITH_AS(write_output((dir.path / "to_dir").string(), "x", "--json"),
                       doctest::Contains("is a directory"), Error);
  CHECK(fs::is_directory(dir.path / "sub"));
  // A loop of links is refused, not followed forever.
  fs::create_symlink("loop_b", dir.path / "loop_a");
  fs::create_symlink("loop_a", dir.path / "loop_b");
  CHECK_THROWS_WITH_AS(write_output((dir.path / "loop_a").string(), "x", "--json"),
                       doctest::Contains("loop of symbolic links"), Error);
  // A CSV through a link: the rows replace the file it names on commit.
  const fs::path csv_link = dir.path / "rows.csv";
  fs::create_symlink("real.csv", csv_link);
  CsvStream csv(csv_link.string(), {"a"}, "--csv");
  csv.row({1});
  csv.commit();
  CHECK(fs::is_symlink(fs::symlink_status(csv_link)));
  CHECK(slurp(dir.path / "real.csv") == "a\n1\n");
}

TEST_CASE("an output to a directory is refused and the directory stays") {
  test::TempDir dir("masav_test_out_dir");
  CHECK_THROWS_WITH_AS(write_output(dir.path.string(), "x", "--json"),
                       doctest::Contains("is a directory"), Error);
  CHECK(fs::is_directory(dir.path));
}

TEST_CASE("an output to a pipe is written in place; one without a reader fails at once") {
  test::TempDir dir("masav_test_out_fifo");
  const fs::path fifo = dir.path / "pipe";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  CHECK_THROWS_WITH_AS(write_output(fifo.string(), "x", "--json"),
                       doctest::Contains("cannot open"), Error);  // no reader: no hang
  std::string got;
  std::thread reader([&] {
    std::ifstream in(fifo);
    std::stringstream ss;
    ss << in.rdbuf();
    got = ss.str();
  });
  // The reader opens the pipe first; until then the open without one fails and is retried.
  for (int tries = 0;; ++tries) {
    try {
      write_output(fifo.string(), "through the pipe\n", "--json");
      break;
    } catch (const Error&) {
      REQUIRE(tries < 2000);
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  }
  reader.join();
  CHECK(got == "through the pipe\n");
  struct stat st {};
  REQUIRE(::lstat(fifo.c_str(), &st) == 0);
  CHECK(S_ISFIFO(st.st_mode));
}

TEST_CASE("an output to a device is written in place and the device stays a device") {
  test::TempDir dir("masav_test_out_dev");
  const fs::path null_dev = dir.path / "null", full_dev = dir.path / "full";
  if (!make_device(null_dev, 1, 3) || !make_device(full_dev, 1, 7)) {
    MESSAGE("SKIPPED: this process may not make private device nodes (mknod: not root, or no "
            "CAP_MKNOD); the pipe and link cases cover writing in place");
    return;
  }
  write_output(null_dev.string(), "discarded\n", "--json");
  CHECK(is_char_device(null_dev));
  // A full device fails the write, naming it: never "wrote".
  CHECK_THROWS_WITH_AS(write_output(full_dev.string(), "x\n", "--json"),
                       doctest::Contains("No space left"), Error);
  CHECK(is_char_device(full_dev));
  // The CSV stream writes a device in place, and a full one fails at the header.
  {
    CsvStream csv(null_dev.string(), {"a"}, "--csv");
    csv.row({1});
    csv.commit();
  }
  CHECK(is_char_device(null_dev));
  CHECK_THROWS_WITH_AS(CsvStream(full_dev.string(), {"a"}, "--csv"),
                       doctest::Contains("failed after 0 rows: No space left"), Error);
  CHECK(is_char_device(full_dev));
  // Staged file sets commit onto a device in place too.
  {
    StagedFiles set(dir.path.string());
    write_output(set.stage("null"), "staged\n");
    set.commit();
  }
  CHECK(is_char_device(null_dev));
}
