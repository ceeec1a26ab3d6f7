#include "engine/points/particles_scene.h"

#include <fmt/format.h>

#include <cmath>

#include "engine/core/error.h"
#include "engine/grid/hash_grid.h"

namespace masav::points {
namespace {

using scene::ParamSet;
using scene::StageGraph;

// Philox streams of the scene (one seed, disjoint streams).
constexpr uint64_t kStartStream = 0, kDirectionStream = 1, kStarStream = 2;

GridParams grid_of(const ParamSet& p, uint32_t n) {
  const float size = float(p.get_real("particles.box_size"));
  const uint32_t cells = uint32_t(p.get_int("particles.grid_cells"));
  return make_grid_params({0, 0, 0}, size / float(cells), {cells, cells, cells}, n);
}

float radius_of(const ParamSet& p) {
  const GridParams g = grid_of(p, 0);
  return g.cell_size * float(p.get_real("particles.neighbor_radius"));
}

// Mean points per cell times 27 cells: what each neighbour walk examines on average.
double expected_candidates(const ParamSet& p) {
  const double cells = double(p.get_int("particles.grid_cells"));
  return 27.0 * double(p.get_int("particles.count")) / (cells * cells * cells);
}

class ParticlesScene final : public scene::SceneInstance {
 public:
  ParticlesScene(Backend& b, const ParamSet& p) : SceneInstance(b, p) {
    validate(params_);
    graph_.add_input("time");
    add_parameter_inputs();
    auto stage = [](auto fn) { return std::make_unique<scene::LambdaStage>(fn); };
    graph_.add_stage("start_uniforms", {"particles.count", "particles.seed"}, [this, stage] {
      return stage([this] { sample(start_, kStartStream, "start uniforms"); });
    });
    graph_.add_stage("direction_uniforms", {"particles.count", "particles.seed"}, [this, stage] {
      return stage([this] { sample(direction_, kDirectionStream, "direction uniforms"); });
    });
    graph_.add_stage("drift_points",
                     {"start_uniforms", "direction_uniforms", "particles.box_size",
                      "particles.drift_speed", "time"},
                     [this, stage] { return stage([this] { drift(); }); });
    graph_.add_stage("hash_grid", {"drift_points", "particles.grid_cells"},
                     [this, stage] { return stage([this] { bin(); }); });
    graph_.add_stage("reorder", {"hash_grid"},
                     [this, stage] { return stage([this] { reorder_points(); }); });
    graph_.add_stage("neighbor_counts", {"reorder", "particles.neighbor_radius"},
                     [this, stage] { return stage([this] { count(); }); });
    graph_.add_stage("stars", {"render.width", "render.height", "particles.seed"},
                     [this, stage] { return stage([this] { stars(); }); });
  }

  std::vector<std::string> targets() const override {
    std::vector<std::string> t;
    t.push_back(by_neighbors() ? "neighbor_counts" : "drift_points");
    if (params_.get_text("render.background") == "stars") t.push_back("stars");
    return t;
  }

  scene::SceneView view() const override {
    scene::SceneView v;
    const float size = float(params_.get_real("particles.box_size"));
    v.box = {{0, 0, 0}, {size, size, size}};
    scene::PointLayer pl;
    pl.count = n();
    const std::string& by = params_.get_text("particles.color_by");
    if (by_neighbors()) {
      pl.positions = &sorted_;
      pl.from = scene::PointLayer::ScalarFrom::buffer;
      pl.scalar = counts_.valid() ? &counts_.impl() : nullptr;
      pl.scalar_lo = 0;
      // The count is Poisson around its mean; twice the mean spans nearly all of it.
      const double r = radius_of(params_), vol = double(size) * size * size;
      const double mean = double(n()) * 4.18879 * r * r * r / vol;
      pl.scalar_hi = float(std::max(2.0, 2.0 * mean));
      pl.scalar_name = "neighbours within r";
      pl.scalar_key = "neighbours";
      pl.version = graph_.version("neighbor_counts");
    } else {
      pl.positions = &positions_;
      pl.version = graph_.version("drift_points");
      if (by == "speed") {
        pl.from = scene::PointLayer::ScalarFrom::position_w;
        pl.scalar_hi = float(params_.get_real("particles.drift_speed") * size * std::sqrt(3.0));
        pl.scalar_name = "speed";
        pl.scalar_key = "speed";
      } else if (by == "height") {
        pl.from = scene::PointLayer::ScalarFrom::position_z;
        pl.scalar_hi = size;
        pl.scalar_name = "height z";
        pl.scalar_key = "height";
      }
    }
    if (!pl.positions->valid()) pl.positions = nullptr;
    v.points = pl;
    if (params_.get_text("render.background") == "stars" && stars_.valid()) {
      scene::ImageLayer img;
      img.pixels = &stars_.impl();
      img.width = star_w_;
      img.height = star_h_;
      img.format = scene::ImageLayer::Format::rgba32f;
      // u^400 keeps about one pixel in 400 visible: a sparse field of faint stars.
      img.gamma = 400.0f;
      img.gain = 0.8f;
      img.mono = true;
      img.version = graph_.version("stars");
      v.background = img;
    }
    return v;
  }

 protected:
  void on_clock(const scene::FrameClock& clock) override {
    if (float(clock.time_s) != time_s_) {
      time_s_ = float(clock.time_s);
      graph_.touch("time");
    }
  }

  void validate(const ParamSet& p) const override {
    const double c = expected_candidates(p);
    // The neighbour walk stops at 65,000 candidates (lavapipe's loop limit); keep the mean far
    // below so that dense spots do not reach it.
    if (p.get_text("particles.color_by") == "neighbors" && c > 8000.0) {
      const double cells =
          std::ceil(std::cbrt(27.0 * double(p.get_int("particles.count")) / 8000.0));
      throw Error("", "particles scene",
                  fmt::format("particles.count = {} in {}^3 cells puts ~{:.0f} candidates in "
                              "each 27-cell neighbour walk (at most 8000 keeps every walk under "
                              "the 65,000 cap)",
                              p.get_int("particles.count"), p.get_int("particles.grid_cells"), c),
                  fmt::format("set particles.grid_cells >= {:.0f}, or fewer particles", cells));
    }
  }

 private:
  uint32_t n() const { return uint32_t(params_.get_int("particles.count")); }
  bool by_neighbors() const { return params_.get_text("particles.color_by") == "neighbors"; }

  void sample(Buffer<float>& out, uint64_t stream, const char* label) {
    if (out.size() != 4 * size_t(n())) out = backend_.create<float>(4 * size_t(n()), label);
    backend_.philox_uniform({uint64_t(params_.get_int("particles.seed")), stream, 0}, out);
  }

  void drift() {
    if (positions_.size() != n()) positions_ = backend_.create<Real4>(n(), "positions");
    DriftParams d;
    d.n = n();
    const float size = float(params_.get_real("particles.box_size"));
    d.box_extent = {size, size, size};
    d.speed = float(params_.get_real("particles.drift_speed"));
    d.time_s = time_s_;
    backend_.drift_points(d, start_, direction_, positions_);
  }

  void bin() {
    const GridParams g = grid_of(params_, n());
    if (!grid_ || grid_->sorted_cells.size() != n() ||
        grid_->cell_start.size() != grid_cell_count(g))
      grid_ = std::make_unique<HashGrid>(make_hash_grid(backend_, g, n()));
    grid_->params = g;
    build_hash_grid(backend_, *grid_, positions_);
  }

  void reorder_points() {
    if (sorted_.size() != n()) sorted_ = backend_.create<Real4>(n(), "sorted positions");
    reorder(backend_, *grid_, positions_.impl(), sorted_.impl());
  }

  void count() {
    if (counts_.size() != n()) counts_ = backend_.create<uint32_t>(n(), "neighbour counts");
    const NeighborParams np = make_neighbor_params(grid_->params, radius_of(params_));
    backend_.grid_count_neighbors(np, sorted_, grid_->cell_start, grid_->cell_end, counts_);
  }

  void stars() {
    // One star texel per pixel up to full HD; larger frames stretch it (a 8192^2 field would
    // not fit lavapipe's 128 MiB per buffer).
    constexpr int64_t kMaxSide = 1920;
    star_w_ = uint32_t(std::min(params_.get_int("render.width"), kMaxSide));
    star_h_ = uint32_t(std::min(params_.get_int("render.height"), kMaxSide));
    const size_t words = 4 * size_t(star_w_) * star_h_;
    if (stars_.size() != words) stars_ = backend_.create<float>(words, "star field");
    backend_.philox_uniform({uint64_t(params_.get_int("particles.seed")), kStarStream, 0}, stars_);
  }

  float time_s_ = 0;
  Buffer<float> start_, direction_, stars_;
  Buffer<Real4> positions_, sorted_;
  Buffer<uint32_t> counts_;
  std::unique_ptr<HashGrid> grid_;
  uint32_t star_w_ = 0, star_h_ = 0;
};

}  // namespace

const scene::TableSchema& particles_table() {
  static const scene::TableSchema t = [] {
    scene::TableSchema s("particles", "a Philox point cloud drifting through a periodic box");
    s.integer("count", 65536, 1, 4000000, "points");
    s.integer("seed", 1, 0, int64_t(1) << 53, "Philox key: the same seed, the same cloud");
    s.real("box_size", 1.0, 1e-3, 1e3, "edge of the cubic box (world units)");
    s.real("drift_speed", 0.05, 0.0, 10.0, "fastest drift along an axis", "box lengths/s");
    s.integer("grid_cells", 32, 1, 512, "hash-grid cells per axis");
    s.real("neighbor_radius", 1.0, 0.05, 1.0, "neighbour search radius", "cells");
    s.choice("color_by", "neighbors", {"neighbors", "speed", "height", "uniform"},
             "per-point scalar shown through the colour map");
    return s;
  }();
  return t;
}

scene::SceneType particles_scene_type() {
  scene::SceneType t;
  t.name = "particles";
  t.help = "Philox point cloud, drifting, binned in a hash grid, coloured by neighbour count";
  t.tables = {&particles_table()};
  t.kernels = [](const ParamSet& p) {
    std::vector<KernelId> k = {KernelId::philox_uniform, KernelId::drift_points};
    if (p.get_text("particles.color_by") == "neighbors")
      k.insert(k.end(),
               {KernelId::grid_assign_cells, KernelId::radix_sort, KernelId::grid_cell_ranges,
                KernelId::gather, KernelId::grid_count_neighbors});
    return k;
  };
  t.check_inputs = [](const ParamSet& p) {
    scene::CheckInputs c;
    c.points = uint32_t(std::min(p.get_int("particles.count"), p.get_int("verify.max_points")));
    c.seed = uint64_t(p.get_int("particles.seed"));
    c.grid = grid_of(p, c.points);
    c.neighbor_radius = radius_of(p);
    return c;
  };
  t.make = [](Backend& b, const ParamSet& p,
              const scene::SceneHost&) -> std::unique_ptr<scene::SceneInstance> {
    return std::make_unique<ParticlesScene>(b, p);
  };
  // The grid's per-cell tables (cell start, end, counts: one u32 per cell each) are the buffers
  // that grow with the cube of grid_cells; the largest cube they fit in is the advice.
  t.fit_advice = [](const ParamSet& p, uint64_t limit_bytes) -> std::string {
    const uint64_t cells = uint64_t(p.get_int("particles.grid_cells"));
    uint64_t fit = cells;
    while (fit > 0 && fit * fit * fit * sizeof(uint32_t) > limit_bytes) --fit;
    if (fit == cells) return "";  // the grid fits: another buffer is the cause
    if (fit == 0) return "this device's buffers cannot hold even one grid cell's table";
    return fmt::format(
        "set particles.grid_cells <= {} (its {}^3-cell tables then fit the "
        "{:.4g} MiB per buffer), or use a device with larger buffers",
        fit, fit, double(limit_bytes) / double(1 << 20));
  };
  return t;
}

}  // namespace masav::points
