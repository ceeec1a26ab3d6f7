// Cross-check of drift_points: positions within the kernel's stated fp32 tolerance
// (drift_compare.h), compared across the periodic boundary.
#include "engine/points/points_checks.h"

#include <fmt/format.h>

#include "engine/kernels/philox.h"
#include "engine/points/drift_compare.h"

namespace masav::verify {
namespace {

DriftParams drift_for(const CheckInputs& in) {
  DriftParams p;
  p.n = in.points;
  if (in.grid) {
    const float size = in.grid->cell_size * float(in.grid->dims.x);
    p.box_lo = in.grid->origin;
    p.box_extent = {size, size, size};
  }
  p.speed = 0.05f;
  p.time_s = 37.5f;  // far enough that most points wrapped at least once
  return p;
}

std::vector<double> flatten(const std::vector<Vec4d>& v) {
  std::vector<double> out;
  out.reserve(4 * v.size());
  for (const auto& q : v) out.insert(out.end(), {q.x, q.y, q.z, q.w});
  return out;
}

std::vector<Vec4d> unflatten(const std::vector<double>& v) {
  std::vector<Vec4d> out(v.size() / 4);
  for (size_t i = 0; i < out.size(); ++i)
    out[i] = {v[4 * i], v[4 * i + 1], v[4 * i + 2], v[4 * i + 3]};
  return out;
}

}  // namespace

std::vector<KernelCheck> points_checks() {
  KernelCheck k;
  k.kernel = "drift_points";
  k.kind = CheckKind::tolerance;
  k.run = [](Backend& b, const CheckInputs& in) {
    const DriftParams p = drift_for(in);
    // Identical inputs: the uniforms made on the host, uploaded to both backends.
    auto uniforms = [&](uint64_t stream) {
      std::vector<float> u(4 * size_t(in.points));
      for (size_t blk = 0; blk < in.points; ++blk) {
        const philox::Block r = philox::stream_block(in.seed, stream, blk);
        for (int j = 0; j < 4; ++j) u[4 * blk + j] = philox::u01(r.w[j]);
      }
      return u;
    };
    auto start = b.create<float>(4 * size_t(in.points), "check start");
    auto dir = b.create<float>(4 * size_t(in.points), "check direction");
    auto pos = b.create<Real4>(in.points, "check positions");
    b.upload(start, uniforms(0));
    b.upload(dir, uniforms(1));
    b.drift_points(p, start, dir, pos);
    return CheckOutputs{{"positions", {}, flatten(b.download(pos))}};
  };
  k.compare = [](const CheckOutputs& got, const CheckOutputs& want, const CheckInputs& in) {
    const DriftParams p = drift_for(in);
    const DriftError e = compare_drift(p, unflatten(got.at(0).reals), unflatten(want.at(0).reals));
    const DriftTolerance tol = drift_tolerance(p);
    Verdict v;
    v.pass = got.at(0).reals.size() == want.at(0).reals.size() && e.non_finite == 0 &&
             e.max_position_abs <= tol.position_abs && e.max_speed_rel <= tol.speed_rel;
    v.metrics = fmt::format("max position error {:.3g} (periodic), max speed rel {:.3g}{}",
                            e.max_position_abs, e.max_speed_rel,
                            e.non_finite ? fmt::format(", {} non-finite", e.non_finite) : "");
    v.tolerance = fmt::format("position within {:.3g}, speed within {:.3g} rel (fp32 rounding)",
                              tol.position_abs, tol.speed_rel);
    v.numbers = {{"max_position_abs", e.max_position_abs},
                 {"max_speed_rel", e.max_speed_rel},
                 {"tol_position_abs", tol.position_abs},
                 {"tol_speed_rel", tol.speed_rel},
                 {"non_finite", double(e.non_finite)}};
    return v;
  };
  return {k};
}

}  // namespace masav::verify
