// SphRanks' exchanges (see sph_ranks.h): at a rebuild the migration of particles to their
// cells' owners and the halos, in the one-process order; between rebuilds the halo updates of
// single arrays, one of them overlapped with the interior's forces. Particles travel as their
// raw device bytes, so nothing is converted.
#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <numeric>
#include <span>

#include "engine/core/error.h"
#include "engine/kernels/grid_cell.h"
#include "engine/sph/sph_ranks.h"

namespace masav {
namespace {

// Particles in transit: the raw device bytes of each array, so that nothing is converted.
struct Fields {
  size_t real4 = 0;  // bytes of one Real4
  size_t extra = 0;  // bytes per particle of the carried arrays, one after the other
};

struct Pack {
  size_t count = 0;
  Bytes x, v, ids, extra;

  void append_all(const Pack& src) {
    x.insert(x.end(), src.x.begin(), src.x.end());
    v.insert(v.end(), src.v.begin(), src.v.end());
    ids.insert(ids.end(), src.ids.begin(), src.ids.end());
    extra.insert(extra.end(), src.extra.begin(), src.extra.end());
    count += src.count;
  }
};

// Particle `i` of pack `p`.
struct Ref {
  const Pack* p;
  uint32_t i;
};

// The particles `refs` names, in that order (one copy per array and particle, no reallocation).
Pack pick(std::span<const Ref> refs, const Fields& f) {
  Pack out;
  out.count = refs.size();
  auto field_of = [&](Bytes Pack::*field, size_t each) {
    Bytes& dst = out.*field;
    dst.resize(refs.size() * each);
    for (size_t k = 0; k < refs.size(); ++k)
      std::memcpy(dst.data() + k * each, ((*refs[k].p).*field).data() + size_t(refs[k].i) * each,
                  each);
  };
  field_of(&Pack::x, f.real4);
  field_of(&Pack::v, f.real4);
  field_of(&Pack::ids, 4);
  if (f.extra) field_of(&Pack::extra, f.extra);
  return out;
}

Pack pick(const Pack& p, std::span<const uint32_t> indices, const Fields& f) {
  std::vector<Ref> refs(indices.size());
  for (size_t k = 0; k < indices.size(); ++k) refs[k] = {&p, indices[k]};
  return pick(refs, f);
}

Bytes serialize(const Pack& p) {
  Bytes out;
  const uint64_t count = p.count;
  append_bytes(out, std::span<const uint64_t>(&count, 1));
  out.insert(out.end(), p.x.begin(), p.x.end());
  out.insert(out.end(), p.v.begin(), p.v.end());
  out.insert(out.end(), p.ids.begin(), p.ids.end());
  out.insert(out.end(), p.extra.begin(), p.extra.end());
  return out;
}

[[noreturn]] void fail_message(int from, size_t bytes, size_t want) {
  throw Error("sph", "ranks",
              fmt::format("rank {} sent {} bytes where {} were expected", from, bytes, want),
              "the ranks run different builds or scenes: start every rank with the same masav "
              "and the same arguments");
}

Pack deserialize(const Bytes& b, const Fields& f, int from) {
  uint64_t count = 0;
  if (b.size() < sizeof count) fail_message(from, b.size(), sizeof count);
  std::memcpy(&count, b.data(), sizeof count);
  const size_t each = 2 * f.real4 + 4 + f.extra;
  if (count > (b.size() - sizeof count) / each || b.size() != sizeof count + count * each)
    fail_message(from, b.size(), sizeof count + size_t(count) * each);
  Pack p;
  p.count = size_t(count);
  auto take = [&, at = sizeof count](Bytes& dst, size_t n) mutable {
    dst.assign(b.begin() + std::ptrdiff_t(at), b.begin() + std::ptrdiff_t(at + n));
    at += n;
  };
  take(p.x, p.count * f.real4);
  take(p.v, p.count * f.real4);
  take(p.ids, p.count * 4);
  take(p.extra, p.count * f.extra);
  return p;
}

// Ranges of device buffers read with one wait for all of them: each copy is queued
// (DeviceApi::read_async) when added, and take() waits for them, where a download per range would
// wait once per range.
class RangeReads {
 public:
  explicit RangeReads(Backend& b) : b_(b) {}
  RangeReads(const RangeReads&) = delete;
  RangeReads& operator=(const RangeReads&) = delete;
  ~RangeReads() {
    for (const Read& r : reads_) b_.discard_read(r.ticket);  // an error on the way
  }
  // `count` elements of `elem` bytes of `src` from element `first` into `dst` at take().
  void add(const BufferImpl& src, Bytes& dst, size_t first, size_t count, size_t elem) {
    dst.clear();
    if (count) reads_.push_back({b_.read_async(src, count * elem, first * elem), &dst});
  }
  void take() {
    while (!reads_.empty()) {
      const Read r = reads_.front();
      reads_.erase(reads_.begin());
      const std::vector<uint8_t> bytes = b_.take_read(r.ticket);
      r.dst->resize(bytes.size());
      std::memcpy(r.dst->data(), bytes.data(), bytes.size());
    }
  }

 private:
  struct Read {
    uint64_t ticket;
    Bytes* dst;
  };
  Backend& b_;
  std::vector<Read> reads_;
};

void upload_range(Backend& b, BufferImpl& dst, const Bytes& src, size_t first) {
  if (!src.empty()) b.upload_bytes(dst, src.data(), src.size(), first);
}

}  // namespace

const SphRankLayout& SphRanks::redistribute(const Buffer<Real4>& x, const Buffer<Real4>& v,
                                            const Buffer<uint32_t>& ids,
                                            std::span<const SphCarried> carried,
                                            Buffer<Real4>& x_out, Buffer<Real4>& v_out,
                                            Buffer<uint32_t>& ids_out) {
  Timer timer(counters_.exchange_seconds);
  const int me = rank(), count = ranks();
  Fields f{4 * backend_.real_bytes(), 0};
  std::vector<size_t> carried_at;  // each carried array's offset in a particle's extra bytes
  for (const SphCarried& c : carried) {
    carried_at.push_back(f.extra);
    f.extra += c.bytes(backend_);
  }
  const SphRankLayout& L = committed_;
  Pack own;
  own.count = L.own;
  {
    RangeReads reads(backend_);
    reads.add(x.impl(), own.x, L.first, L.own, f.real4);
    reads.add(v.impl(), own.v, L.first, L.own, f.real4);
    reads.add(ids.impl(), own.ids, L.first, L.own, 4);
    std::vector<Bytes> parts(carried.size());
    for (size_t a = 0; a < carried.size(); ++a)
      reads.add(carried[a].from(), parts[a], L.first, L.own, carried[a].bytes(backend_));
    reads.take();
    // Interleaved per particle, so that a particle's bytes move as one piece.
    own.extra.resize(own.count * f.extra);
    for (size_t a = 0; a < carried.size(); ++a) {
      const size_t each = carried[a].bytes(backend_);
      for (size_t i = 0; i < own.count; ++i)
        std::memcpy(own.extra.data() + i * f.extra + carried_at[a], parts[a].data() + i * each,
                    each);
    }
  }
  std::vector<uint32_t> cells(own.count);
  for (size_t i = 0; i < own.count; ++i) cells[i] = cell_of(&own.x[i * f.real4]);
  maybe_rebalance(cells);

  // Migration: each particle to its cell's owner, in this rank's order (leaving[me]: those
  // that stay).
  std::vector<std::vector<uint32_t>> leaving(static_cast<size_t>(count));
  for (size_t i = 0; i < own.count; ++i)
    leaving[size_t(partition_.owner(cells[i]))].push_back(uint32_t(i));
  std::vector<Bytes> out(static_cast<size_t>(count));
  for (int r = 0; r < count; ++r)
    if (r != me) {
      out[size_t(r)] = serialize(pick(own, leaving[size_t(r)], f));
      counters_.bytes_sent += out[size_t(r)].size();
    }
  const std::vector<Bytes> arrived = transfer(out);

  // In the one-process order: lower ranks' particles, this rank's, higher ranks'.
  std::vector<Pack> in(static_cast<size_t>(count));
  std::vector<Ref> merged;
  std::vector<uint32_t> merged_cells;
  merged.reserve(own.count);
  merged_cells.reserve(own.count);
  for (int r = 0; r < count; ++r) {
    if (r == me) {
      for (uint32_t i : leaving[size_t(me)]) {
        merged.push_back({&own, i});
        merged_cells.push_back(cells[i]);
      }
      continue;
    }
    const Pack& p = in[size_t(r)] = deserialize(arrived[size_t(r)], f, r);
    counters_.migrated += p.count;
    for (size_t i = 0; i < p.count; ++i) {
      const uint32_t c = cell_of(&p.x[i * f.real4]);
      if (partition_.owner(c) != me)
        throw Error("sph", "ranks",
                    fmt::format("rank {} sent rank {} a particle of cell {}, owned by rank {}", r,
                                me, c, partition_.owner(c)),
                    "the ranks disagree on the decomposition: start every rank with the same "
                    "masav and the same arguments");
      merged.push_back({&p, uint32_t(i)});
      merged_cells.push_back(c);
    }
  }
  std::vector<uint32_t> order(merged.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(),
                   [&](uint32_t a, uint32_t b) { return merged_cells[a] < merged_cells[b]; });
  std::vector<Ref> by_cell(order.size());
  std::vector<uint32_t> sorted_cells(order.size());
  for (size_t k = 0; k < order.size(); ++k) {
    by_cell[k] = merged[order[k]];
    sorted_cells[k] = merged_cells[order[k]];
  }
  const Pack sorted = pick(by_cell, f);

  // Halos: every particle of a cell next to another rank's range goes to that rank.
  halo_send_.assign(size_t(count), {});
  std::vector<char> wants(size_t(count), 0);
  const uint32_t dims[3] = {grid_.dims.x, grid_.dims.y, grid_.dims.z};
  uint32_t last = UINT32_MAX;
  for (uint32_t k = 0; k < sorted.count; ++k) {
    const uint32_t c = sorted_cells[k];
    if (c != last) {
      last = c;
      std::fill(wants.begin(), wants.end(), 0);
      const int cz = int(c % dims[2]), cy = int((c / dims[2]) % dims[1]),
                cx = int(c / (dims[2] * dims[1]));
      for (int n = 0; n < 27; ++n) {
        const int nx = cx + n / 9 - 1, ny = cy + (n / 3) % 3 - 1, nz = cz + n % 3 - 1;
        if (nx < 0 || ny < 0 || nz < 0 || nx >= int(dims[0]) || ny >= int(dims[1]) ||
            nz >= int(dims[2]))
          continue;
        wants[size_t(partition_.owner(
            grid::cell_id(uint32_t(nx), uint32_t(ny), uint32_t(nz), dims[1], dims[2])))] = 1;
      }
      wants[size_t(me)] = 0;
    }
    for (int r = 0; r < count; ++r)
      if (wants[size_t(r)]) halo_send_[size_t(r)].push_back(k);
  }
  for (int r = 0; r < count; ++r) {
    out[size_t(r)].clear();
    if (r == me) continue;
    out[size_t(r)] = serialize(pick(sorted, halo_send_[size_t(r)], f));
    counters_.bytes_sent += out[size_t(r)].size();
  }
  const std::vector<Bytes> halos = transfer(out);

  Pack local;
  halo_recv_.assign(size_t(count), 0);
  auto add_halo = [&](int r) {
    const Pack in = deserialize(halos[size_t(r)], f, r);
    halo_recv_[size_t(r)] = uint32_t(in.count);
    counters_.halo += in.count;
    local.append_all(in);
  };
  for (int r = 0; r < me; ++r) add_halo(r);
  const uint32_t first = uint32_t(local.count);
  local.append_all(sorted);
  for (int r = me + 1; r < count; ++r) add_halo(r);
  if (reserve_) reserve_(uint32_t(local.count));
  if (local.count > x_out.size())
    throw Error(backend_.name(), "sph ranks",
                fmt::format("rank {} holds {} particles with its halos, more than its buffers' "
                            "{}",
                            me, local.count, x_out.size()),
                "run on fewer ranks or with more particles per rank");
  upload_range(backend_, x_out.impl(), local.x, 0);
  upload_range(backend_, v_out.impl(), local.v, 0);
  upload_range(backend_, ids_out.impl(), local.ids, 0);
  for (size_t a = 0; a < carried.size(); ++a) {
    const size_t each = carried[a].bytes(backend_);
    Bytes values(local.count * each);
    for (size_t i = 0; i < local.count; ++i)
      std::memcpy(values.data() + i * each, local.extra.data() + i * f.extra + carried_at[a], each);
    upload_range(backend_, carried[a].to(), values, 0);
  }
  staged_ = {uint32_t(local.count), first, uint32_t(sorted.count)};
  // The own particles that go to lower ranks lie before lo_end_, to higher ones from hi_begin_.
  lo_end_ = 0;
  hi_begin_ = staged_.own;
  for (int r = 0; r < count; ++r) {
    const std::vector<uint32_t>& k = halo_send_[size_t(r)];
    if (r == me || k.empty()) continue;
    if (r < me) lo_end_ = std::max(lo_end_, k.back() + 1);
    if (r > me) hi_begin_ = std::min(hi_begin_, k.front());
  }
  ++counters_.rebuilds;
  return staged_;
}

void SphRanks::start_halos(HaloArrays arrays) {
  if (pending_)
    throw Error("sph", "ranks", "a halo update started before the last one finished",
                "internal error: call finish_halos() first");
  Timer timer(counters_.exchange_seconds);
  const int me = rank(), count = ranks();
  const SphRankLayout& L = staged_;
  std::vector<Bytes> out(static_cast<size_t>(count));
  std::vector<size_t> sizes(static_cast<size_t>(count), 0);
  // Only the own particles that go anywhere are read (see lo_end_, hi_begin_): every array's
  // spans queued together, one wait for all.
  struct Span {
    size_t from, to;
    Bytes data;
  };
  std::vector<std::vector<Span>> spans(arrays.size());
  {
    RangeReads reads(backend_);
    for (size_t a = 0; a < arrays.size(); ++a) {
      std::vector<Span>& sp = spans[a];
      if (hi_begin_ <= lo_end_) {
        sp.push_back({0, L.own, {}});
      } else {
        sp.push_back({0, lo_end_, {}});
        sp.push_back({hi_begin_, L.own, {}});
      }
      const auto& [b, elem] = arrays[a];
      for (Span& x : sp)
        if (x.from < x.to) reads.add(*b, x.data, L.first + x.from, x.to - x.from, elem);
    }
    reads.take();
  }
  for (size_t a = 0; a < arrays.size(); ++a) {
    const size_t elem = arrays[a].second;
    Bytes own(size_t(L.own) * elem);
    for (const Span& x : spans[a])
      std::copy(x.data.begin(), x.data.end(), own.begin() + std::ptrdiff_t(x.from * elem));
    for (int r = 0; r < count; ++r) {
      if (r == me) continue;
      Bytes& m = out[size_t(r)];
      for (uint32_t k : halo_send_[size_t(r)])
        m.insert(m.end(), own.begin() + std::ptrdiff_t(k * elem),
                 own.begin() + std::ptrdiff_t((k + 1) * elem));
      sizes[size_t(r)] += size_t(halo_recv_[size_t(r)]) * elem;
    }
  }
  for (int r = 0; r < count; ++r) counters_.bytes_sent += out[size_t(r)].size();
  pending_arrays_ = std::move(arrays);
  pending_ = comm_.start_exchange(std::move(out), std::move(sizes));
}

void SphRanks::finish_halos() {
  if (!pending_) return;
  Timer timer(counters_.exchange_seconds);
  const int me = rank(), count = ranks();
  const SphRankLayout& L = staged_;
  std::vector<Bytes> in;
  {
    Timer in_mpi(counters_.mpi_seconds);
    in = pending_->finish();
  }
  pending_.reset();
  // Each message holds the arrays' values one after the other, halo_recv_[r] of each.
  std::vector<size_t> at(static_cast<size_t>(count), 0);
  for (const auto& [b, elem] : pending_arrays_) {
    Bytes lower, upper;
    for (int r = 0; r < count; ++r) {
      if (r == me) continue;
      const Bytes& m = in[size_t(r)];
      const size_t bytes = size_t(halo_recv_[size_t(r)]) * elem;
      if (m.size() < at[size_t(r)] + bytes) fail_message(r, m.size(), at[size_t(r)] + bytes);
      Bytes& dst = r < me ? lower : upper;
      dst.insert(dst.end(), m.begin() + std::ptrdiff_t(at[size_t(r)]),
                 m.begin() + std::ptrdiff_t(at[size_t(r)] + bytes));
      at[size_t(r)] += bytes;
    }
    upload_range(backend_, *b, lower, 0);
    upload_range(backend_, *b, upper, size_t(L.first + L.own) * elem);
  }
  for (int r = 0; r < count; ++r)
    if (r != me && in[size_t(r)].size() != at[size_t(r)])
      fail_message(r, in[size_t(r)].size(), at[size_t(r)]);
  pending_arrays_.clear();
  ++counters_.halo_updates;
}

void SphRanks::exchange_halos(Buffer<Real4>& a, Buffer<Real4>& b) {
  const size_t real4 = 4 * backend_.real_bytes();
  start_halos({{&a.impl(), real4}, {&b.impl(), real4}});
  finish_halos();
}

void SphRanks::exchange_halos(Buffer<Real4>& a) {
  start_halos({{&a.impl(), 4 * backend_.real_bytes()}});
  finish_halos();
}

void SphRanks::exchange_halos(Buffer<Real>& a) {
  start_halos({{&a.impl(), backend_.real_bytes()}});
  finish_halos();
}

void SphRanks::start_halos(Buffer<Real>& a, Buffer<Real>& b) {
  start_halos({{&a.impl(), backend_.real_bytes()}, {&b.impl(), backend_.real_bytes()}});
}

std::pair<uint32_t, uint32_t> SphRanks::interior() const {
  const SphRankLayout& l = staged_;
  if (hi_begin_ <= lo_end_) return {l.first, l.first};  // every own particle is next to a halo
  return {l.first + lo_end_, l.first + hi_begin_};
}

}  // namespace masav
