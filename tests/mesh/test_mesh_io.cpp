// Loading and saving meshes: round trips, the Debian models, and every kind of bad input.
#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "clothcd/geometry/bounding_volumes.hpp"
#include "clothcd/mesh/mesh_error.hpp"
#include "clothcd/mesh/mesh_generators.hpp"
#include "clothcd/mesh/mesh_info.hpp"
#include "clothcd/mesh/mesh_io.hpp"
#include "clothcd/mesh/mesh_validation.hpp"
#include "clothcd/mesh/model_catalog.hpp"
#include "support/test_support.hpp"

using clothcd::load_mesh;
using clothcd::MeshError;
using clothcd::save_mesh;
using clothcd::TriangleMesh;
using clothcd::test::TempDir;
using clothcd::test::write_file;

namespace {

/// Same faces and the same doubles: the writers and readers round-trip exactly.
void require_same_mesh(const TriangleMesh& saved, const TriangleMesh& loaded) {
  REQUIRE(saved.vertex_count() == loaded.vertex_count());
  REQUIRE(saved.faces == loaded.faces);
  REQUIRE(saved.vertices == loaded.vertices);
}

std::string ply_header(long long vertices, int faces) {
  return "ply\nformat ascii 1.0\nelement vertex " + std::to_string(vertices) +
         "\nproperty float x\nproperty float y\nproperty float z\nelement face " + std::to_string(faces) +
         "\nproperty list uchar int vertex_indices\nend_header\n";
}

/// Requires load_mesh(path) to throw a MeshError whose message names the file and contains `problem`.
void require_load_error(const std::filesystem::path& path, const std::string& problem) {
  try {
    (void)load_mesh(path);
    FAIL("expected an error for " << path);
  } catch (const MeshError& e) {
    const std::string message = e.what();
    INFO(message);
    CHECK(message.find(path.string()) != std::string::npos);
    CHECK(message.find(problem) != std::string::npos);
  }
}

}  // namespace

TEST_CASE("generated meshes survive an OBJ and a PLY round trip", "[mesh][io]") {
  TempDir dir;
  const auto extension = GENERATE(as<std::string>{}, ".obj", ".ply");
  for (const TriangleMesh& mesh : {clothcd::make_paper_cloth('A'), clothcd::make_uv_sphere(2.0, 12, 7),
                                   clothcd::make_uv_sphere(1.0, 8, 16),  // first coordinate's low byte is 0x0a
                                   clothcd::make_box(Eigen::Vector3d(1, 2, 3)), clothcd::make_fish()}) {
    const auto path = dir / ("mesh" + extension);
    save_mesh(mesh, path);
    require_same_mesh(mesh, load_mesh(path));
  }
}

TEST_CASE("identical vertices are joined across a polygon soup", "[mesh][io]") {
  TempDir dir;
  // Two triangles written as a soup of six corners: four distinct positions.
  const auto path = write_file(dir / "soup.obj",
                               "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 4 5 6\n");
  clothcd::LoadReport report;
  const TriangleMesh mesh = load_mesh(path, {}, &report);
  CHECK(mesh.vertex_count() == 4);
  CHECK(mesh.face_count() == 2);
  CHECK(report.vertices_joined == 2);
  CHECK(clothcd::compute_mesh_info(mesh).components == 1);
}

TEST_CASE("quads are triangulated", "[mesh][io]") {
  TempDir dir;
  const auto path = write_file(dir / "quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
  const TriangleMesh mesh = load_mesh(path);
  CHECK(mesh.face_count() == 2);
  CHECK(clothcd::compute_mesh_info(mesh).surface_area == Approx(1.0));
}

TEST_CASE("degenerate faces are reported and dropped", "[mesh][io]") {
  TempDir dir;
  // Face 2 is collinear, face 3 repeats an index: both have zero area.
  const auto path = write_file(dir / "degenerate.obj",
                               "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 1 2 4\nf 1 1 3\n");
  clothcd::LoadReport report;
  const TriangleMesh mesh = load_mesh(path, {}, &report);
  CHECK(mesh.face_count() == 1);
  CHECK(report.degenerate_faces_dropped >= 1);

  clothcd::LoadOptions keep;
  keep.drop_degenerate_faces = false;
  CHECK(clothcd::compute_mesh_info(load_mesh(path, keep)).degenerate_faces >= 1);
}

TEST_CASE("the Debian-package models load, validate and round-trip", "[mesh][io][models]") {
  TempDir dir;
  for (const auto& model : clothcd::model_catalog()) {
    INFO(model.name);
    const TriangleMesh mesh = load_mesh(clothcd::fetch_model(model.name, clothcd::test::test_model_dir()));
    CHECK(mesh.face_count() >= 12);
    CHECK(clothcd::compute_mesh_info(mesh).degenerate_faces == 0);
    const auto path = dir / (model.name + ".ply");
    save_mesh(mesh, path);
    require_same_mesh(mesh, load_mesh(path));
  }
}

TEST_CASE("bad mesh files give a clear error naming the file", "[mesh][io][errors]") {
  TempDir dir;
  SECTION("missing file") { require_load_error(dir / "nothing-here.obj", "no such file"); }
  SECTION("a directory") { require_load_error(dir.path(), "is a directory"); }
  SECTION("empty file") { require_load_error(write_file(dir / "empty.ply", ""), "empty"); }
  SECTION("truncated PLY") {
    require_load_error(write_file(dir / "truncated.ply", ply_header(3, 1) + "0 0 0\n1 0 0\n"), "");
  }
  SECTION("truncated binary PLY") {
    TriangleMesh mesh = clothcd::make_paper_cloth('A');
    const auto whole = dir / "whole.ply";
    save_mesh(mesh, whole);
    std::ifstream in(whole, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    require_load_error(write_file(dir / "cut.ply", bytes.substr(0, bytes.size() / 2)), "");
  }
  SECTION("NaN coordinate") {
    require_load_error(write_file(dir / "nan.obj", "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n"), "non-finite");
  }
  SECTION("infinite coordinate in PLY") {
    require_load_error(write_file(dir / "inf.ply", ply_header(3, 1) + "0 0 0\n1 0 0\ninf 1 0\n3 0 1 2\n"),
                       "non-finite");
  }
  SECTION("out-of-range index in OBJ") {
    require_load_error(write_file(dir / "index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n"), "out of range");
  }
  SECTION("out-of-range index in PLY") {
    require_load_error(write_file(dir / "index.ply", ply_header(3, 1) + "0 0 0\n1 0 0\n0 1 0\n3 0 1 9\n"),
                       "out of range");
  }
  SECTION("out-of-range index in OFF (which assimp would clamp silently)") {
    require_load_error(write_file(dir / "index.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 9\n"), "out of range");
  }
  SECTION("negative and wrapping indices in OFF") {
    require_load_error(write_file(dir / "negative.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 -1 1 2\n"), "out of range");
    require_load_error(write_file(dir / "wrap.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 4294967296\n"),
                       "out of range");
  }
  SECTION("an OFF face of two vertices") {
    require_load_error(write_file(dir / "two.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n"), "needs 3");
  }
  SECTION("an OFF body shorter than its counts (or a huge count)") {
    require_load_error(write_file(dir / "short.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"), "truncated");
    require_load_error(write_file(dir / "huge.off", "OFF\n3 99999999999 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
                       "truncated");
  }
  SECTION("an ASCII PLY body shorter than its header") {
    require_load_error(write_file(dir / "short.ply", ply_header(30, 1) + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"), "truncated");
    require_load_error(write_file(dir / "huge.ply", ply_header(4000000000, 1) + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
                       "truncated");
  }
  SECTION("an ASCII PLY line whose values do not match its element's properties") {
    const std::string vertices = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
    require_load_error(write_file(dir / "long_face.ply", ply_header(4, 2) + vertices + "255 0 1 2\n3 0 1 3\n"),
                       "PLY face 0 has 4 values, its properties need 256");
    require_load_error(write_file(dir / "short_vertex.ply", ply_header(4, 2) + "0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n3 0 1 3\n"),
                       "PLY vertex 0 has 2 values");
    CHECK(load_mesh(write_file(dir / "good.ply", ply_header(4, 2) + vertices + "3 0 1 2\n3 0 1 3\n")).face_count() == 2);
  }
  SECTION("a binary PLY body shorter than its header (a huge count would be allocated first)") {
    const auto binary = [](long long vertices) {
      std::string text = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(vertices) +
                         "\nproperty float x\nproperty float y\nproperty float z\nelement face 1\n"
                         "property list uchar int vertex_indices\nend_header\n";
      const float corners[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
      const int face[3] = {0, 1, 2};
      text.append(reinterpret_cast<const char*>(corners), sizeof corners);
      text.push_back(3);
      text.append(reinterpret_cast<const char*>(face), sizeof face);
      return text;
    };
    CHECK(load_mesh(write_file(dir / "ok.ply", binary(3))).face_count() == 1);
    require_load_error(write_file(dir / "huge_binary.ply", binary(2000000000)), "truncated");
    require_load_error(write_file(dir / "long_binary.ply", binary(4)), "byte offset");  // the face read as a vertex
  }
  SECTION("a coordinate of many integer digits reads as its double (assimp's readers read 0)") {
    const std::string big = "100000000000000000000";
    CHECK(load_mesh(write_file(dir / "big.obj", "v " + big + " 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")).vertices(0, 0) == 1e20);
    CHECK(load_mesh(write_file(dir / "big.off", "OFF\n3 1 0\n" + big + " 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")).vertices(0, 0) == 1e20);
    CHECK(load_mesh(write_file(dir / "big.ply", ply_header(3, 1) + big + " 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")).vertices(0, 0) == 1e20);
  }
  SECTION("no faces") { require_load_error(write_file(dir / "points.obj", "v 0 0 0\nv 1 0 0\n"), ""); }
  SECTION("only degenerate faces") {
    require_load_error(write_file(dir / "flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n"), "degenerate");
  }
  SECTION("not a mesh") { require_load_error(write_file(dir / "junk.xyz", "garbage\x01\x02"), "cannot be read"); }
  SECTION("an OFF file with comment lines loads (the reader alone lost the faces after one)") {
    const TriangleMesh mesh =
        load_mesh(write_file(dir / "comments.off", "OFF\n# c\n3 1 0\n# c\n0 0 0\n1 0 0 # end\n0 1 0\n# c\n3 0 1 2\n"));
    CHECK(mesh.face_count() == 1);
    CHECK(mesh.vertices(1, 0) == 1.0);
  }
  SECTION("text that the ASE reader would turn into a mesh at the origin") {
    require_load_error(write_file(dir / "hello.ase", "hello world\n"), "not an ASE file");
  }
  SECTION("a PLY vertex without x, y or z (the reader would put it at the origin)") {
    const std::string header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float a\nproperty float y\n"
                               "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
    require_load_error(write_file(dir / "noxyz.ply", header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"), "no 'x' property");
  }
}

TEST_CASE("files cut at any point load or fail cleanly, never crash", "[mesh][io][errors]") {
  TempDir dir;
  const TriangleMesh mesh = clothcd::make_uv_sphere(1.0, 8, 5);
  for (const std::string extension : {".ply", ".obj"}) {
    const auto whole = dir / ("whole" + extension);
    save_mesh(mesh, whole);
    std::ifstream in(whole, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (int cut = 1; cut < 40; ++cut) {
      const auto path = write_file(dir / ("cut" + std::to_string(cut) + extension), bytes.substr(0, bytes.size() * cut / 40));
      INFO(path);
      try {
        const TriangleMesh loaded = load_mesh(path);
        CHECK_NOTHROW(clothcd::validate_mesh(loaded, path.string()));
        CHECK(loaded.face_count() <= mesh.face_count());
      } catch (const MeshError& e) {
        CHECK(std::string(e.what()).find(path.string()) != std::string::npos);
      }
    }
  }
}

TEST_CASE("saving rejects unknown formats and unwritable paths", "[mesh][io][errors]") {
  TempDir dir;
  const TriangleMesh mesh = clothcd::make_box();
  CHECK_THROWS_AS(save_mesh(mesh, dir / "box.stl"), MeshError);
  CHECK_THROWS_AS(save_mesh(mesh, dir / "no-such-folder" / "box.obj"), MeshError);
  TriangleMesh bad_index = mesh;
  bad_index.faces(0, 2) = 99;
  CHECK_THROWS_WITH(save_mesh(bad_index, dir / "bad.obj"), Catch::Contains("face index"));
  TriangleMesh nan = mesh;
  nan.vertices(1, 1) = std::nan("");
  CHECK_THROWS_WITH(save_mesh(nan, dir / "nan.ply"), Catch::Contains("NaN"));
  CHECK_FALSE(std::filesystem::exists(dir / "bad.obj"));
}

TEST_CASE("validate_mesh rejects NaN, bad indices and empty meshes", "[mesh][validation]") {
  TriangleMesh mesh = clothcd::make_box();
  CHECK_NOTHROW(clothcd::validate_mesh(mesh, "box"));
  TriangleMesh nan_mesh = mesh;
  nan_mesh.vertices(3, 1) = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH(clothcd::validate_mesh(nan_mesh, "box"), Catch::Contains("vertex 3"));
  TriangleMesh bad_index = mesh;
  bad_index.faces(5, 2) = -1;
  CHECK_THROWS_WITH(clothcd::validate_mesh(bad_index, "box"), Catch::Contains("face 5"));
  TriangleMesh empty;
  CHECK_THROWS_WITH(clothcd::validate_mesh(empty, "empty"), Catch::Contains("no faces"));
  CHECK_THROWS_AS(clothcd::is_degenerate_face(bad_index, 5), std::out_of_range);
  CHECK_THROWS_AS(clothcd::is_degenerate_face(mesh, mesh.face_count()), std::out_of_range);
  CHECK_THROWS_AS(clothcd::drop_degenerate_faces(bad_index), std::out_of_range);
}
