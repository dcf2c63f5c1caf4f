// Detection on meshes read at the file's full double precision: collisions that coordinates rounded to float would
// miss (or invent) are decided on the file's doubles, and every ground-truth pair of the shared simulation steps is
// found, in every culling mode, when that data is present.
#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <cstdlib>
#include <cstring>
#include <set>

#include "clothcd/culling/network_culler.hpp"
#include "clothcd/detection/collision_detector.hpp"
#include "clothcd/mesh/mesh_frames.hpp"
#include "clothcd/mesh/mesh_io.hpp"
#include "support/test_support.hpp"

namespace {

namespace fs = std::filesystem;
using clothcd::MeshFrames;
using clothcd::PairKind;

/// The collisions clothcd's detector finds between the frames (interval-undecided pairs decided exactly).
std::vector<clothcd::Collision> detect_exactly(const clothcd::TriangleMesh& start, const clothcd::Vertices& end,
                                               clothcd::CullingMode culling = clothcd::CullingMode::Filters) {
  clothcd::DetectorSettings settings;
  settings.decide_exactly = true;
  settings.culling = culling;
  clothcd::learning::attach_network_culler(settings, "");
  clothcd::CollisionDetector detector(start.faces, static_cast<int>(start.vertex_count()), settings);
  return detector.detect(start.vertices, end);
}

/// `positions` rounded to float, as assimp stored them.
clothcd::Vertices rounded_to_float(const clothcd::Vertices& positions) {
  return positions.cast<float>().cast<double>();
}

/// True when a vertex-face collision of `vertex` against the triangle of face `face` is among `collisions`.
bool has_vertex_face(const std::vector<clothcd::Collision>& collisions, const clothcd::Faces& faces, int vertex, int face) {
  return std::any_of(collisions.begin(), collisions.end(), [&](const clothcd::Collision& c) {
    return c.kind == PairKind::VertexFace && c.vertices[0].vertex == vertex && c.vertices[1].vertex == faces(face, 0) &&
           c.vertices[2].vertex == faces(face, 1) && c.vertices[3].vertex == faces(face, 2);
  });
}

/// The shared data folder: $CLOTHCD_SHARED_DATA, else ../shared/data beside the source tree.
fs::path shared_data() {
  if (const char* dir = std::getenv("CLOTHCD_SHARED_DATA")) return dir;
  return fs::path(CLOTHCD_TEST_DATA_DIR).parent_path().parent_path().parent_path() / "shared" / "data";
}

}  // namespace

TEST_CASE("the rod-twist vertex-face collision that float coordinates miss is found", "[mesh][readers][detection]") {
  // Vertex 12290 and face 65321 of the shared rod-twist step (with one face around the vertex), copied exactly.
  const fs::path data = fs::path(CLOTHCD_TEST_DATA_DIR) / "mesh";
  const MeshFrames frames = clothcd::load_mesh_frames(data / "rod-twist-pair-t0.ply", data / "rod-twist-pair-t1.ply");
  CHECK(has_vertex_face(detect_exactly(frames.start, frames.end), frames.start.faces, 4, 0));
  clothcd::TriangleMesh rounded = frames.start;
  rounded.vertices = rounded_to_float(frames.start.vertices);
  CHECK_FALSE(has_vertex_face(detect_exactly(rounded, rounded_to_float(frames.end)), frames.start.faces, 4, 0));

  const auto run = clothcd::test::run_cli("detect '" + (data / "rod-twist-pair-t0.ply").string() + "' '" +
                                          (data / "rod-twist-pair-t1.ply").string() + "'");
  CHECK(run.exit_code == 0);
  CHECK_THAT(run.output, Catch::Contains("collisions:  1 vertex-face"));
}

TEST_CASE("a vertex 1e-11 outside a triangle's edge does not collide with it", "[mesh][readers][detection]") {
  // A triangle at rest in z = 0 and a small triangle falling through that plane next to the first one's long edge
  // (x + y = 1): its corner (0.5 + 1e-11, 0.5) passes outside by about 7e-12. Rounded to float, it lands on the edge.
  clothcd::TriangleMesh start;
  start.vertices.resize(6, 3);
  start.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.5 + 1e-11, 0.5, 1, 1.5, 0.5, 1, 0.5, 1.5, 1;
  start.faces.resize(2, 3);
  start.faces << 0, 1, 2, 3, 4, 5;
  clothcd::TriangleMesh end = start;
  end.vertices.col(2).tail(3).setConstant(-1.0);
  clothcd::test::TempDir dir;
  clothcd::save_mesh(start, dir / "t0.ply");
  clothcd::save_mesh(end, dir / "t1.ply", clothcd::PlyEncoding::binary_little_endian);

  const MeshFrames frames = clothcd::load_mesh_frames(dir / "t0.ply", dir / "t1.ply");
  CHECK(frames.start.vertices(3, 0) == 0.5 + 1e-11);
  CHECK(detect_exactly(frames.start, frames.end).empty());
  clothcd::TriangleMesh rounded = frames.start;
  rounded.vertices = rounded_to_float(frames.start.vertices);
  CHECK(has_vertex_face(detect_exactly(rounded, rounded_to_float(frames.end)), frames.start.faces, 3, 0));

  const auto run = clothcd::test::run_cli("detect '" + (dir / "t0.ply").string() + "' '" +
                                          (dir / "t1.ply").string() + "'");
  CHECK(run.exit_code == 0);
  CHECK_THAT(run.output, Catch::Contains("collisions:  0 vertex-face, 0 edge-edge"));
}

TEST_CASE("every ground-truth pair of the shared simulation steps is found", "[mesh][readers][detection][shared]") {
  const fs::path root = shared_data() / "scalable-ccd-sample";
  for (const std::string scene : {"rod-twist", "cloth-funnel"}) {
    if (!fs::exists(root / scene / "truth.json")) {
      WARN("skipped: no " << (root / scene).string());
      continue;
    }
    INFO(scene);
    const MeshFrames frames = clothcd::load_mesh_frames(root / scene / "t0.ply", root / scene / "t1.ply");
    const auto truth = nlohmann::json::parse(clothcd::test::read_file(root / scene / "truth.json"));
    REQUIRE(truth["vertices"].get<double>() == frames.start.vertex_count());
    // The frames are binary little-endian PLY whose vertex element (x, y, z as double) comes first.
    for (const auto& [name, positions] : {std::make_pair("t0.ply", &frames.start.vertices), std::make_pair("t1.ply", &frames.end)}) {
      const std::string bytes = clothcd::test::read_file(root / scene / name);
      const std::size_t body = bytes.find("end_header\n") + 11;
      REQUIRE(bytes.size() >= body + positions->size() * sizeof(double));
      CHECK(std::memcmp(bytes.data() + body, positions->data(), positions->size() * sizeof(double)) == 0);
    }
    using clothcd::CullingMode;
    for (const CullingMode culling : {CullingMode::None, CullingMode::NonPenetration, CullingMode::Projection,
                                      CullingMode::Filters, CullingMode::Network}) {
      INFO("culling mode " << static_cast<int>(culling));
      std::set<std::array<int, 4>> found;  // vertex-face: vertex, sorted triangle; edge-edge: sorted sorted edges
      for (const clothcd::Collision& c : detect_exactly(frames.start, frames.end, culling)) {
        std::array<int, 4> key{c.vertices[0].vertex, c.vertices[1].vertex, c.vertices[2].vertex, c.vertices[3].vertex};
        if (c.kind == PairKind::VertexFace) {
          std::sort(key.begin() + 1, key.end());
        } else {
          if (key[0] > key[1]) std::swap(key[0], key[1]);
          if (key[2] > key[3]) std::swap(key[2], key[3]);
          if (std::make_pair(key[2], key[3]) < std::make_pair(key[0], key[1])) key = {key[2], key[3], key[0], key[1]};
          key[0] = -1 - key[0];  // edge-edge keys apart from vertex-face ones
        }
        found.insert(key);
      }
      int missed = 0;
      for (const auto& pair : truth["vf"]) {
        const int vertex = pair[0].get<int>(), face = pair[1].get<int>();
        std::array<int, 4> key{vertex, frames.start.faces(face, 0), frames.start.faces(face, 1),
                               frames.start.faces(face, 2)};
        std::sort(key.begin() + 1, key.end());
        missed += found.count(key) == 0;
      }
      for (const auto& pair : truth["ee"]) {
        std::array<int, 4> key{};
        for (int k = 0; k < 4; ++k) key[k] = pair[k / 2][k % 2].get<int>();
        if (std::make_pair(key[2], key[3]) < std::make_pair(key[0], key[1])) key = {key[2], key[3], key[0], key[1]};
        key[0] = -1 - key[0];
        missed += found.count(key) == 0;
      }
      CHECK(missed == 0);
    }
    CHECK(truth["vf"].size() + truth["ee"].size() > 100);
  }
}
