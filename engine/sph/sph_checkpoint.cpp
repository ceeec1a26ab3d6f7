#include "engine/sph/sph_checkpoint.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <bit>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>
#include <type_traits>
#include <vector>

#include "engine/core/error.h"

#ifndef MASAV_VERSION
#define MASAV_VERSION "unknown"
#endif

namespace masav {

static_assert(std::endian::native == std::endian::little,
              "checkpoints are little-endian, written and read as the host's bytes");

namespace {

constexpr char kMagic[8] = {'M', 'A', 'S', 'A', 'V', 'S', 'P', 'H'};
constexpr uint32_t kSectionCount = 3;
constexpr uint32_t kMaxWriterBytes = 64;
constexpr uint32_t kMaxPresetBytes = 256;
constexpr const char* kRemedy =
    "restart from an intact checkpoint (the run keeps only the newest: copy it away to keep "
    "more), or start the run again";

constexpr uint32_t tag(const char (&t)[5]) {
  return uint32_t(uint8_t(t[0])) | uint32_t(uint8_t(t[1])) << 8 | uint32_t(uint8_t(t[2])) << 16 |
         uint32_t(uint8_t(t[3])) << 24;
}
constexpr char kSectionNames[kSectionCount][5] = {"SCEN", "STAT", "PART"};

[[noreturn]] void fail(const std::string& path, std::string_view field, std::string_view problem) {
  throw Error("", "sph checkpoint", fmt::format("{}: {}: {}", path, field, problem), kRemedy);
}

// ---- writing

class Out {
 public:
  template <class T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto* p = reinterpret_cast<const uint8_t*>(&v);
    bytes_.insert(bytes_.end(), p, p + sizeof(T));
  }
  template <class T>
  void array(const std::vector<T>& v) {
    put(uint64_t(v.size()));
    const auto* p = reinterpret_cast<const uint8_t*>(v.data());
    bytes_.insert(bytes_.end(), p, p + v.size() * sizeof(T));
  }
  void string(const std::string& s) {
    put(uint32_t(s.size()));
    bytes_.insert(bytes_.end(), s.begin(), s.end());
  }
  std::vector<uint8_t>& bytes() { return bytes_; }

 private:
  std::vector<uint8_t> bytes_;
};

// ---- reading: a bounded cursor over one section's payload

class In {
 public:
  In(std::span<const uint8_t> b, const std::string& path, std::string section)
      : b_(b), path_(path), section_(std::move(section)) {}

  template <class T>
  T get(std::string_view field) {
    static_assert(std::is_trivially_copyable_v<T>);
    need(sizeof(T), field);
    T v;
    std::memcpy(&v, b_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return v;
  }
  bool flag(std::string_view field) {
    const uint8_t v = get<uint8_t>(field);
    if (v > 1) fail(path_, name(field), fmt::format("{} where 0 or 1 was expected", v));
    return v == 1;
  }
  double real(std::string_view field) { return get<double>(field); }
  template <class E>
  E enumeration(std::string_view field, E last) {
    const uint32_t v = get<uint32_t>(field);
    if (v > uint32_t(last))
      fail(path_, name(field), fmt::format("{} where 0 to {} was expected", v, uint32_t(last)));
    return E(v);
  }
  // `count` values exactly (0 or the particle count), checked against the bytes left before
  // anything is allocated.
  template <class T>
  std::vector<T> array(std::string_view field, uint64_t count) {
    const uint64_t n = get<uint64_t>(field);
    if (n != count)
      fail(path_, name(field), fmt::format("{} values where {} were expected", n, count));
    if (n > (b_.size() - pos_) / sizeof(T))
      fail(path_, name(field),
           fmt::format("{} values need {} bytes, the section has {} left (truncated?)", n,
                       n * sizeof(T), b_.size() - pos_));
    std::vector<T> v(n);
    std::memcpy(v.data(), b_.data() + pos_, n * sizeof(T));
    pos_ += n * sizeof(T);
    return v;
  }
  std::string string(std::string_view field, uint32_t max_bytes) {
    const uint32_t n = get<uint32_t>(field);
    if (n > max_bytes)
      fail(path_, name(field),
           fmt::format("{} bytes where at most {} were expected", n, max_bytes));
    need(n, field);
    std::string s(reinterpret_cast<const char*>(b_.data() + pos_), n);
    pos_ += n;
    return s;
  }
  void end() {
    if (pos_ != b_.size())
      fail(path_, section_,
           fmt::format("{} bytes past its last field (a file of another layout?)",
                       b_.size() - pos_));
  }

 private:
  std::string name(std::string_view field) const { return fmt::format("{}.{}", section_, field); }
  void need(uint64_t bytes, std::string_view field) {
    if (bytes > b_.size() - pos_)
      fail(path_, name(field),
           fmt::format("needs {} bytes, the section has {} left (truncated?)", bytes,
                       b_.size() - pos_));
  }
  std::span<const uint8_t> b_;
  size_t pos_ = 0;
  const std::string& path_;
  std::string section_;
};

// ---- the scene, field by field (every field of SphScene: each one changes the run)

struct SceneWriter {
  Out& out;
  void operator()(const char*, const std::string& v) { out.string(v); }
  void operator()(const char*, uint32_t v) { out.put(v); }
  void operator()(const char*, uint64_t v) { out.put(v); }
  void operator()(const char*, double v) { out.put(v); }
  void operator()(const char*, bool v) { out.put(uint8_t(v)); }
  void operator()(const char*, const Vec3d& v) {
    out.put(v.x);
    out.put(v.y);
    out.put(v.z);
  }
  void operator()(const char*, const std::optional<double>& v) {
    out.put(uint8_t(v.has_value()));
    out.put(v.value_or(0.0));
  }
  template <class E>
  requires std::is_enum_v<E>
  void operator()(const char*, E v) { out.put(uint32_t(v)); }
};

struct SceneReader {
  In& in;
  void operator()(const char* f, std::string& v) { v = in.string(f, kMaxPresetBytes); }
  void operator()(const char* f, uint32_t& v) { v = in.get<uint32_t>(f); }
  void operator()(const char* f, uint64_t& v) { v = in.get<uint64_t>(f); }
  void operator()(const char* f, double& v) { v = in.real(f); }
  void operator()(const char* f, bool& v) { v = in.flag(f); }
  void operator()(const char* f, Vec3d& v) {
    v.x = in.real(f);
    v.y = in.real(f);
    v.z = in.real(f);
  }
  void operator()(const char* f, std::optional<double>& v) {
    const bool has = in.flag(f);
    const double x = in.real(f);
    v = has ? std::optional<double>(x) : std::nullopt;
  }
  void operator()(const char* f, SphPressureModel& v) {
    v = in.enumeration(f, SphPressureModel::dfsph);
  }
  void operator()(const char* f, SphIntegrator& v) {
    v = in.enumeration(f, SphIntegrator::leapfrog);
  }
  void operator()(const char* f, SphCflGuard& v) { v = in.enumeration(f, SphCflGuard::off); }
};

template <class S, class F>
void visit_scene(S& s, F&& f) {
  f("preset", s.preset);
  f("particles", s.particles);
  f("block.min", s.block.min);
  f("block.max", s.block.max);
  f("block.velocity", s.block.velocity);
  f("block.density_ratio", s.block.density_ratio);
  f("block.hydrostatic", s.block.hydrostatic);
  f("obstacle.enabled", s.obstacle.enabled);
  f("obstacle.min", s.obstacle.min);
  f("obstacle.max", s.obstacle.max);
  f("obstacle.mass_ratio", s.obstacle.mass_ratio);
  f("obstacle.pinned", s.obstacle.pinned);
  f("model", s.model);
  f("rest_density", s.rest_density);
  f("h_over_dx", s.h_over_dx);
  f("smoothing_radius", s.smoothing_radius);
  f("viscosity", s.viscosity);
  f("sound_speed", s.sound_speed);
  f("kp", s.kp);
  f("clamp_negative_pressure", s.clamp_negative_pressure);
  f("dfsph_density_error", s.dfsph_density_error);
  f("dfsph_divergence_error", s.dfsph_divergence_error);
  f("dfsph_max_iterations", s.dfsph_max_iterations);
  f("gravity", s.gravity);
  f("box_min", s.box_min);
  f("box_max", s.box_max);
  f("walls", s.walls);
  f("restitution", s.restitution);
  f("tangential_damping", s.tangential_damping);
  f("integrator", s.integrator);
  f("dt", s.dt);
  f("cfl_velocity", s.cfl_velocity);
  f("cfl_force", s.cfl_force);
  f("cfl_viscous", s.cfl_viscous);
  f("dt_max", s.dt_max);
  f("dt_min", s.dt_min);
  f("cfl_guard", s.cfl_guard);
  f("rk4_skin", s.rk4_skin);
  f("max_candidates", s.max_candidates);
  f("seed", s.seed);
  f("jitter", s.jitter);
}

void put_stats(Out& o, const SphStepStats& s) {
  o.put(s.max_speed);
  o.put(s.max_accel);
  o.put(s.max_drift);
  o.put(s.max_density);
  o.put(s.max_candidates);
  o.put(s.max_neighbors);
  o.put(s.outside);
}

SphStepStats get_stats(In& in, const char* field) {
  SphStepStats s;
  s.max_speed = in.real(field);
  s.max_accel = in.real(field);
  s.max_drift = in.real(field);
  s.max_density = in.real(field);
  s.max_candidates = in.get<uint32_t>(field);
  s.max_neighbors = in.get<uint32_t>(field);
  s.outside = in.get<uint32_t>(field);
  return s;
}

std::vector<uint8_t> scene_bytes(const SphScene& s) {
  Out o;
  visit_scene(s, SceneWriter{o});
  return std::move(o.bytes());
}

std::vector<uint8_t> state_bytes(const SphResumeState& r) {
  Out o;
  o.put(uint64_t(r.positions.size()));
  o.put(r.time);
  o.put(r.last_dt);
  o.put(r.adaptive_dt);
  o.put(r.steps);
  o.put(r.substeps);
  o.put(r.retries);
  o.put(r.block_replays);
  put_stats(o, r.stats);
  put_stats(o, r.lag_stats);
  const SphSolveStats& ss = r.solve_stats;
  o.put(ss.steps);
  o.put(ss.density_iterations);
  o.put(ss.divergence_iterations);
  o.put(ss.unconverged);
  o.put(ss.last_density_error);
  o.put(ss.last_divergence_error);
  o.put(uint8_t(r.accel_valid));
  o.put(uint8_t(r.fields_current));
  o.put(uint8_t(r.kappa_warm));
  o.put(r.block_steps);
  o.put(uint8_t(!r.block_stats.empty()));
  if (!r.block_stats.empty()) {
    o.put(r.block_limit);
    o.array(r.block_stats);
  }
  o.put(r.watchdog.max_speed);
  o.put(r.watchdog.max_density);
  o.put(r.watchdog.energy0);
  o.put(r.next_energy_check);
  o.put(r.good_time);
  o.put(r.good_last_dt);
  o.put(r.good_steps);
  o.put(r.good_substeps);
  put_stats(o, r.good_stats);
  o.put(uint8_t(!r.kappa_density.empty()));
  return std::move(o.bytes());
}

std::vector<uint8_t> particle_bytes(const SphResumeState& r) {
  Out o;
  o.array(r.positions);
  o.array(r.velocities);
  o.array(r.accel);
  o.array(r.ids);
  o.array(r.density);
  o.array(r.pressure);
  o.array(r.kappa_density);
  o.array(r.kappa_divergence);
  o.array(r.good_positions);
  o.array(r.good_velocities);
  return std::move(o.bytes());
}

// ---- files

class File {
 public:
  File(const std::string& path, int flags) : path_(path), fd_(::open(path.c_str(), flags, 0644)) {}
  ~File() {
    if (fd_ >= 0) ::close(fd_);
  }
  File(const File&) = delete;
  File& operator=(const File&) = delete;
  bool ok() const { return fd_ >= 0; }
  int fd() const { return fd_; }
  void write_all(const void* data, size_t bytes) {
    const auto* p = static_cast<const uint8_t*>(data);
    while (bytes > 0) {
      const ssize_t w = ::write(fd_, p, bytes);
      if (w < 0 && errno == EINTR) continue;
      if (w <= 0)
        throw Error("", "sph checkpoint",
                    fmt::format("cannot write '{}': {}", path_, std::strerror(errno)),
                    "check the disk space and the directory's permissions");
      p += w;
      bytes -= size_t(w);
    }
  }
  // Reads exactly `bytes` unless the file ends first; returns the bytes read.
  size_t read_some(void* data, size_t bytes) {
    auto* p = static_cast<uint8_t*>(data);
    size_t done = 0;
    while (done < bytes) {
      const ssize_t r = ::read(fd_, p + done, bytes - done);
      if (r < 0 && errno == EINTR) continue;
      if (r < 0) fail(path_, "file", fmt::format("cannot be read: {}", std::strerror(errno)));
      if (r == 0) break;
      done += size_t(r);
    }
    return done;
  }

 private:
  std::string path_;
  int fd_;
};

}  // namespace

uint64_t fnv1a64(std::span<const uint8_t> bytes) {
  uint64_t h = 0xcbf29ce484222325ull;
  for (const uint8_t b : bytes) {
    h ^= b;
    h *= 0x100000001b3ull;
  }
  return h;
}

void write_sph_checkpoint(const std::string& path, const SphScene& scene,
                          const SphResumeState& state) {
  const std::vector<uint8_t> sections[kSectionCount] = {scene_bytes(scene), state_bytes(state),
                                                        particle_bytes(state)};
  Out head;
  for (const char c : kMagic) head.put(c);
  head.put(kSphCheckpointVersion);
  head.put(kSectionCount);
  head.string(MASAV_VERSION);
  const std::string tmp = path + ".tmp";
  {
    File f(tmp, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC);
    if (!f.ok())
      throw Error("", "sph checkpoint",
                  fmt::format("cannot create '{}': {}", tmp, std::strerror(errno)),
                  "check that --checkpoint-dir exists and is writable");
    try {
      f.write_all(head.bytes().data(), head.bytes().size());
      for (uint32_t i = 0; i < kSectionCount; ++i) {
        Out s;
        s.put(tag(kSectionNames[i]));
        s.put(uint32_t(0));
        s.put(uint64_t(sections[i].size()));
        s.put(fnv1a64(sections[i]));
        f.write_all(s.bytes().data(), s.bytes().size());
        f.write_all(sections[i].data(), sections[i].size());
      }
      if (::fsync(f.fd()) != 0)
        throw Error("", "sph checkpoint",
                    fmt::format("cannot flush '{}': {}", tmp, std::strerror(errno)),
                    "check the disk");
    } catch (...) {
      std::remove(tmp.c_str());
      throw;
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const int e = errno;
    std::remove(tmp.c_str());
    throw Error("", "sph checkpoint",
                fmt::format("cannot rename '{}' onto '{}': {}", tmp, path, std::strerror(e)),
                "check the directory's permissions");
  }
  // The rename itself is durable once the directory is flushed.
  const std::string dir = std::filesystem::path(path).parent_path().string();
  File d(dir.empty() ? "." : dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (d.ok()) ::fsync(d.fd());
}

void write_sph_checkpoint(const std::string& path, SphSimulation& sim) {
  write_sph_checkpoint(path, sim.scene(), sim.export_resume_state());
}

SphCheckpoint read_sph_checkpoint(const std::string& path) {
  File f(path, O_RDONLY | O_CLOEXEC);
  if (!f.ok())
    throw Error("", "sph checkpoint",
                fmt::format("cannot open '{}': {}", path, std::strerror(errno)),
                "give --restart the --checkpoint-dir of an earlier run");
  struct stat st {};
  if (::fstat(f.fd(), &st) != 0 || !S_ISREG(st.st_mode))
    fail(path, "file", "is not a regular file");
  const uint64_t file_bytes = uint64_t(st.st_size);
  uint64_t left = file_bytes;
  auto read_exact = [&](std::vector<uint8_t>& buf, uint64_t bytes, std::string_view field) {
    if (bytes > left)
      fail(path, field,
           fmt::format("needs {} bytes, the file has {} left (truncated?)", bytes, left));
    buf.resize(size_t(bytes));
    if (f.read_some(buf.data(), buf.size()) != buf.size())
      fail(path, field, "the file ended early (truncated?)");
    left -= bytes;
  };

  std::vector<uint8_t> head;
  read_exact(head, sizeof(kMagic) + 2 * sizeof(uint32_t), "header");
  if (std::memcmp(head.data(), kMagic, sizeof(kMagic)) != 0)
    fail(path, "magic", "not a masav SPH checkpoint (expected the bytes MASAVSPH at its start)");
  In h(head, path, "header");
  for (size_t i = 0; i < sizeof(kMagic); ++i) h.get<char>("magic");
  const uint32_t version = h.get<uint32_t>("format version");
  if (version != kSphCheckpointVersion)
    fail(path, "format version",
         fmt::format("{}; this masav ({}) reads version {}{}", version, MASAV_VERSION,
                     kSphCheckpointVersion,
                     version > kSphCheckpointVersion ? " (written by a newer masav)" : ""));
  const uint32_t count = h.get<uint32_t>("section count");
  if (count != kSectionCount)
    fail(path, "section count", fmt::format("{} where {} was expected", count, kSectionCount));
  std::vector<uint8_t> buf;
  read_exact(buf, sizeof(uint32_t), "writer version");
  uint32_t writer_bytes;
  std::memcpy(&writer_bytes, buf.data(), sizeof(writer_bytes));
  if (writer_bytes > kMaxWriterBytes)
    fail(path, "writer version",
         fmt::format("{} bytes where at most {} were expected", writer_bytes, kMaxWriterBytes));
  read_exact(buf, writer_bytes, "writer version");
  SphCheckpoint c;
  c.writer.assign(buf.begin(), buf.end());

  std::vector<uint8_t> payload[kSectionCount];
  for (uint32_t i = 0; i < kSectionCount; ++i) {
    const std::string name = kSectionNames[i];
    read_exact(buf, 24, name + " section header");
    In sh(buf, path, name + " section header");
    const uint32_t t = sh.get<uint32_t>("tag");
    const uint32_t reserved = sh.get<uint32_t>("reserved");
    const uint64_t bytes = sh.get<uint64_t>("bytes");
    const uint64_t sum = sh.get<uint64_t>("checksum");
    if (t != tag(kSectionNames[i]) || reserved != 0)
      fail(path, name + " section", fmt::format("section {} of the file is not {}", i + 1, name));
    read_exact(payload[i], bytes, name + " section");
    if (fnv1a64(payload[i]) != sum)
      fail(path, name + " section",
           "checksum mismatch (FNV-1a 64 of its bytes): the file is corrupted");
  }
  if (left != 0) fail(path, "file", fmt::format("{} bytes past the last section", left));

  In scene(payload[0], path, "SCEN");
  visit_scene(c.scene, SceneReader{scene});
  scene.end();
  try {
    validate(c.scene);
  } catch (const Error& e) {
    fail(path, "SCEN", e.problem());
  }

  In s(payload[1], path, "STAT");
  SphResumeState& r = c.state;
  const uint64_t n = s.get<uint64_t>("particles");
  // Bounded before anything is allocated: the scene's limit, and the bytes PART holds (its 10
  // arrays take at least 140 bytes per particle).
  if (n == 0 || n > kSphCheckpointMaxParticles)
    fail(path, "STAT.particles",
         fmt::format("{} where 1 to {} was expected", n, kSphCheckpointMaxParticles));
  if (n > payload[2].size() / 140)
    fail(path, "STAT.particles",
         fmt::format("{} particles need more than the {} bytes of the PART section", n,
                     payload[2].size()));
  // The scene's fluid alone is part of that count: a simulation built from the scene then
  // holds no more particles than the file has values for.
  if (c.scene.particles > n)
    fail(path, "SCEN.particles",
         fmt::format("{} fluid particles where STAT holds {} in all", c.scene.particles, n));
  r.time = s.real("time");
  r.last_dt = s.real("last_dt");
  r.adaptive_dt = s.real("adaptive_dt");
  r.steps = s.get<uint64_t>("steps");
  r.substeps = s.get<uint64_t>("substeps");
  r.retries = s.get<uint64_t>("retries");
  r.block_replays = s.get<uint64_t>("block_replays");
  r.stats = get_stats(s, "stats");
  r.lag_stats = get_stats(s, "lag_stats");
  SphSolveStats& ss = r.solve_stats;
  ss.steps = s.get<uint64_t>("solve_stats");
  ss.density_iterations = s.get<uint64_t>("solve_stats");
  ss.divergence_iterations = s.get<uint64_t>("solve_stats");
  ss.unconverged = s.get<uint64_t>("solve_stats");
  ss.last_density_error = s.real("solve_stats");
  ss.last_divergence_error = s.real("solve_stats");
  r.accel_valid = s.flag("accel_valid");
  r.fields_current = s.flag("fields_current");
  r.kappa_warm = s.flag("kappa_warm");
  r.block_steps = s.get<uint32_t>("block_steps");
  if (s.flag("block_open")) {
    r.block_limit = s.real("block_limit");
    if (!(r.block_limit > 0))
      fail(path, "STAT.block_limit",
           fmt::format("{} where a positive dt was expected", r.block_limit));
    r.block_stats = s.array<uint32_t>("block_stats", kSphStatWords);
  }
  r.watchdog.max_speed = s.real("watchdog.max_speed");
  r.watchdog.max_density = s.real("watchdog.max_density");
  r.watchdog.energy0 = s.real("watchdog.energy0");
  r.next_energy_check = s.get<uint64_t>("next_energy_check");
  r.good_time = s.real("good.time");
  r.good_last_dt = s.real("good.last_dt");
  r.good_steps = s.get<uint64_t>("good.steps");
  r.good_substeps = s.get<uint64_t>("good.substeps");
  r.good_stats = get_stats(s, "good.stats");
  const bool kappas = s.flag("dfsph kappa sums");
  s.end();
  if (kappas != (c.scene.model == SphPressureModel::dfsph))
    fail(path, "STAT.dfsph kappa sums",
         fmt::format("{} for a scene of pressure model {}", kappas ? "present" : "absent",
                     to_string(c.scene.model)));

  In p(payload[2], path, "PART");
  const uint64_t nk = kappas ? n : 0;
  r.positions = p.array<Vec4d>("positions", n);
  r.velocities = p.array<Vec4d>("velocities", n);
  r.accel = p.array<Vec4d>("accelerations", n);
  r.ids = p.array<uint32_t>("ids", n);
  r.density = p.array<double>("density", n);
  r.pressure = p.array<double>("pressure", n);
  r.kappa_density = p.array<double>("dfsph density kappa sums", nk);
  r.kappa_divergence = p.array<double>("dfsph divergence kappa sums", nk);
  r.good_positions = p.array<Vec4d>("watchdog positions", n);
  r.good_velocities = p.array<Vec4d>("watchdog velocities", n);
  p.end();
  return c;
}

std::string sph_scene_difference(const SphScene& a, const SphScene& b) {
  std::vector<std::pair<std::string, std::vector<uint8_t>>> fa;
  visit_scene(a, [&](const char* name, const auto& v) {
    Out o;
    SceneWriter{o}(name, v);
    fa.emplace_back(name, std::move(o.bytes()));
  });
  size_t i = 0;
  std::string differs;
  visit_scene(b, [&](const char* name, const auto& v) {
    Out o;
    SceneWriter{o}(name, v);
    if (differs.empty() && o.bytes() != fa[i].second) differs = name;
    ++i;
  });
  return differs;
}

void restore_sph_checkpoint(SphSimulation& sim, const SphCheckpoint& c, const std::string& path) {
  if (const std::string field = sph_scene_difference(sim.scene(), c.scene); !field.empty())
    fail(path, "SCEN." + field, "differs from the scene of the simulation it is restored into");
  if (c.state.positions.size() != sim.particle_count())
    fail(path, "STAT.particles",
         fmt::format("{} where the scene has {}", c.state.positions.size(), sim.particle_count()));
  try {
    sim.restore_resume_state(c.state);
  } catch (const Error& e) {
    fail(path, "PART", e.problem());
  }
}

}  // namespace masav
