// Inputs bounded before they are read: checked 64-bit size arithmetic, regular files only (never
// an endless device or a FIFO), text inputs capped, declared volume sizes checked against the file
// (no wrap-around at 2^32), every NRRD field honoured or refused by name, and the checked cache
// file envelope (damaged, truncated or mismatched files are detected).
#include <doctest/doctest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "engine/util/bounded_file.h"
#include "engine/util/cache_file.h"
#include "engine/util/checked_size.h"
#include "engine/volume/transfer_function.h"
#include "engine/volume/volume_io.h"
#include "registry/scene_file.h"
#include "tests/temp_dir.h"
#include "tests/error_of.h"

using namespace masav;
using masav::test::error_of;
using namespace masav::volume;

namespace {

void write_text(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
}

// A header for a 4x3x2 uint16 volume, data detached in `data`, with extra lines.
std::string nhdr(const std::string& data, const std::string& extra = "") {
  return "NRRD0004\ntype: uint16\ndimension: 3\nsizes: 4 3 2\nencoding: raw\nendian: little\n" +
         extra + "data file: " + data + "\n";
}

std::string ramp_bytes() {
  std::string s;
  for (uint16_t i = 0; i < 24; ++i) s.append(reinterpret_cast<const char*>(&i), 2);
  return s;
}

}  // namespace

TEST_CASE("checked sizes: overflow and wrap-around are errors naming the field") {
  CHECK(checked_mul(uint64_t(1) << 31, 4, "f", "sizes") == uint64_t(1) << 33);
  CHECK(error_of([] {
          checked_mul(uint64_t(1) << 40, uint64_t(1) << 40, "NRRD x", "sizes");
        }).find("NRRD x: invalid sizes") != std::string::npos);
  CHECK(error_of([] {
          checked_add(~uint64_t(0), 1, "w", "byte skip");
        }).find("invalid byte skip") != std::string::npos);
  CHECK(parse_u64(" 4294967312 ", "w", "sizes") == 4294967312ull);
  for (const char* bad : {"-1", "1.5", "1e3", "", "18446744073709551616", "12abc", "0x10"})
    CHECK(error_of([&] { parse_u64(bad, "w", "sizes"); }).find("invalid sizes") !=
          std::string::npos);
  CHECK(parse_i64("-1", "w", "byte skip") == -1);
  // 2^32 + 16 is not 16.
  CHECK(error_of([] {
          checked_u32_in(4294967312ull, 2, 8192, "w", "sizes");
        }).find("invalid sizes = 4294967312") != std::string::npos);
}

TEST_CASE("bounded files: endless devices, FIFOs and directories are refused without reading") {
  test::TempDir t("masav_bounded");
  for (const char* dev : {"/dev/zero", "/dev/urandom"}) {
    CHECK(error_of([&] { read_bounded_file(dev, "input"); }).find("character device") !=
          std::string::npos);
    CHECK(error_of([&] {
            load_raw(dev, {8, 8, 8}, SampleType::u8);
          }).find("not a regular file") != std::string::npos);
    CHECK(error_of([&] { load_nrrd(dev); }).find("not a regular file") != std::string::npos);
    CHECK(error_of([&] { load_vti(dev); }).find("not a regular file") != std::string::npos);
    CHECK(error_of([&] { scene::load_scene_file(dev); }).find("not a regular file") !=
          std::string::npos);
    CHECK(error_of([&] { load_transfer_points(dev); }).find("not a regular file") !=
          std::string::npos);
  }
  // A FIFO with no writer: opening it for reading would block forever.
  const std::string fifo = t.file("fifo");
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  CHECK(error_of([&] { read_bounded_file(fifo, "input"); }).find("a FIFO") != std::string::npos);
  CHECK(error_of([&] { scene::load_scene_file(fifo); }).find("not a regular file") !=
        std::string::npos);
  CHECK(error_of([&] { read_bounded_file(t.path.string(), "input"); }).find("is a directory") !=
        std::string::npos);
  CHECK(error_of([&] { read_bounded_file(t.file("none"), "input"); }).find("does not exist") !=
        std::string::npos);
  // A declared range past the end is refused, naming the field, before anything is allocated.
  write_text(t.file("small"), "0123456789");
  const BoundedFile f(t.file("small"), "input");
  CHECK(f.size() == 10);
  CHECK(f.read(2, 3, "sizes") == "234");
  CHECK(error_of([&] {
          (void)f.read(4, uint64_t(1) << 62, "sizes");
        }).find("sizes declares bytes 4 to") != std::string::npos);
  CHECK(error_of([&] { (void)f.read(~uint64_t(0), 2, "byte skip"); }).find("invalid byte skip") !=
        std::string::npos);
  CHECK(f.read_some(8, 100) == "89");
}

TEST_CASE("text inputs over 16 MiB are refused before they are read (a 1 GB scene file)") {
  test::TempDir t("masav_bounded");
  const std::string big = t.file("big.toml");
  write_text(big, "[particles]\ncount = 1000\n");
  std::filesystem::resize_file(big, uint64_t(1) << 30);  // sparse: costs no disk
  const std::string e = error_of([&] { scene::load_scene_file(big); });
  CHECK(e.find("over the limit of 16.0 MiB") != std::string::npos);
  std::filesystem::resize_file(big, kMaxTextInputBytes);
  CHECK(error_of([&] { scene::load_scene_file(big); }).find("not a text file") !=
        std::string::npos);  // at the limit it is read (and then its zeros are refused)
}

TEST_CASE("NRRD: sizes that wrap, a missing sizes field, and unknown fields are named") {
  test::TempDir t("masav_bounded");
  write_text(t.file("d.raw"), ramp_bytes());
  write_text(t.file("ok.nhdr"), nhdr("d.raw"));
  CHECK(load_nrrd(t.file("ok.nhdr")).values[23] == 23.0f);
  // 2^32 + 16 used to be read as 16.
  std::string h = nhdr("d.raw");
  h.replace(h.find("sizes: 4 3 2"), 12, "sizes: 4294967312 3 2");
  write_text(t.file("wrap.nhdr"), h);
  CHECK(error_of([&] { load_nrrd(t.file("wrap.nhdr")); }).find("invalid sizes = 4294967312") !=
        std::string::npos);
  h = nhdr("d.raw");
  h.replace(h.find("sizes: 4 3 2"), 12, "sizes: 4 3 -2");
  write_text(t.file("neg.nhdr"), h);
  CHECK(error_of([&] { load_nrrd(t.file("neg.nhdr")); }).find("invalid sizes = -2") !=
        std::string::npos);
  h = nhdr("d.raw");
  h.erase(h.find("sizes: 4 3 2\n"), 13);
  write_text(t.file("nosizes.nhdr"), h);
  const std::string e = error_of([&] { load_nrrd(t.file("nosizes.nhdr")); });
  CHECK(e.find("invalid sizes = missing") != std::string::npos);
  CHECK(e.find("dimension") == std::string::npos);
  write_text(t.file("block.nhdr"), nhdr("d.raw", "block size: 4\n"));
  CHECK(error_of([&] { load_nrrd(t.file("block.nhdr")); }).find("invalid field = block size") !=
        std::string::npos);
  write_text(t.file("twice.nhdr"), nhdr("d.raw", "sizes: 4 3 2\n"));
  CHECK(error_of([&] { load_nrrd(t.file("twice.nhdr")); }).find("two 'sizes' lines") !=
        std::string::npos);
  write_text(t.file("rot.nhdr"), nhdr("d.raw", "space directions: (0,1,0) (1,0,0) (0,0,1)\n"));
  CHECK(error_of([&] { load_nrrd(t.file("rot.nhdr")); }).find("axis-aligned") != std::string::npos);
  write_text(t.file("list.nhdr"), nhdr("LIST"));
  CHECK(error_of([&] { load_nrrd(t.file("list.nhdr")); }).find("invalid data file = LIST") !=
        std::string::npos);
  // Fields that do not change the samples are read and accepted.
  write_text(t.file("info.nhdr"),
             nhdr("d.raw", "content: ramp\nkinds: domain domain domain\nspace: RAS\nkey:=v\n"));
  CHECK(load_nrrd(t.file("info.nhdr")).values[23] == 23.0f);
}

TEST_CASE("NRRD: line skip and byte skip are honoured") {
  test::TempDir t("masav_bounded");
  const std::string data = ramp_bytes();
  write_text(t.file("lines.raw"), "first line\nsecond\n" + data);
  write_text(t.file("lines.nhdr"), nhdr("lines.raw", "line skip: 2\n"));
  CHECK(load_nrrd(t.file("lines.nhdr")).values[23] == 23.0f);
  write_text(t.file("bytes.raw"), "JUNK!" + data);
  write_text(t.file("bytes.nhdr"), nhdr("bytes.raw", "byte skip: 5\n"));
  CHECK(load_nrrd(t.file("bytes.nhdr")).values[23] == 23.0f);
  write_text(t.file("tail.nhdr"), nhdr("bytes.raw", "byte skip: -1\n"));
  CHECK(load_nrrd(t.file("tail.nhdr")).values[0] == 0.0f);
  // Without the skip the junk would be read as data: the size no longer matches.
  write_text(t.file("noskip.nhdr"), nhdr("bytes.raw"));
  CHECK(error_of([&] { load_nrrd(t.file("noskip.nhdr")); }).find("invalid sizes") !=
        std::string::npos);
  write_text(t.file("far.nhdr"), nhdr("bytes.raw", "byte skip: 1000\n"));
  CHECK(error_of([&] { load_nrrd(t.file("far.nhdr")); }).find("invalid sizes") !=
        std::string::npos);
  write_text(t.file("manylines.nhdr"), nhdr("lines.raw", "line skip: 99\n"));
  CHECK(error_of([&] { load_nrrd(t.file("manylines.nhdr")); }).find("invalid line skip = 99") !=
        std::string::npos);
  write_text(t.file("badskip.nhdr"), nhdr("bytes.raw", "byte skip: -2\n"));
  CHECK(error_of([&] { load_nrrd(t.file("badskip.nhdr")); }).find("invalid byte skip = -2") !=
        std::string::npos);
  // Attached ASCII data with a line skip.
  write_text(t.file("a.nrrd"),
             "NRRD0004\ntype: float\ndimension: 3\nsizes: 2 2 2\nencoding: ascii\nline skip: 1\n\n"
             "skipped line\n1 2 3 4 5 6 7 8\n");
  CHECK(load_nrrd(t.file("a.nrrd")).values[7] == 8.0f);
}

TEST_CASE(
    "NRRD: detached data on an endless device or a FIFO fail fast; huge sizes do not allocate") {
  test::TempDir t("masav_bounded");
  write_text(t.file("zero.nhdr"), nhdr("/dev/zero"));
  CHECK(error_of([&] {
          load_nrrd(t.file("zero.nhdr"));
        }).find("'/dev/zero' is a character device") != std::string::npos);
  REQUIRE(::mkfifo(t.file("fifo").c_str(), 0600) == 0);
  write_text(t.file("fifo.nhdr"), nhdr("fifo"));
  CHECK(error_of([&] { load_nrrd(t.file("fifo.nhdr")); }).find("a FIFO") != std::string::npos);
  // 8192^3 samples declared, 48 bytes present: refused from the sizes alone.
  write_text(t.file("d.raw"), ramp_bytes());
  std::string h = nhdr("d.raw");
  h.replace(h.find("sizes: 4 3 2"), 12, "sizes: 8192 8192 8192");
  write_text(t.file("huge.nhdr"), h);
  CHECK(error_of([&] { load_nrrd(t.file("huge.nhdr")); }).find("the dims need 549755813888") !=
        std::string::npos);
  // A header with no blank line that goes on past 16 MiB is refused as a header.
  const std::string big = t.file("big.nrrd");
  write_text(big, "NRRD0004\ntype: uint8\n");
  std::filesystem::resize_file(big, kMaxTextInputBytes + 100);
  CHECK(error_of([&] { load_nrrd(big); }).find("header") != std::string::npos);
}

TEST_CASE("VTI: extents that wrap and malformed documents are errors, never a crash") {
  test::TempDir t("masav_bounded");
  const auto vti = [](const std::string& extent, const std::string& extra = "") {
    return "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"1.0\">\n"
           "<ImageData WholeExtent=\"" +
           extent + "\" Origin=\"0 0 0\" Spacing=\"1 1 1\"" + extra + ">\n<Piece Extent=\"" +
           extent +
           "\"><PointData>\n"
           "<DataArray type=\"Float32\" Name=\"v\" format=\"ascii\">1 2 3 4 5 6 7 8</DataArray>\n"
           "</PointData></Piece></ImageData></VTKFile>\n";
  };
  write_text(t.file("ok.vti"), vti("0 1 0 1 0 1"));
  CHECK(load_vti(t.file("ok.vti")).values[7] == 8.0f);
  write_text(t.file("wrap.vti"), vti("0 4294967311 0 1 0 1"));  // 2^32 + 16 points
  CHECK(error_of([&] { load_vti(t.file("wrap.vti")); }).find("invalid WholeExtent") !=
        std::string::npos);
  write_text(t.file("huge.vti"), vti("-9223372036854775808 9223372036854775807 0 1 0 1"));
  CHECK(error_of([&] { load_vti(t.file("huge.vti")); }).find("invalid WholeExtent") !=
        std::string::npos);
  write_text(t.file("rot.vti"), vti("0 1 0 1 0 1", " Direction=\"0 1 0 1 0 0 0 0 1\""));
  CHECK(error_of([&] { load_vti(t.file("rot.vti")); }).find("invalid Direction") !=
        std::string::npos);
  write_text(t.file("noimage.vti"), "<VTKFile type=\"ImageData\">\n");
  CHECK(error_of([&] { load_vti(t.file("noimage.vti")); }).find("ImageData = missing") !=
        std::string::npos);
  write_text(t.file("noappended.vti"),
             "<VTKFile type=\"ImageData\"><ImageData WholeExtent=\"0 1 0 1 0 1\"><Piece>"
             "<DataArray type=\"Float32\" format=\"appended\" offset=\"99999999999\"/>");
  CHECK(error_of([&] { load_vti(t.file("noappended.vti")); }).find("AppendedData") !=
        std::string::npos);
}

TEST_CASE("cache files: version, key and checksum checked; damage is detected, never used") {
  test::TempDir t("masav_bounded");
  const std::string path = t.file("c.bin");
  const CacheFileId id{"test-table", 3, "rows=4 g=0x1p-1"};
  std::string payload(1000, '\0');
  for (size_t i = 0; i < payload.size(); ++i) payload[i] = char(i * 7);
  write_cache_file(path, id, payload);
  CHECK(read_cache_file(path, id, 1000).payload == payload);
  CHECK(read_cache_file(path, id, 999).rejected.find("more than the 999") != std::string::npos);
  // No file: a plain miss, nothing to note.
  const CacheRead none = read_cache_file(t.file("absent.bin"), id, 1000);
  CHECK_FALSE(none.payload);
  CHECK(none.rejected.empty());
  CHECK(read_cache_file(path, {"test-table", 3, "rows=5 g=0x1p-1"}, 1000).rejected ==
        "computed for other parameters: key mismatch");
  CHECK(read_cache_file(path, {"test-table", 4, id.key}, 1000)
            .rejected.find("not 'kind test-table 4'") != std::string::npos);
  const std::string header = cache_file_header(id, payload);
  const auto damaged = [&](auto&& damage) {
    std::string file = header + payload;
    damage(file);
    write_text(path, file);
    const CacheRead r = read_cache_file(path, id, 1000);
    CHECK_FALSE(r.payload);
    return r.rejected;
  };
  // Overwritten at the same size (the failure the issue names: NaNs in place of the table).
  CHECK(damaged([&](std::string& f) {
          const double nan = std::nan("");
          for (size_t at = header.size(); at + 8 <= f.size(); at += 8) std::memcpy(&f[at], &nan, 8);
        }).find("checksum") != std::string::npos);
  // One flipped bit anywhere: payload, key, size or checksum.
  for (size_t at : {header.size() + 500, size_t(30), header.size() - 3, header.size() - 25}) {
    CAPTURE(at);
    CHECK_FALSE(damaged([&](std::string& f) { f[at] = char(f[at] ^ 0x10); }).empty());
  }
  CHECK(damaged([](std::string& f) { f.resize(f.size() - 1); }).find("truncated") !=
        std::string::npos);
  CHECK(damaged([](std::string& f) { f += "x"; }).find("truncated or extended") !=
        std::string::npos);
  CHECK(damaged([](std::string& f) { f.resize(10); }).find("not a masav cache file") !=
        std::string::npos);
  CHECK(damaged([](std::string& f) { f = "junk"; }).find("not a masav cache file") !=
        std::string::npos);
  // A directory where the file should be is noted, not thrown.
  std::filesystem::remove(path);
  std::filesystem::create_directories(path);
  CHECK(read_cache_file(path, id, 1000).rejected.find("is a directory") != std::string::npos);
  // The writer leaves no temporary file behind.
  std::filesystem::remove_all(path);
  write_cache_file(path, id, payload);
  size_t files = 0;
  for (const auto& e : std::filesystem::directory_iterator(t.path)) files += e.is_regular_file();
  CHECK(files == 1);
}
