// Deterministic fuzzing of the SPH checkpoint reader: seeded mutants of a valid checkpoint
// (bytes flipped, cut short, length and count fields set huge, fields overwritten with hostile
// numbers), most with their sections' checksums recomputed so that they get past the framing to
// the field checks (sph_resume_checks.h). Every mutant must either load a state that passes
// validation -- and then restores into a simulation of its scene and takes a step or stops with
// masav::Error -- or be refused with masav::Error. Any other exception fails the test, a crash
// kills it, a hang runs into its ctest timeout; the reader allocates no more than the file holds.
// "checkpoint fuzz" runs 300 mutants (ctest fuzz.checkpoints); "checkpoint fuzz stress" 20000
// (fuzz.checkpoints.stress, label stress; skipped unless asked for by name with --no-skip).
#include <doctest/doctest.h>
#include <fmt/format.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "engine/sph/sph_resume_checks.h"
#include "tests/sph_checkpoint_fixture.h"
#include "tests/temp_dir.h"

using namespace masav;

namespace {

using Bytes = std::vector<uint8_t>;
using Rng = std::mt19937_64;

size_t pick(Rng& rng, size_t n) {
  return std::uniform_int_distribution<size_t>(0, n - 1)(rng);
}

Bytes read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(in), {});
}

void write_file(const std::string& path, const Bytes& b) {
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(b.data()), std::streamsize(b.size()));
}

template <class T>
std::optional<T> load(const Bytes& b, size_t at) {
  if (at > b.size() || b.size() - at < sizeof(T)) return std::nullopt;
  T v;
  std::memcpy(&v, b.data() + at, sizeof(T));
  return v;
}

template <class T>
void store(Bytes& b, size_t at, T v) {
  if (at <= b.size() && b.size() - at >= sizeof(T)) std::memcpy(b.data() + at, &v, sizeof(T));
}

// A section of the file (format in engine/sph/sph_checkpoint.h): where its header and payload
// start and the payload's bytes, as far as the (possibly mutated) file says.
struct Section {
  size_t header = 0, payload = 0, bytes = 0;
};

std::vector<Section> sections(const Bytes& b) {
  std::vector<Section> out;
  const auto writer = load<uint32_t>(b, 16);
  if (!writer) return out;
  size_t at = 20 + size_t(*writer);
  for (int i = 0; i < 3; ++i) {
    const auto bytes = load<uint64_t>(b, at + 8);
    if (!bytes || at + 24 > b.size() || *bytes > b.size() - (at + 24)) break;
    out.push_back({at, at + 24, size_t(*bytes)});
    at += 24 + size_t(*bytes);
  }
  return out;
}

// The checksums of every section the file still frames, made to match its bytes again.
void fix_checksums(Bytes& b) {
  for (const Section& s : sections(b))
    store(b, s.header + 16, fnv1a64(std::span<const uint8_t>(b.data() + s.payload, s.bytes)));
}

const std::vector<double> kHostileReals = {std::numeric_limits<double>::quiet_NaN(),
                                           std::numeric_limits<double>::infinity(),
                                           -std::numeric_limits<double>::infinity(),
                                           -1.0,
                                           0.0,
                                           -0.0,
                                           1e308,
                                           -1e308,
                                           1e-308,
                                           4.9e-324,
                                           1e6,
                                           2.5};
const std::vector<uint64_t> kHostileCounts = {0,
                                              1,
                                              2,
                                              299,
                                              301,
                                              UINT32_MAX,
                                              uint64_t(UINT32_MAX) + 1,
                                              uint64_t(1) << 40,
                                              uint64_t(1) << 53,
                                              UINT64_MAX / 16,
                                              UINT64_MAX - 1,
                                              UINT64_MAX};

// One to three mutations of a valid checkpoint `b`; usually its checksums recomputed after.
Bytes mutate(Bytes b, Rng& rng) {
  const int count = 1 + int(pick(rng, 3));
  for (int m = 0; m < count && !b.empty(); ++m) {
    const std::vector<Section> s = sections(b);
    // Most mutations aim inside one section's payload, where the field checks are.
    size_t lo = 0, hi = b.size();
    if (!s.empty() && pick(rng, 4) != 0) {
      const Section& sec = s[pick(rng, s.size())];
      if (sec.bytes > 0) lo = sec.payload, hi = sec.payload + sec.bytes;
    }
    const size_t at = lo + pick(rng, hi - lo);
    switch (pick(rng, 8)) {
      case 0:  // a byte flipped, one bit or all of them
        b[at] ^= pick(rng, 2) ? uint8_t(1u << pick(rng, 8)) : uint8_t(pick(rng, 256));
        break;
      case 1:  // cut short
        b.resize(pick(rng, b.size() + 1));
        break;
      case 2: {  // a section's payload length set huge or off by a little
        if (s.empty()) break;
        const Section& sec = s[pick(rng, s.size())];
        const uint64_t v = pick(rng, 2) ? kHostileCounts[pick(rng, kHostileCounts.size())]
                                        : uint64_t(sec.bytes) + pick(rng, 17) - 8;
        store(b, sec.header + 8, v);
        break;
      }
      case 3:  // the writer's version length
        store(b, 16, uint32_t(kHostileCounts[pick(rng, kHostileCounts.size())]));
        break;
      case 4:  // an 8-byte field (a real, a counter, an array's count) set to a hostile value
        if (pick(rng, 2))
          store(b, at & ~size_t(7), kHostileReals[pick(rng, kHostileReals.size())]);
        else
          store(b, at & ~size_t(7), kHostileCounts[pick(rng, kHostileCounts.size())]);
        break;
      case 5:  // the same, unaligned (the sections' fields are packed)
        if (pick(rng, 2))
          store(b, at, kHostileReals[pick(rng, kHostileReals.size())]);
        else
          store(b, at, kHostileCounts[pick(rng, kHostileCounts.size())]);
        break;
      case 6:  // one of STAT's first eight fields: the count, time, the dts, the counters
        if (s.size() > 1) {
          const size_t field = s[1].payload + 8 * pick(rng, 8);
          if (pick(rng, 2))
            store(b, field, kHostileReals[pick(rng, kHostileReals.size())]);
          else
            store(b, field, kHostileCounts[pick(rng, kHostileCounts.size())]);
        }
        break;
      default:  // a 4-byte field (an enum, a flag pair, a u32 count, a string length)
        store(b, at, uint32_t(kHostileCounts[pick(rng, kHostileCounts.size())]));
    }
  }
  if (pick(rng, 8) != 0) fix_checksums(b);
  return b;
}

struct Tally {
  int loaded = 0, refused = 0, stepped = 0;
};

void fuzz(int mutants) {
  test::TempDir dir("checkpoint_fuzz");
  const test::CheckpointCase c(make_preset("water", 300), 10);
  const std::string good = dir.file("good.masav");
  write_sph_checkpoint(good, c.scene, c.state);
  const Bytes valid = read_file(good);
  const std::string path = dir.file("mutant.masav");
  Rng rng(20260045);
  Tally t;
  for (int i = 0; i < mutants; ++i) {
    const Bytes b = mutate(valid, rng);
    write_file(path, b);
    INFO(fmt::format("mutant {} ({} bytes)", i, b.size()));
    try {
      const SphCheckpoint k = read_sph_checkpoint(path);
      ++t.loaded;
      CHECK_NOTHROW(validate_resume_state(k.scene, k.state));
      // A state that loads is one a simulation of its scene takes, and continues from.
      if (sph_scene_difference(k.scene, c.scene).empty()) {
        CHECK_NOTHROW(restore_sph_checkpoint(*c.sim, k, path));
        const double t0 = c.sim->time();
        const uint64_t steps0 = c.sim->steps();
        try {
          c.sim->step();
          ++t.stepped;
          // It goes on: a step later, at a later finite time (a NaN time never reaches an end).
          CHECK(c.sim->steps() == steps0 + 1);
          CHECK(std::isfinite(c.sim->time()));
          CHECK(c.sim->time() > t0);
        } catch (const Error&) {
          // A watchdog or the CFL guard may stop it: with a message, which is what counts.
        }
      }
    } catch (const Error& e) {
      ++t.refused;
      CHECK(std::string(e.what()).size() > 10);
    } catch (const std::exception& e) {
      FAIL_CHECK("not a masav::Error: " << e.what());
    }
  }
  MESSAGE(fmt::format("{} mutants: {} loaded ({} stepped on), {} refused with a message", mutants,
                      t.loaded, t.stepped, t.refused));
  CHECK(t.loaded > 0);  // some mutants are harmless (a velocity's last bit)
  CHECK(t.refused > t.loaded);
}

}  // namespace

TEST_CASE("checkpoint fuzz") {
  fuzz(300);
}

TEST_CASE("checkpoint fuzz stress" * doctest::skip()) {
  fuzz(20000);
}
