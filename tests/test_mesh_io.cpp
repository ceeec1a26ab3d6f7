// Triangle meshes read from OBJ and STL files within limits, and the closed-surface check: round
// trips of meshes made in code, and every refusal with the text that names its cause.
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <regex>

#include "engine/core/error.h"
#include "engine/mesh/mesh_check.h"
#include "engine/mesh/mesh_io.h"
#include "tests/mesh_fixture.h"
#include "tests/temp_dir.h"
#include "tests/error_of.h"

using namespace masav;
using masav::test::error_of;
using namespace masav::mesh;
using masav::test::TempDir;

namespace {

std::string read_error(const std::string& path) {
  return error_of([&] { read_mesh(path); });
}

// The double nearest x that a float holds, as a binary STL stores it. Through a volatile: GCC 12
// at -O2 dropped the rounding of double(float(x)) for two of the three coordinates of a Point
// built in this loop (a standalone copy of the loop reproduces it; -O0 and -O1 do not).
double as_float_value(double x) {
  volatile float f = float(x);
  return f;
}

// Every triangle of `got` has the corner positions of the same triangle of `want`.
void check_same_surface(const TriangleMesh& got, const TriangleMesh& want, bool as_float = false) {
  REQUIRE(got.triangles.size() == want.triangles.size());
  for (size_t t = 0; t < got.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const Point o = want.vertices[want.triangles[t][k]];
      const Point w =
          as_float ? Point{as_float_value(o.x), as_float_value(o.y), as_float_value(o.z)} : o;
      const Point g = got.vertices[got.triangles[t][k]];
      REQUIRE_MESSAGE(std::memcmp(&g, &w, sizeof(Point)) == 0,
                      fmt::format("triangle {} corner {}: {} {} {} read, {} {} {} written", t, k,
                                  g.x, g.y, g.z, w.x, w.y, w.z));
    }
}

}  // namespace

TEST_CASE("mesh files: OBJ, binary STL and ASCII STL read back what was written") {
  TempDir dir("mesh_round_trip");
  const TriangleMesh cube = test::unit_cube(), ball = test::icosphere(0.5, 2, {0.1, -0.2, 0.3});
  MeshFormat format{};

  test::write_bytes(dir.file("ball.obj"), test::obj_text(ball));
  const TriangleMesh obj = read_mesh(dir.file("ball.obj"), &format);
  CHECK(format == MeshFormat::obj);
  CHECK(obj.vertices.size() == ball.vertices.size());
  CHECK(std::memcmp(obj.vertices.data(), ball.vertices.data(), ball.vertices.size() * 24) == 0);
  CHECK(obj.triangles == ball.triangles);

  // STL repeats each corner; welding by position gives back one vertex per position.
  test::write_bytes(dir.file("cube.stl"), test::stl_binary(cube));
  const TriangleMesh bin = read_mesh(dir.file("cube.stl"), &format);
  CHECK(format == MeshFormat::stl_binary);
  CHECK(bin.vertices.size() == 8);
  check_same_surface(bin, cube);
  CHECK(check_mesh(bin).closed());

  test::write_bytes(dir.file("ball_bin.STL"), test::stl_binary(ball));
  const TriangleMesh ball_bin = read_mesh(dir.file("ball_bin.STL"), &format);
  CHECK(ball_bin.vertices.size() == ball.vertices.size());
  check_same_surface(ball_bin, ball, true);

  test::write_bytes(dir.file("ball_ascii.stl"), test::stl_ascii(ball));
  const TriangleMesh ascii = read_mesh(dir.file("ball_ascii.stl"), &format);
  CHECK(format == MeshFormat::stl_ascii);
  CHECK(ascii.vertices.size() == ball.vertices.size());
  check_same_surface(ascii, ball);
}

TEST_CASE("OBJ: polygons as fans, relative indices, v/t/n forms; other lines ignored") {
  const std::string text =
      "# a unit cube of quads\r\nmtllib cube.mtl\no cube\n"
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 0 1\nv 1 0 1\nv 0 1 1\nv +1 1 1 1.0\n"
      "vt 0 0\nvn 0 0 1\ns off\ng sides\nusemtl grey\n"
      "f 1/1 3/1 4/1 2/1\n"      // z = 0
      "f 5//1 6//1 8//1 7//1\n"  // z = 1
      "f -8/1/1 -7/1/1 -3 -4\n"  // y = 0: 1 2 6 5, counted back from vertex 8
      "f 3 7 8 4\n"              // y = 1
      "f 1 5 7 3\n"              // x = 0
      "l 1 2\n"
      "f 2 4 8 6\n";  // x = 1
  const TriangleMesh m = parse_obj(text, "cube.obj");
  CHECK(m.vertices.size() == 8);
  REQUIRE(m.triangles.size() == 12);
  CHECK(m.triangles[0] == std::array<uint32_t, 3>{0, 2, 3});
  CHECK(m.triangles[1] == std::array<uint32_t, 3>{0, 3, 1});
  CHECK(m.triangles[4] == std::array<uint32_t, 3>{0, 1, 5});
  const MeshCheck c = check_mesh(m);
  CHECK_MESSAGE(c.closed(), c.problem);
  CHECK(c.area == doctest::Approx(6).epsilon(1e-15));
  CHECK(c.volume == doctest::Approx(1).epsilon(1e-15));
  // Positive indices may name vertices listed later (checked once the file is read).
  CHECK(parse_obj("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n", "x").triangles.size() == 1);
}

TEST_CASE("mesh files: bad contents are refused, naming the line or triangle and the value") {
  TempDir dir("mesh_bad");
  auto obj = [&](const std::string& text) {
    test::write_bytes(dir.file("m.obj"), text);
    return read_error(dir.file("m.obj"));
  };
  const std::string verts = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  CHECK(obj("").find("mesh file '" + dir.file("m.obj") + "': the file is empty (0 bytes)") !=
        std::string::npos);
  CHECK(obj(verts).find("holds 3 vertices and no triangles (no 'f' lines): a mesh needs at "
                        "least one") != std::string::npos);
  CHECK(obj("v 0 0 0\nv nan 0 0\n").find("line 2: invalid vertex 2 x = nan") != std::string::npos);
  CHECK(obj("v 0 0 0\nv 0 inf 0\n").find("line 2: invalid vertex 2 y = inf") != std::string::npos);
  CHECK(obj("v 0 0 1e999\n").find("line 1: invalid vertex 1 z = 1e999") != std::string::npos);
  CHECK(obj("v 0 zero 0\n").find("line 1: invalid vertex 1 y = 'zero'") != std::string::npos);
  CHECK(obj("v 0 0\n").find("line 1: invalid vertex 1 z = (missing)") != std::string::npos);
  CHECK(obj(verts + "f 1 2 9\n")
            .find("line 4: invalid face index = 9 (remedy: face index must be from 1 to 3: the "
                  "file has 3 vertices)") != std::string::npos);
  CHECK(obj(verts + "f 1 2 -4\n").find("line 4: invalid face index = -4") != std::string::npos);
  CHECK(obj(verts + "f 1 2 0\n").find("line 4: invalid face index = '0'") != std::string::npos);
  CHECK(obj(verts + "f 1 2\n").find("line 4: a face of 2 vertices") != std::string::npos);

  auto stl = [&](const std::string& bytes) {
    test::write_bytes(dir.file("m.stl"), bytes);
    return read_error(dir.file("m.stl"));
  };
  CHECK(stl("").find("the file is empty (0 bytes)") != std::string::npos);
  TriangleMesh cube = test::unit_cube();
  cube.vertices[5].y = std::nan("");
  const std::string nan_vertex = stl(test::stl_binary(cube));
  CHECK_MESSAGE(std::regex_search(nan_vertex, std::regex("triangle [0-9]+: invalid vertex [0-2] "
                                                         "y = nan")),
                nan_vertex);
  CHECK(stl("solid x\nendsolid x\n").find("holds 0 vertices and no triangles (no facets)") !=
        std::string::npos);
  CHECK(stl("solid x\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 nan\n")
            .find("line 5: invalid vertex z = nan") != std::string::npos);
  CHECK(stl("solid x\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n  endloop\n endfacet\n")
            .find("line 6: a facet with 1 vertices") != std::string::npos);
  CHECK(stl("solid x\n facet normal 0 0 1\n").find("ends inside a facet") != std::string::npos);
  CHECK(stl("solid x\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n"
            "   vertex 0 1 0\n   vertex 1 1 0\n")
            .find("line 7: a facet with more than 3 vertices") != std::string::npos);
  CHECK(stl("hello\n").find("shorter than a binary STL's 84-byte header") != std::string::npos);
  CHECK(stl("solid x\n bogus\n").find("line 2: unexpected 'bogus'") != std::string::npos);
}

TEST_CASE("binary STL: a header count over the limit or unlike the file size is refused first") {
  TempDir dir("mesh_stl_header");
  const TriangleMesh cube = test::unit_cube();
  const auto t0 = std::chrono::steady_clock::now();
  test::write_bytes(dir.file("huge.stl"), test::stl_binary(cube, 100'000'000));
  const std::string huge = read_error(dir.file("huge.stl"));
  CHECK_MESSAGE(huge.find("(binary STL header): invalid triangles = 100000000 (remedy: triangles "
                          "must be at most 10000000)") != std::string::npos,
                huge);
  // A sparse file as long as 10^8 triangles need: refused by the count before a byte is read.
  test::write_bytes(dir.file("sparse.stl"), test::stl_binary(cube, 100'000'000).substr(0, 84));
  if (::truncate(dir.file("sparse.stl").c_str(), 84 + 50 * off_t(100'000'000)) == 0)
    CHECK(read_error(dir.file("sparse.stl")).find("invalid triangles = 100000000") !=
          std::string::npos);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  CHECK(s < 1.0);

  test::write_bytes(dir.file("lies.stl"), test::stl_binary(cube, 5));
  CHECK(read_error(dir.file("lies.stl"))
            .find("the binary STL header declares 5 triangles, which take 84 + 50 x 5 = 334 bytes, "
                  "but the file holds 684 bytes") != std::string::npos);
  // A binary file whose header starts with "solid" and whose count lies is read as ASCII, and
  // the error says why.
  std::string solid = test::stl_binary(cube, 7);
  std::memcpy(solid.data(), "solid", 5);
  test::write_bytes(dir.file("solid.stl"), solid);
  CHECK(read_error(dir.file("solid.stl"))
            .find("read as ASCII because its 684 bytes are not the 84 + 50 x 7 = 434 of a binary "
                  "STL") != std::string::npos);
}

TEST_CASE("mesh files: a directory, a FIFO, a device or an unknown extension is refused") {
  TempDir dir("mesh_paths");
  std::filesystem::create_directories(dir.file("folder.obj"));
  CHECK(read_error(dir.file("folder.obj")).find("is a directory") != std::string::npos);
  REQUIRE(::mkfifo(dir.file("pipe.stl").c_str(), 0600) == 0);
  CHECK(read_error(dir.file("pipe.stl")).find("is a FIFO (named pipe), not a regular file") !=
        std::string::npos);
  CHECK(read_error("/dev/zero").find("'/dev/zero' is a character device, not a regular file") !=
        std::string::npos);
  CHECK(read_error(dir.file("absent.obj")).find("does not exist") != std::string::npos);
  test::write_bytes(dir.file("cube.ply"), "ply\n");
  CHECK(read_error(dir.file("cube.ply")).find("is neither an OBJ nor an STL file by its name") !=
        std::string::npos);
}

TEST_CASE("mesh check: area, volume, and the first open, non-manifold or misoriented edge") {
  const TriangleMesh cube = test::unit_cube();
  MeshCheck c = check_mesh(cube);
  CHECK_MESSAGE(c.closed(), c.problem);
  CHECK(c.area == 6);
  CHECK(c.volume == doctest::Approx(1).epsilon(1e-15));
  const TriangleMesh ball = test::icosphere(2, 4);
  c = check_mesh(ball);
  CHECK_MESSAGE(c.closed(), c.problem);
  CHECK(c.volume == doctest::Approx(4 / 3.0 * M_PI * 8).epsilon(0.01));
  CHECK(c.area == doctest::Approx(4 * M_PI * 4).epsilon(0.01));

  // The box's last face (its last two triangles, z = 1) removed.
  TriangleMesh open = cube;
  open.triangles.resize(10);
  c = check_mesh(open);
  CHECK(c.open_edges == 4);
  CHECK(c.problem.find("not watertight: 4 open edges (used by one triangle only); the first: "
                       "vertices ") == 0);
  std::smatch mt;
  REQUIRE_MESSAGE(std::regex_search(c.problem, mt,
                                    std::regex("vertices [0-9]+ \\(([-0-9.e]+), "
                                               "([-0-9.e]+), ([-0-9.e]+)\\) and "
                                               "[0-9]+ \\(([-0-9.e]+), "
                                               "([-0-9.e]+), ([-0-9.e]+)\\)")),
                  c.problem);
  // Both ends on the removed face (the last face box_mesh makes is z = 1).
  CHECK(std::stod(mt[3]) == 1);
  CHECK(std::stod(mt[6]) == 1);
  CHECK(c.remedy.find("close the surface") == 0);
  CHECK(error_of([&] { edge_neighbours(open, "m.obj"); }).find("m.obj: not watertight") == 0);

  // A fin: a third triangle on one of the cube's edges.
  TriangleMesh fin = cube;
  const auto e = cube.triangles[0];
  fin.vertices.push_back({-1, -1, -1});
  fin.triangles.push_back({e[0], e[1], uint32_t(fin.vertices.size() - 1)});
  c = check_mesh(fin);
  CHECK(c.nonmanifold_edges == 1);
  CHECK_MESSAGE(c.problem.find(fmt::format("not manifold: 1 edge shared by three or more "
                                           "triangles; the first: vertices {} ",
                                           e[0])) == 0,
                c.problem);
  CHECK(c.problem.find("shared by triangles 0, ") != std::string::npos);
  CHECK(c.problem.find(", 12") != std::string::npos);

  // Two cubes touching along an edge: closed, but that edge has four triangles.
  TriangleMesh pair = cube;
  const TriangleMesh other = test::box_mesh({1, 1, 0}, {2, 2, 1});
  for (const auto& t : other.triangles) {
    std::array<uint32_t, 3> u{};
    for (int k = 0; k < 3; ++k) {
      const Point p = other.vertices[t[k]];
      uint32_t found = uint32_t(pair.vertices.size());
      for (uint32_t v = 0; v < pair.vertices.size(); ++v)
        if (std::memcmp(&pair.vertices[v], &p, sizeof(p)) == 0) found = v;
      if (found == pair.vertices.size()) pair.vertices.push_back(p);
      u[k] = found;
    }
    pair.triangles.push_back(u);
  }
  c = check_mesh(pair);
  CHECK(c.open_edges == 0);
  CHECK(c.nonmanifold_edges == 1);
  CHECK(c.problem.find(" (1, 1, 0)") != std::string::npos);
  CHECK(c.problem.find(" (1, 1, 1)") != std::string::npos);

  TriangleMesh flipped = cube;
  std::swap(flipped.triangles[3][1], flipped.triangles[3][2]);
  c = check_mesh(flipped);
  CHECK(c.misoriented_edges == 3);
  CHECK(c.problem.find("faces oriented inconsistently: 3 edges run in the same direction by both "
                       "of their triangles") == 0);
  CHECK(c.remedy.find("flip triangle 3") != std::string::npos);

  TriangleMesh inward = cube;
  for (auto& t : inward.triangles) std::swap(t[1], t[2]);
  c = check_mesh(inward);
  CHECK(c.problem.find("the enclosed volume is -1 (negative): the faces' normals point inward") ==
        0);
  CHECK(c.remedy.find("flip the faces") == 0);

  TriangleMesh flat = cube;
  flat.vertices.push_back(0.5 * (cube.vertices[0] + cube.vertices[1]));  // zero area with 0, 1
  flat.triangles.push_back({0, 1, uint32_t(flat.vertices.size() - 1)});
  c = check_mesh(flat);
  CHECK(c.degenerate == 1);
  CHECK(c.problem.find("1 zero-area triangle; the first: triangle 12 (vertices 0 (0, 0, 0), ") ==
        0);

  TriangleMesh bad_index = cube;
  bad_index.triangles[2][1] = 99;
  CHECK(check_mesh(bad_index).problem == "triangle 2 names vertex 99, but the mesh has 8 vertices");
}
