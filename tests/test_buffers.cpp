// Buffers and ordering on every backend: round trips of each element kind, offsets, copy, fill,
// empty buffers, Real precision, device timestamps, and sizes over the device's limit.
#include <doctest/doctest.h>
#include <fmt/format.h>

#include <cstdlib>
#include <cstring>
#include <memory>
#include <new>
#include <numeric>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "registry/backends.h"
#include "tests/backend_fixture.h"

using namespace masav;

TEST_CASE("buffers round-trip every element kind") {
  Backend& b = test::backend();
  std::vector<uint32_t> u(1001);
  std::iota(u.begin(), u.end(), 7u);
  auto bu = b.create<uint32_t>(u.size(), "u32");
  b.upload(bu, u);
  CHECK(b.download(bu) == u);

  std::vector<int32_t> i = {-5, 0, 5, INT32_MIN, INT32_MAX};
  auto bi = b.create<int32_t>(i.size(), "i32");
  b.upload(bi, i);
  CHECK(b.download(bi) == i);

  std::vector<float> f = {0.5f, -1e-30f, 3.25e30f, 1.0f / 3.0f};
  auto bf = b.create<float>(f.size(), "f32");
  b.upload(bf, f);
  CHECK(b.download(bf) == f);

  // Reals: exact for values representable in fp32; fp64 kept only by the CPU reference.
  std::vector<double> r = {0.1, 1.0 / 3.0, -2.5};
  auto br = b.create<Real>(r.size(), "real");
  b.upload(br, r);
  const auto back = b.download(br);
  for (size_t k = 0; k < r.size(); ++k)
    CHECK(back[k] == (b.caps().real_is_double ? r[k] : double(float(r[k]))));

  std::vector<Vec4f> p = {{1, 2, 3, 4}, {-0.5f, 0.25f, 1e-3f, 0}};
  auto bp = b.create<Real4>(p.size(), "real4");
  b.upload(bp, p);
  const auto pf = b.download_f32(bp);
  for (size_t k = 0; k < p.size(); ++k) {
    CHECK(pf[k].x == p[k].x);
    CHECK(pf[k].w == p[k].w);
  }
}

TEST_CASE("copy, fill, partial upload and empty buffers keep their order") {
  Backend& b = test::backend();
  std::vector<uint32_t> a(5000), z(5000, 0);
  std::iota(a.begin(), a.end(), 1u);
  auto x = b.create<uint32_t>(a.size(), "x");
  auto y = b.create<uint32_t>(a.size(), "y");
  b.upload(x, a);
  b.fill(y, 0xABCDEF01u);
  CHECK(b.download(y) == std::vector<uint32_t>(a.size(), 0xABCDEF01u));
  b.copy(x, y);
  b.fill(x, 0u);  // recorded after the copy: the copy must still see the old contents
  CHECK(b.download(y) == a);
  CHECK(b.download(x) == z);
  const uint32_t patch[3] = {9, 9, 9};
  b.upload_bytes(y.impl(), patch, sizeof patch, 40);
  const auto yy = b.download(y);
  CHECK(yy[9] == 10);
  CHECK(yy[10] == 9);
  CHECK(yy[12] == 9);
  CHECK(yy[13] == 14);

  auto empty = b.create<uint32_t>(0, "empty");
  CHECK(empty.size() == 0);
  CHECK(b.download(empty).empty());
  b.radix_sort({0, 32}, empty, nullptr);
  CHECK_THROWS_WITH_AS(b.upload(empty, a), doctest::Contains("do not fit"), Error);
}

TEST_CASE("a fill writes every word, whether or not its four bytes are equal") {
  // CUDA sets a word of four equal bytes with a memset and any other word with a kernel.
  Backend& b = test::backend();
  auto x = b.create<uint32_t>(4099, "x");  // not a multiple of a workgroup or of 16 bytes
  for (const uint32_t word : {0u, ~0u, 0x7F7F7F7Fu, 0x00000001u, 0x01000000u, 0xABCDEF01u}) {
    CAPTURE(word);
    b.fill(x, word);
    CHECK(b.download(x) == std::vector<uint32_t>(x.size(), word));
  }
}

TEST_CASE("captured work gives what it gives uncaptured, split by a download or abandoned") {
  // DeviceApi::begin_capture (CUDA: a graph). A download inside a capture ends it there: the
  // work before it must have run, the work after it still runs, in order.
  Backend& b = test::backend();
  const uint32_t n = 3000;
  std::vector<uint32_t> order(n), a(n);
  for (uint32_t i = 0; i < n; ++i) {
    order[i] = (i * 7) % n;
    a[i] = 3 * i + 1;
  }
  auto o = b.create<uint32_t>(n, "order");
  auto x = b.create<uint32_t>(n, "x"), y = b.create<uint32_t>(n, "y"),
       z = b.create<uint32_t>(n, "z");
  b.upload(o, order);
  b.upload(x, a);
  {
    CaptureScope scope(b);
    b.gather({n}, o, x.impl(), y.impl());
    const auto once = b.download(y);  // ends the capture
    for (uint32_t i = 0; i < n; ++i) REQUIRE(once[i] == a[order[i]]);
    b.gather({n}, o, y.impl(), z.impl());
    b.fill(x, 5u);
    scope.commit();
  }
  const auto twice = b.download(z);
  for (uint32_t i = 0; i < n; ++i) REQUIRE(twice[i] == a[order[order[i]]]);
  CHECK(b.download(x) == std::vector<uint32_t>(n, 5u));
  // An error inside a capture abandons it; the backend goes on as before.
  auto small = b.create<uint32_t>(n / 2, "small");
  CHECK_THROWS_AS(([&] {
                    CaptureScope scope(b);
                    b.gather({n}, o, x.impl(), small.impl());  // too small: refused
                    scope.commit();
                  }()),
                  Error);
  b.gather({n}, o, z.impl(), y.impl());
  const auto after = b.download(y);
  for (uint32_t i = 0; i < n; ++i) REQUIRE(after[i] == a[order[order[order[i]]]]);
}

// Vulkan replays a capture whose commands equal a kept recording's, push constants byte for byte
// (compute/vk_stream.h); the padding of parameters a caller left unspecified must not count.
TEST_CASE("captures of one call replay, whatever the padding of its parameters holds") {
  Backend& b = test::backend();
  const uint32_t n = 64, cells = 8;
  std::vector<uint32_t> cell_of(n), end(cells);
  for (uint32_t i = 0; i < n; ++i) cell_of[i] = i % cells;
  for (uint32_t c = 0; c < cells; ++c) end[c] = (c + 1) * (n / cells);
  auto cell_buf = b.create<uint32_t>(n, "cells"), end_buf = b.create<uint32_t>(cells, "cell_end");
  auto counts = b.create<uint32_t>(cells, "counts"), unsorted = b.create<uint32_t>(n, "unsorted");
  b.upload(cell_buf, cell_of);
  b.upload(end_buf, end);
  auto scatter = [&](const CellScatterParams& p) {
    CaptureScope scope(b);
    b.fill(counts, n / cells);
    b.grid_scatter_cells(p, cell_buf, end_buf, counts, unsorted);
    scope.commit();
  };
  CellScatterParams clean{};
  clean.n = n;
  clean.cell_count = cells;
  // The same values over padding bytes of 0xA5: default-initialised in place, the padding keeps
  // what the storage held.
  alignas(CellScatterParams) unsigned char raw[sizeof(CellScatterParams)];
  std::memset(raw, 0xA5, sizeof raw);
  CellScatterParams* dirty = new (raw) CellScatterParams;
  dirty->n = n;
  dirty->cell_count = cells;
  REQUIRE(sizeof(CellScatterParams) > 2 * sizeof(uint32_t));  // it has padding to fill
  const uint64_t graphs0 = b.counters().graphs, builds0 = b.counters().graph_builds;
  scatter(clean);
  scatter(*dirty);
  scatter(clean);
  const auto got = b.download(unsorted);
  for (uint32_t i = 0; i < n; ++i) REQUIRE(got[i] < n);
  for (uint32_t s = 0; s < n; ++s) CHECK(cell_of[got[s]] == s / (n / cells));
  if (b.name() != "vulkan" || !resolve(b.tuning().vulkan.replay, true)) {
    MESSAGE("skipped the replay count: " << b.name() << " does not replay captures here");
    return;
  }
  CHECK(b.counters().graphs - graphs0 == 3);
  CHECK(b.counters().graph_builds - builds0 == 1);  // recorded once, replayed twice
}

TEST_CASE("device timestamps are ordered") {
  Backend& b = test::backend();
  auto x = b.create<uint32_t>(1 << 18, "x");
  b.finish();
  b.reset_timestamps();
  const TimestampId t0 = b.timestamp();
  b.philox_u32({1, 1, 0}, x);
  const TimestampId t1 = b.timestamp();
  b.finish();
  CHECK(b.timestamp_ns(t1) >= b.timestamp_ns(t0));
  CHECK_THROWS_AS(b.timestamp_ns(t1 + 1), Error);
}

TEST_CASE("kernel timing records each call that ran, by kernel, in call order") {
  Backend& b = test::backend();
  auto x = b.create<uint32_t>(1 << 16, "x");
  auto empty = b.create<uint32_t>(0, "empty");
  b.finish();
  b.reset_timestamps();
  b.philox_u32({1, 1, 0}, x);  // before timing is on: not recorded
  b.set_kernel_timing(true);
  b.philox_u32({1, 2, 0}, x);
  b.philox_u32({1, 3, 0}, empty);  // empty work runs nothing: not recorded
  b.radix_sort({1 << 16, 32}, x, nullptr);
  b.set_kernel_timing(false);
  b.philox_u32({1, 4, 0}, x);
  b.finish();
  const std::vector<KernelTiming> t = b.take_kernel_timings();
  REQUIRE(t.size() == 2);
  CHECK(t[0].kernel == KernelId::philox_u32);
  CHECK(t[1].kernel == KernelId::radix_sort);
  for (const KernelTiming& k : t) CHECK(b.timestamp_ns(k.end) >= b.timestamp_ns(k.begin));
  CHECK(b.timestamp_ns(t[1].begin) >= b.timestamp_ns(t[0].end));
  CHECK(b.take_kernel_timings().empty());  // taken once
}

TEST_CASE("a kernel form is built once per backend, and counted where it is built at run time") {
  // DeviceCounters::pipelines_built: Vulkan creates a kernel form's pipeline at its first use on
  // a backend (a fresh one here, so the shared one's earlier tests have built nothing of it);
  // CUDA and the CPU reference compiled every kernel ahead of time.
  const std::unique_ptr<Backend> fresh = test::backend_with(test::tuning());
  Backend& b = *fresh;
  auto x = b.create<uint32_t>(1024, "x");
  b.finish();
  b.reset_counters();
  b.philox_u32({1, 1, 0}, x);
  b.finish();
  const uint64_t first = b.counters().pipelines_built;
  CHECK(first == (b.name() == "vulkan" ? 1u : 0u));
  b.philox_u32({1, 2, 0}, x);
  b.finish();
  CHECK(b.counters().pipelines_built == first);  // the same form again: built already
}

TEST_CASE("a buffer over the device's limit is refused with the largest size that fits") {
  Backend& b = test::backend();
  const uint64_t limit = b.caps().max_buffer_bytes;
  if (limit == 0) {
    MESSAGE("backend " << b.name() << " has no per-buffer limit; nothing to refuse");
    return;
  }
  const std::string expected = fmt::format("use at most {} elements", limit / 4);
  CHECK_THROWS_WITH_AS(b.create<uint32_t>(size_t(limit / 4 + 1), "too big"),
                       doctest::Contains(expected.c_str()), Error);
}

TEST_CASE("a kernel binds the buffers of each call, also where a freed buffer's memory is reused") {
  // Backends may cache what a call binds (Vulkan caches descriptor sets by kernel and buffers);
  // buffers freed and created again, often at the same address, must never see a stale binding.
  Backend& b = test::backend();
  for (uint32_t round = 0; round < 40; ++round) {
    const uint32_t n = 64 + 37 * (round % 5);
    std::vector<uint32_t> order(n), src(n);
    for (uint32_t i = 0; i < n; ++i) {
      order[i] = (i * 7 + round) % n;
      src[i] = round * 1000 + i;
    }
    auto o = b.create<uint32_t>(n, "order");
    auto s = b.create<uint32_t>(n, "src");
    auto d = b.create<uint32_t>(n, "dst");
    b.upload(o, order);
    b.upload(s, src);
    b.gather({n}, o, s.impl(), d.impl());
    const std::vector<uint32_t> got = b.download(d);
    bool same = true;
    for (uint32_t i = 0; i < n; ++i) same = same && got[i] == src[order[i]];
    CHECK_MESSAGE(same, "round ", round);
  }
}

TEST_CASE("independent commands are not ordered against each other; dependent ones are") {
  Backend& b = test::backend();
  const uint32_t n = 1000;
  std::vector<uint32_t> order(n), a(n), c(n);
  for (uint32_t i = 0; i < n; ++i) {
    order[i] = (i * 13) % n;
    a[i] = i;
    c[i] = 5 * i;
  }
  auto o = b.create<uint32_t>(n, "order");
  auto sa = b.create<uint32_t>(n, "a"), sc = b.create<uint32_t>(n, "c");
  auto da = b.create<uint32_t>(n, "a sorted"), dc = b.create<uint32_t>(n, "c sorted");
  auto twice = b.create<uint32_t>(n, "a sorted twice");
  b.upload(o, order);
  b.upload(sa, a);
  b.upload(sc, c);
  b.finish();
  b.reset_counters();
  b.gather({n}, o, sa.impl(), da.impl());
  b.gather({n}, o, sc.impl(), dc.impl());     // reads what the first reads: no barrier
  b.gather({n}, o, da.impl(), twice.impl());  // reads the first's output: a barrier
  b.finish();
  CHECK(b.counters().launches == 3);
  // Vulkan records exactly the one barrier the third gather needs; the others have none.
  CHECK(b.counters().barriers == (b.name() == "vulkan" ? 1u : 0u));
  const auto got = b.download(twice), got_c = b.download(dc);
  bool same = true;
  for (uint32_t i = 0; i < n; ++i)
    same = same && got[i] == a[order[order[i]]] && got_c[i] == c[order[i]];
  CHECK(same);
}

TEST_CASE("an asynchronous read returns the bytes of its copy while later work runs") {
  Backend& b = test::backend();
  const uint32_t n = 3000;
  std::vector<uint32_t> a(n), z(n), order(n);
  for (uint32_t i = 0; i < n; ++i) {
    a[i] = i + 1;
    z[i] = 7 * i + 3;
    order[i] = (i * 17) % n;
  }
  auto x = b.create<uint32_t>(n, "x");
  auto src = b.create<uint32_t>(n, "z");
  auto o = b.create<uint32_t>(n, "order");
  auto y = b.create<uint32_t>(n, "y");
  b.upload(x, a);
  b.upload(src, z);
  b.upload(o, order);
  b.finish();
  b.reset_counters();
  const uint64_t first = b.read_async(x.impl(), n * 4);
  // Recorded after the read: x is overwritten, then read by a gather whose output is read too.
  b.copy(src, x);
  b.gather({n}, o, x.impl(), y.impl());
  const uint64_t second = b.read_async(y.impl(), n * 4);
  auto words = [](const std::vector<uint8_t>& bytes) {
    std::vector<uint32_t> w(bytes.size() / 4);
    std::memcpy(w.data(), bytes.data(), bytes.size());
    return w;
  };
  CHECK(words(b.take_read(first)) == a);  // as it was when the copy ran
  std::vector<uint32_t> gathered(n);
  for (uint32_t i = 0; i < n; ++i) gathered[i] = z[order[i]];
  CHECK(words(b.take_read(second)) == gathered);
  const DeviceCounters& c = b.counters();
  CHECK(c.bytes_to_host == 2 * n * 4);
  if (b.name() == "cpu") {
    // Its work is done when recorded: nothing to wait for, nothing queued.
    CHECK(c.async_reads == 0);
  } else {
    // The first take comes with the gather still queued; the second drains the queue, a host
    // sync where its copy has not finished yet (on a fast GPU it may have: none).
    CHECK(c.async_reads == 1);
    CHECK(c.host_syncs <= 1);
  }
  CHECK(b.download(x) == z);

  // Out of order, and each ticket once.
  const uint64_t t1 = b.read_async(x.impl(), 8), t2 = b.read_async(y.impl(), 4);
  CHECK(words(b.take_read(t2)) == std::vector<uint32_t>{gathered[0]});
  CHECK(words(b.take_read(t1)) == std::vector<uint32_t>{z[0], z[1]});
  CHECK_THROWS_WITH_AS(b.take_read(t1), doctest::Contains("no outstanding read"), Error);
  CHECK_THROWS_WITH_AS(b.take_read(0), doctest::Contains("no outstanding read"), Error);
  CHECK_THROWS_WITH_AS(b.read_async(x.impl(), n * 4 + 4), doctest::Contains("overrun"), Error);
  CHECK_THROWS_WITH_AS(b.read_async(x.impl(), 0), doctest::Contains("0 bytes"), Error);
  std::vector<uint64_t> held;
  for (uint32_t k = 0; k < DeviceApi::kMaxPendingReads; ++k)
    held.push_back(b.read_async(x.impl(), 4));
  CHECK_THROWS_WITH_AS(b.read_async(x.impl(), 4), doctest::Contains("reads outstanding"), Error);
  for (uint64_t t : held) CHECK(words(b.take_read(t)) == std::vector<uint32_t>{z[0]});
}
