#include "engine/core/tuning.h"

#include <fmt/format.h>

#include <array>
#include <charconv>
#include <functional>
#include <vector>

#include "engine/core/error.h"

namespace masav {
namespace {

constexpr std::string_view kSwitch = "auto, on or off";

// One option: its documentation, and how it reads and writes its field as text.
struct Option {
  TuningKey doc;
  std::function<void(Tuning&, std::string_view)> set;
  std::function<std::string(const Tuning&)> get;  // "" where automatic (or 0)
};

[[noreturn]] void bad_value(std::string_view key, std::string_view value,
                            std::string_view allowed) {
  throw_invalid("--tune", key, value, allowed);
}

Choice parse_choice(std::string_view key, std::string_view v) {
  if (v == "auto") return Choice::automatic;
  if (v == "on") return Choice::on;
  if (v == "off") return Choice::off;
  bad_value(key, v, kSwitch);
}
std::string choice_text(Choice c) {
  return c == Choice::automatic ? "" : c == Choice::on ? "on" : "off";
}

// A whole number in [1, most], or auto (0).
uint64_t parse_count(std::string_view key, std::string_view v, uint64_t most) {
  if (v == "auto") return 0;
  uint64_t n = 0;
  const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), n);
  if (ec != std::errc() || end != v.data() + v.size() || n < 1 || n > most)
    bad_value(key, v, fmt::format("auto or a whole number from 1 to {}", most));
  return n;
}
std::string count_text(uint64_t n) {
  return n ? std::to_string(n) : "";
}

// A named choice among `names` (index 0: automatic, spelled "auto").
template <class E, size_t N>
E parse_named(std::string_view key, std::string_view v, const std::array<std::string_view, N>& names,
              std::string_view allowed) {
  for (size_t i = 0; i < N; ++i)
    if (v == names[i]) return E(i);
  bad_value(key, v, allowed);
}

constexpr std::array<std::string_view, 3> kSortNames = {"auto", "tiled", "subgroup"};
constexpr std::array<std::string_view, 3> kWalkNames = {"auto", "cooperative", "lanes"};
constexpr std::array<std::string_view, 3> kPrecisionNames = {"auto", "fp64", "fp32"};
constexpr std::array<std::string_view, 4> kSimdNames = {"auto", "generic", "avx2", "avx512"};

// A named option's text: "" where automatic.
template <size_t N>
std::string named_text(size_t index, const std::array<std::string_view, N>& names) {
  return index == 0 ? std::string() : std::string(names[index]);
}

#define MASAV_SWITCH(key, field, automatic, description)                                     \
  Option {                                                                                   \
    {key, kSwitch, automatic, description},                                                  \
        [](Tuning& t, std::string_view v) { t.field = parse_choice(key, v); },               \
        [](const Tuning& t) { return choice_text(t.field); }                                 \
  }

const std::vector<Option>& options() {
  static const std::vector<Option> all = {
      {{"cpu.threads", "auto or 1 to 1024", "the hardware's threads",
        "worker threads of the CPU backend"},
       [](Tuning& t, std::string_view v) { t.cpu.threads = uint32_t(parse_count("cpu.threads", v, 1024)); },
       [](const Tuning& t) { return count_text(t.cpu.threads); }},
      {{"cpu.sph_precision", "auto, fp64 or fp32", "fp64",
        "the precision of the CPU backend's SPH kernels (density, forces, the DFSPH solves)"},
       [](Tuning& t, std::string_view v) {
         t.cpu.sph_precision = parse_named<CpuSphPrecision>("cpu.sph_precision", v,
                                                            kPrecisionNames, "auto, fp64 or fp32");
       },
       [](const Tuning& t) { return named_text(size_t(t.cpu.sph_precision), kPrecisionNames); }},
      {{"cpu.sph_simd", "auto, generic, avx2 or avx512", "the widest this CPU runs",
        "the instruction set of the fp32 SPH pair loops (the same bits with each)"},
       [](Tuning& t, std::string_view v) {
         t.cpu.sph_simd = parse_named<CpuSphSimd>("cpu.sph_simd", v, kSimdNames,
                                                  "auto, generic, avx2 or avx512");
       },
       [](const Tuning& t) { return named_text(size_t(t.cpu.sph_simd), kSimdNames); }},
      {{"vulkan.sort_scatter", "auto, tiled or subgroup", "subgroup on a CPU device, else tiled",
        "the radix sort's scatter pass"},
       [](Tuning& t, std::string_view v) {
         t.vulkan.sort_scatter =
             parse_named<SortScatter>("vulkan.sort_scatter", v, kSortNames, "auto, tiled or subgroup");
       },
       [](const Tuning& t) { return named_text(size_t(t.vulkan.sort_scatter), kSortNames); }},
      {{"vulkan.sph_walk", "auto, cooperative or lanes", "cooperative on a CPU device, else lanes",
        "how the SPH kernels walk a particle's neighbour rows"},
       [](Tuning& t, std::string_view v) {
         t.vulkan.sph_walk =
             parse_named<SphWalk>("vulkan.sph_walk", v, kWalkNames, "auto, cooperative or lanes");
       },
       [](const Tuning& t) { return named_text(size_t(t.vulkan.sph_walk), kWalkNames); }},
      MASAV_SWITCH("vulkan.sph_wall_split", vulkan.sph_wall_split,
                   "sph_density always; the others on a CPU device",
                   "a second copy of the SPH walks without wall images, for subgroups far from "
                   "the walls"),
      MASAV_SWITCH("vulkan.sph_images_after", vulkan.sph_images_after, "on a GPU, off on a CPU device",
                   "sph_forces adds the wall images after its masked walk"),
      MASAV_SWITCH("vulkan.raymarch_quads", vulkan.raymarch_quads, "on a CPU device, off on a GPU",
                   "raymarch reads the volume four voxels to a texel"),
      MASAV_SWITCH("vulkan.replay", vulkan.replay, "on",
                   "a recorded block of SPH steps replays an equal earlier recording"),
      {{"vulkan.max_buffer_mib", "auto or 1 to 1048576", "the device's own limit",
        "the largest buffer a kernel may bind, lowered (tests)"},
       [](Tuning& t, std::string_view v) {
         t.vulkan.max_buffer_mib = parse_count("vulkan.max_buffer_mib", v, uint64_t(1) << 20);
       },
       [](const Tuning& t) { return count_text(t.vulkan.max_buffer_mib); }},
      {{"vulkan.max_texels", "auto or 1 to 4294967296", "the device's own limit",
        "the most texels a texel buffer may span, lowered (tests)"},
       [](Tuning& t, std::string_view v) {
         t.vulkan.max_texels = parse_count("vulkan.max_texels", v, uint64_t(1) << 32);
       },
       [](const Tuning& t) { return count_text(t.vulkan.max_texels); }},
      MASAV_SWITCH("cuda.graphs", cuda.graphs, "off",
                   "a block of SPH steps launched as one CUDA graph"),
      MASAV_SWITCH("cuda.sph_images_after", cuda.sph_images_after, "on",
                   "sph_forces adds the wall images in a walk of their own after the direct terms"),
      {{"cuda.sync_each_launch", "on or off", "off",
        "wait for every kernel so that a fault names it (debugging, slow)"},
       [](Tuning& t, std::string_view v) {
         if (v != "on" && v != "off") bad_value("cuda.sync_each_launch", v, "on or off");
         t.cuda.sync_each_launch = v == "on";
       },
       [](const Tuning& t) { return t.cuda.sync_each_launch ? std::string("on") : std::string(); }},
      MASAV_SWITCH("sph.neighbor_state", sph.neighbor_state, "on where it fits the memory budget",
                   "sph_forces reads sph_density's packed neighbour records"),
  };
  return all;
}
#undef MASAV_SWITCH

std::string key_list() {
  std::string s;
  for (const Option& o : options()) s += (s.empty() ? "" : ", ") + std::string(o.doc.key);
  return s;
}

}  // namespace

std::span<const TuningKey> tuning_keys() {
  static const std::vector<TuningKey> keys = [] {
    std::vector<TuningKey> k;
    for (const Option& o : options()) k.push_back(o.doc);
    return k;
  }();
  return keys;
}

void set_tuning(Tuning& t, std::string_view assignment) {
  const size_t eq = assignment.find('=');
  if (eq == std::string_view::npos)
    throw_invalid("--tune", "option", assignment, fmt::format("key=value, key one of {}", key_list()));
  const std::string_view key = assignment.substr(0, eq), value = assignment.substr(eq + 1);
  for (const Option& o : options())
    if (o.doc.key == key) return o.set(t, value);
  throw_invalid("--tune", "key", key, key_list());
}

std::string describe(const Tuning& t) {
  std::string s;
  for (const Option& o : options())
    if (const std::string v = o.get(t); !v.empty())
      s += fmt::format("{}{}={}", s.empty() ? "" : " ", o.doc.key, v);
  return s;
}

}  // namespace masav
