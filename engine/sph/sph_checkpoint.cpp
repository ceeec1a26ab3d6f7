// SPH checkpoint files: the header and the framing of the sections (tag, size, checksum), the
// durable write (temporary file, fsync, rename) and the bounded read; the sections' contents are
// in sph_checkpoint_sections.cpp.
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
#include <vector>

#include "engine/core/error.h"
#include "engine/sph/sph_checkpoint_codec.h"
#include "engine/sph/sph_checkpoint_sections.h"

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

constexpr uint32_t tag(const char (&t)[5]) {
  return uint32_t(uint8_t(t[0])) | uint32_t(uint8_t(t[1])) << 8 | uint32_t(uint8_t(t[2])) << 16 |
         uint32_t(uint8_t(t[3])) << 24;
}
constexpr char kSectionNames[kSectionCount][5] = {"SCEN", "STAT", "PART"};

using checkpoint_io::fail;
using checkpoint_io::In;
using checkpoint_io::Out;

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
  const std::vector<uint8_t> sections[kSectionCount] = {checkpoint_io::scene_bytes(scene),
                                                        checkpoint_io::state_bytes(state),
                                                        checkpoint_io::particle_bytes(state)};
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

  checkpoint_io::read_sections(payload, path, c);
  return c;
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
    fail(path, "state", fmt::format("{}; {}", e.problem(), e.remedy()));
  }
}

}  // namespace masav
