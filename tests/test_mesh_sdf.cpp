// The signed distance field of a closed mesh: exact at the nodes against analytic distances (a
// box to 1e-12, a sphere within the mesh's own approximation), the sign inside and out, trilinear
// samples and gradients, the grid's limits, the same bits for any thread count, and the disk
// cache (a second call loads; a damaged, truncated or lying file is rebuilt).
#include <doctest/doctest.h>

#include <chrono>
#include <fstream>

#include "engine/core/error.h"
#include "engine/mesh/mesh_distance.h"
#include "engine/mesh/mesh_sdf.h"
#include "engine/mesh/sdf_cache.h"
#include "engine/util/cache_file.h"
#include "tests/mesh_fixture.h"
#include "tests/temp_dir.h"
#include "tests/error_of.h"

using namespace masav;
using masav::test::error_of;
using namespace masav::mesh;
using masav::test::TempDir;

namespace {

// The largest |field - box distance| over the nodes.
double box_error(const SignedDistanceField& f, Point lo, Point hi) {
  double worst = 0;
  for (uint32_t k = 0; k < f.dims.z; ++k)
    for (uint32_t j = 0; j < f.dims.y; ++j)
      for (uint32_t i = 0; i < f.dims.x; ++i)
        worst = std::max(worst, std::fabs(f.node(i, j, k) -
                                          test::box_distance(f.node_position(i, j, k), lo, hi)));
  return worst;
}

}  // namespace

TEST_CASE("closest point on a triangle: each Voronoi region, and its feature") {
  const Point a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
  auto q = [&](Point p) { return closest_point_on_triangle(p, a, b, c); };
  CHECK(q({-1, -1, 3}).feature == Feature::corner0);
  CHECK(q({2, -1, 0}).feature == Feature::corner1);
  CHECK(q({-0.5, 3, 1}).feature == Feature::corner2);
  const ClosestPoint e0 = q({0.25, -2, 1});
  CHECK(e0.feature == Feature::edge0);
  CHECK(e0.point.x == 0.25);
  CHECK(e0.point.y == 0);
  const ClosestPoint e1 = q({1, 1, -2});
  CHECK(e1.feature == Feature::edge1);
  CHECK(e1.point.x == doctest::Approx(0.5).epsilon(1e-15));
  CHECK(q({-3, 0.5, 0}).feature == Feature::edge2);
  const ClosestPoint f = q({0.2, 0.3, -5});
  CHECK(f.feature == Feature::face);
  CHECK(f.point.x == doctest::Approx(0.2).epsilon(1e-15));
  CHECK(f.point.z == 0);
}

TEST_CASE("mesh sdf: a box's field is the analytic box distance at every node") {
  const Point lo{-0.3, 0, 0.1}, hi{0.7, 2, 0.6};
  for (uint32_t n : {1u, 3u}) {
    CAPTURE(n);
    const TriangleMesh box = test::box_mesh(lo, hi, n);
    const SignedDistanceField f = build_sdf(box, {0.05, 0.2});
    CHECK(f.dims.x == 29);  // (1 + 0.4) / 0.05 = 28 cells
    CHECK(f.dims.y == 49);
    CHECK(f.dims.z == 19);
    CHECK(f.origin.x == doctest::Approx(-0.5).epsilon(1e-15));
    CHECK(box_error(f, lo, hi) < 1e-12);
    CHECK(f.min_value() == doctest::Approx(-0.25).epsilon(1e-12));
    // Outward from a face the distance is affine: trilinear samples and gradients are exact.
    const Point p{0.113, 2.07, 0.333};
    CHECK(f.sample(p) == doctest::Approx(0.07).epsilon(1e-12));
    const Point g = f.gradient(p);
    CHECK(std::fabs(g.x) < 1e-10);
    CHECK(g.y == doctest::Approx(1).epsilon(1e-10));
    CHECK(std::fabs(g.z) < 1e-10);
    // At a node the sample is the node.
    const Point at = f.node_position(3, 7, 11);
    CHECK(f.sample(at) == doctest::Approx(f.node(3, 7, 11)).epsilon(1e-13));
    // Off the grid: the value at the nearest point of the grid's box.
    CHECK(f.sample({100, 1, 0.35}) ==
          doctest::Approx(f.sample({f.origin.x + 28 * 0.05, 1, 0.35})).epsilon(1e-12));
  }
}

TEST_CASE("mesh sdf: an icosphere's field is within its approximation error of |p| - r") {
  const double r = 0.5;
  const Point centre{0.1, -0.2, 0.3};
  for (uint32_t levels : {1u, 3u}) {
    CAPTURE(levels);
    const TriangleMesh ball = test::icosphere(r, levels, centre);
    // The mesh lies between the ball of radius r and that of its nearest face plane, so its
    // signed distance lies between theirs: |sdf - (|p| - r)| <= r - r_in.
    double r_in = r;
    for (const auto& t : ball.triangles) {
      const Point a = ball.vertices[t[0]] - centre, b = ball.vertices[t[1]] - centre,
                  c = ball.vertices[t[2]] - centre;
      const Point n = cross(b - a, c - a);
      r_in = std::min(r_in, dot(a, n) / length(n));
    }
    const SignedDistanceField f = build_sdf(ball, {0.04, 0.1});
    uint64_t inside = 0, outside = 0;
    double worst = 0;
    for (uint32_t k = 0; k < f.dims.z; ++k)
      for (uint32_t j = 0; j < f.dims.y; ++j)
        for (uint32_t i = 0; i < f.dims.x; ++i) {
          const double d = f.node(i, j, k), rho = length(f.node_position(i, j, k) - centre);
          worst = std::max(worst, std::fabs(d - (rho - r)));
          if (rho < r_in - 1e-9) {
            CHECK(d < 0);
            ++inside;
          } else if (rho > r + 1e-9) {
            CHECK(d > 0);
            ++outside;
          }
        }
    MESSAGE("levels " << levels << ": r - r_in = " << r - r_in << ", worst " << worst);
    CHECK(worst <= r - r_in + 1e-12);
    CHECK(inside > 1000);
    CHECK(outside > 1000);
    CHECK(f.sample(centre) < -r_in + 0.05);
    // The gradient points away from the centre (within the facets' tilt) and has length 1
    // (within the interpolation's error), off the centre's kink.
    double min_cos = 1, worst_length = 0;
    for (int n = 0; n < 200; ++n) {
      const double rho = 0.2 + 0.4 * (n % 10) / 9.0, phi = 0.7 * n, z = std::cos(1.3 * n);
      const Point u{std::sqrt(1 - z * z) * std::cos(phi), std::sqrt(1 - z * z) * std::sin(phi), z};
      const Point g = f.gradient(centre + rho * u);
      min_cos = std::min(min_cos, dot(g, u) / length(g));
      worst_length = std::max(worst_length, std::fabs(length(g) - 1));
    }
    MESSAGE("levels " << levels << ": gradients within " << std::acos(min_cos)
                      << " rad of radial, lengths within " << worst_length << " of 1");
    CHECK(min_cos > (levels == 1 ? 0.85 : 0.97));
    CHECK(worst_length < 0.2);
  }
}

TEST_CASE("mesh sdf: the same bits for any thread count") {
  const TriangleMesh ball = test::icosphere(1, 3);
  const SignedDistanceField one = build_sdf(ball, {0.1, 0.3, 1});
  const SignedDistanceField three = build_sdf(ball, {0.1, 0.3, 3});
  REQUIRE(one.values.size() == three.values.size());
  CHECK(std::memcmp(one.values.data(), three.values.data(), one.values.size() * 8) == 0);
  // The search's hint changes nothing: a point queried cold and from a far triangle agrees.
  const MeshDistance dist(ball, "ball");
  const Point p{0.3, -0.7, 0.2};
  uint32_t hint = 0;
  const double cold = dist.signed_distance(p), warm = dist.signed_distance(p, &hint);
  CHECK(cold == warm);
  CHECK(dist.nearest(p).triangle == hint);
}

TEST_CASE("mesh sdf: bad parameters, a grid over the limit and an open mesh are refused") {
  const TriangleMesh cube = test::unit_cube();
  CHECK(error_of([&] {
          build_sdf(cube, {0, 0.1});
        }).find("mesh sdf: invalid spacing = 0 (remedy: spacing must be a finite number > 0)") ==
        0);
  CHECK(error_of([&] {
          build_sdf(cube, {std::nan(""), 0.1});
        }).find("invalid spacing = nan") != std::string::npos);
  CHECK(error_of([&] {
          build_sdf(cube, {0.1, -1});
        }).find("invalid padding = -1") != std::string::npos);
  CHECK(error_of([&] {
          build_sdf(cube, {0.1, INFINITY});
        }).find("invalid padding = inf") != std::string::npos);
  const std::string big = error_of([&] { build_sdf(cube, {0.001, 0}); });
  CHECK_MESSAGE(
      big.find("invalid grid = 1001 x 1001 x 1001 nodes at spacing 0.001 (remedy: grid "
               "must be at most 16777216 nodes: a spacing of about ") != std::string::npos,
      big);
  CHECK(error_of([&] {
          build_sdf(cube, {1e-300, 1e300});
        }).find("invalid grid") != std::string::npos);
  TriangleMesh open = cube;
  open.triangles.pop_back();
  CHECK(error_of([&] {
          build_sdf(open, {0.1, 0.1}, "mesh file 'open.obj'");
        }).find("mesh file 'open.obj': not watertight: 3 open edges") == 0);
}

TEST_CASE("mesh sdf cache: a second call loads; a damaged or lying file is rebuilt") {
  TempDir dir("mesh_sdf_cache");
  const TriangleMesh ball = test::icosphere(1, 2);
  const SdfParams p{0.1, 0.2};
  CHECK(sdf_cache_path(ball, p, "") == "");
  const SdfBuild none = load_or_build_sdf(ball, p, "");
  CHECK(!none.from_cache);
  CHECK(none.cache_path.empty());

  const std::string root = dir.path.string();
  const SdfBuild first = load_or_build_sdf(ball, p, root);
  CHECK(!first.from_cache);
  CHECK(first.rejected.empty());
  REQUIRE(std::filesystem::exists(first.cache_path));
  CHECK(first.cache_path.find(root + "/mesh-sdf/") == 0);
  const SdfBuild second = load_or_build_sdf(ball, p, root);
  CHECK(second.from_cache);
  CHECK(second.field.dims.x == first.field.dims.x);
  CHECK(std::memcmp(second.field.values.data(), first.field.values.data(),
                    first.field.values.size() * 8) == 0);
  CHECK(std::memcmp(second.field.values.data(), none.field.values.data(),
                    first.field.values.size() * 8) == 0);

  // Other parameters or another mesh: another file.
  CHECK(sdf_content_hash(ball, {0.1, 0.25}) != sdf_content_hash(ball, p));
  TriangleMesh moved = ball;
  moved.vertices[7].x = std::nextafter(moved.vertices[7].x, 2.0);
  CHECK(sdf_content_hash(moved, p) != sdf_content_hash(ball, p));

  auto bytes = [&] {
    std::ifstream in(first.cache_path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  const std::string good = bytes();
  auto damaged = [&](const std::string& content, const std::string& why) {
    CAPTURE(why);
    test::write_bytes(first.cache_path, content);
    const SdfBuild b = load_or_build_sdf(ball, p, root);
    CHECK(!b.from_cache);
    CHECK_MESSAGE(b.rejected.find(why) != std::string::npos, b.rejected);
    CHECK(std::memcmp(b.field.values.data(), first.field.values.data(),
                      first.field.values.size() * 8) == 0);
    CHECK(bytes() == good);  // rewritten
    CHECK(load_or_build_sdf(ball, p, root).from_cache);
  };
  std::string flipped = good;
  flipped[flipped.size() - 100] ^= 0x10;
  damaged(flipped, "payload checksum mismatch");
  damaged(good.substr(0, good.size() - 8), "truncated or extended");
  damaged(good + "x", "truncated or extended");
  damaged("", "not a masav cache file");
  // A file whose envelope is whole but whose key is another's: refused by the key.
  std::string other_key = good;
  other_key.replace(other_key.find("dims="), 5, "dimz=");
  damaged(other_key, "key mismatch");
  // Checksummed but impossible: a distance the grid cannot hold.
  std::vector<double> lying = first.field.values;
  lying[42] = 1e9;
  const std::string payload(reinterpret_cast<const char*>(lying.data()), lying.size() * 8);
  const size_t k0 = good.find("\nkey ") + 5, k1 = good.find('\n', k0);
  const CacheFileId id{"mesh-sdf", 1, good.substr(k0, k1 - k0)};
  damaged(cache_file_header(id, payload) + payload, "node 42 holds 1000000000");
}

// 10^5 triangles and a 64^3 field in seconds (its own ctest entry, mesh.sdf_speed).
TEST_CASE("mesh sdf speed: 10^5 triangles, 64^3 nodes") {
  const double r = 1;
  const TriangleMesh ball = test::icosphere(r, 6);
  CHECK(ball.triangles.size() == 81920);
  auto t0 = std::chrono::steady_clock::now();
  const SignedDistanceField f = build_sdf(ball, {(2 * r + 0.2) / 63, 0.1});
  const double ball_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  CHECK(f.dims.x == 64);
  CHECK(f.values.size() == 64 * 64 * 64);
  const Point lo{-1, -1, -1}, hi{1, 1, 1};
  const TriangleMesh box = test::box_mesh(lo, hi, 92);
  CHECK(box.triangles.size() == 101568);
  t0 = std::chrono::steady_clock::now();
  const SignedDistanceField g = build_sdf(box, {2.2 / 63, 0.1});
  const double box_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  CHECK(g.dims.x == 64);
  CHECK(box_error(g, lo, hi) < 1e-12);
  MESSAGE("icosphere of " << ball.triangles.size() << " triangles, 64^3 nodes: " << ball_s
                          << " s; box of " << box.triangles.size() << " triangles: " << box_s
                          << " s (one thread)");
  CHECK(ball_s < 60);
  CHECK(box_s < 60);
}
