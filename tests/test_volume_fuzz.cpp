// Deterministic fuzzing of the volume readers: seeded mutations of valid NRRD (attached and
// detached, raw and ASCII), VTI (ASCII, base64, appended raw) and raw files. Every mutant must
// either load (finite values, dims in range) or throw masav::Error with a message; any other
// exception fails the test, a crash kills it and a hang runs into its ctest timeout.
// MASAV_FUZZ_MUTANTS sets the number of mutants (default 400; the `stress` run uses more).
#include <doctest/doctest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "engine/atom/atom_export.h"
#include "engine/core/error.h"
#include "engine/volume/volume_io.h"

using namespace masav;
using namespace masav::atom;
using namespace masav::volume;

namespace {

struct Seed {
  const char* name;
  std::string file;  // the mutated file
  std::function<ScalarVolume(const std::string&)> load;
};

std::string read(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

void write(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

std::string u16_ramp(size_t n) {
  std::string s;
  for (uint16_t i = 0; i < n; ++i) s.append(reinterpret_cast<const char*>(&i), 2);
  return s;
}

// Tokens that have broken parsers: sizes that wrap 32 or 64 bits, signs, fractions, special
// numbers, header fields, paths that never end.
const std::vector<std::string> kTokens = {"0",
                                          "1",
                                          "-1",
                                          "2",
                                          "8192",
                                          "8193",
                                          "4294967312",
                                          "4294967296",
                                          "18446744073709551616",
                                          "9223372036854775807",
                                          "-9223372036854775808",
                                          "1e308",
                                          "nan",
                                          "inf",
                                          "0.5",
                                          "",
                                          "sizes: ",
                                          "line skip: 3\n",
                                          "byte skip: -1\n",
                                          "byte skip: 99999999999\n",
                                          "data file: /dev/zero\n",
                                          "encoding: ascii\n",
                                          "type: double\n",
                                          "dimension: 4\n",
                                          "\n\n",
                                          "\"",
                                          "<",
                                          ">",
                                          "_",
                                          "offset=\"7\"",
                                          "format=\"appended\"",
                                          "header_type=\"UInt64\"",
                                          "byte_order=\"BigEndian\"",
                                          "WholeExtent=\"0 4294967311 0 1 0 1\""};

std::string mutate(std::string s, std::mt19937_64& rng) {
  const auto pick = [&](size_t n) { return n ? size_t(rng() % n) : 0; };
  const int edits = 1 + int(rng() % 3);
  for (int e = 0; e < edits; ++e) {
    const size_t at = pick(s.size() + 1);
    switch (rng() % 8) {
      case 0:  // flip bits of a byte
        if (!s.empty()) s[pick(s.size())] ^= char(1u << (rng() % 8));
        break;
      case 1:  // a random byte
        if (!s.empty()) s[pick(s.size())] = char(rng());
        break;
      case 2:  // delete a range
        s.erase(at, 1 + pick(16));
        break;
      case 3:  // insert a token
        s.insert(at, kTokens[pick(kTokens.size())]);
        break;
      case 4: {  // replace a run of digits with a token
        const size_t d = s.find_first_of("0123456789", at);
        if (d == std::string::npos) break;
        const size_t end = s.find_first_not_of("0123456789", d);
        s.replace(d, (end == std::string::npos ? s.size() : end) - d, kTokens[pick(16)]);
        break;
      }
      case 5:  // truncate
        s.resize(at);
        break;
      case 6: {  // duplicate a line
        const size_t b = s.rfind('\n', at == 0 ? 0 : at - 1);
        const size_t begin = b == std::string::npos ? 0 : b + 1;
        const size_t end = s.find('\n', begin);
        if (end != std::string::npos) s.insert(begin, s.substr(begin, end - begin + 1));
        break;
      }
      default:  // append bytes
        for (int i = int(rng() % 40); i > 0; --i) s.push_back(char(rng()));
    }
  }
  return s;
}

int mutant_count() {
  if (const char* n = std::getenv("MASAV_FUZZ_MUTANTS")) return std::max(1, std::atoi(n));
  return 400;
}

}  // namespace

TEST_CASE("volume header fuzz: every mutant loads or throws masav::Error with a message") {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("masav_volume_fuzz_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto file = [&](const std::string& n) { return (dir / n).string(); };

  // Valid seeds, each checked to load before it is mutated.
  const std::string ramp = u16_ramp(24);
  write(file("d.raw"), ramp);
  const std::string head =
      "NRRD0004\ntype: uint16\ndimension: 3\nsizes: 4 3 2\nencoding: raw\n"
      "endian: little\nspacings: 1 1 2\nspace origin: (0,0,0)\n";
  write_scalar_vti(make_volume_desc({3, 2, 2}, {0, 0, 0}, {1, 1, 1}),
                   {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11}, "v", file("binary.vti"));
  const std::string vti_head =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"1.0\" "
      "byte_order=\"LittleEndian\" header_type=\"UInt32\">\n"
      "<ImageData WholeExtent=\"0 1 0 1 0 1\" Origin=\"0 0 0\" Spacing=\"1 1 1\">\n"
      "<Piece Extent=\"0 1 0 1 0 1\"><PointData>\n";
  std::string appended =
      vti_head +
      "<DataArray type=\"UInt16\" Name=\"v\" format=\"appended\" offset=\"0\"/>\n"
      "</PointData></Piece></ImageData>\n<AppendedData encoding=\"raw\">\n_";
  const uint32_t n16 = 16;
  appended.append(reinterpret_cast<const char*>(&n16), 4);
  appended += u16_ramp(8) + "\n</AppendedData></VTKFile>\n";
  const std::vector<Seed> seeds = {
      {"attached.nrrd", head + "\n" + ramp, load_nrrd},
      {"detached.nhdr", head + "line skip: 0\nbyte skip: 0\ndata file: d.raw\n", load_nrrd},
      {"ascii.nrrd",
       "NRRD0004\ntype: float\ndimension: 3\nsizes: 2 2 2\nencoding: ascii\n\n1 2 3 4 5 6 7 8\n",
       load_nrrd},
      {"ascii.vti",
       vti_head + "<DataArray type=\"Float32\" Name=\"v\" format=\"ascii\">1 2 3 4 5 6 7 8"
                  "</DataArray>\n</PointData></Piece></ImageData></VTKFile>\n",
       [](const std::string& p) { return load_vti(p); }},
      {"binary.vti", read(file("binary.vti")), [](const std::string& p) { return load_vti(p); }},
      {"appended.vti", appended, [](const std::string& p) { return load_vti(p); }},
      {"a.raw", ramp,
       [](const std::string& p) {
         return load_raw(p, {4, 3, 2}, SampleType::u16);
       }},
  };
  for (const Seed& s : seeds) {
    CAPTURE(s.name);
    write(file(s.name), s.file);
    CHECK_NOTHROW(s.load(file(s.name)));
  }

  std::mt19937_64 rng(20261126);
  const int mutants = mutant_count();
  int loaded = 0, refused = 0;
  for (int i = 0; i < mutants; ++i) {
    const Seed& s = seeds[size_t(i) % seeds.size()];
    const std::string bytes = mutate(s.file, rng);
    write(file(s.name), bytes);
    try {
      const ScalarVolume v = s.load(file(s.name));
      for (uint32_t d : {v.dims.x, v.dims.y, v.dims.z}) CHECK((d >= 2 && d <= 8192));
      CHECK(v.values.size() == size_t(v.dims.x) * v.dims.y * v.dims.z);
      CHECK(std::isfinite(v.min));
      ++loaded;
    } catch (const Error& e) {
      CHECK(std::string(e.what()).size() > 10);
      ++refused;
    } catch (const std::exception& e) {
      FAIL("mutant ", i, " of ", s.name, " threw a non-masav exception: ", e.what(),
           "\n--- mutant bytes ---\n", bytes);
    }
  }
  MESSAGE(mutants, " mutants: ", loaded, " loaded, ", refused, " refused with a message");
  CHECK(loaded + refused == mutants);
  CHECK(refused > 0);  // the mutations do reach the checks
  std::filesystem::remove_all(dir);
}
