// `clothcd proximity` and `clothcd intersections`: one mesh in, the detector's state-query answers out (checked
// against the library on the same mesh), and clear errors on bad input.
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "clothcd/detection/collision_detector.hpp"
#include "clothcd/mesh/mesh_generators.hpp"
#include "clothcd/mesh/mesh_io.hpp"

namespace fs = std::filesystem;

namespace {

int run(const std::string& arguments, const fs::path& log) {
  const std::string command = std::string(CLOTHCD_CLI_PATH) + " " + arguments + " > " + log.string() + " 2>&1";
  return std::system(command.c_str());
}

nlohmann::json read_json(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

std::string read(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Two 5 x 5 sheets in one mesh: a flat one and a tilted one 0.01 above it at x = -0.02, which crosses it there; the
// flat sheet's vertices are crumpled slightly so that pairs come at many distances.
clothcd::TriangleMesh crossing_sheets() {
  const clothcd::TriangleMesh sheet = clothcd::make_grid(5, 5, 0.4, 0.4);
  clothcd::TriangleMesh mesh;
  mesh.vertices.resize(2 * sheet.vertex_count(), 3);
  clothcd::Vertices tilted = sheet.vertices;
  tilted.col(1) = 0.5 * sheet.vertices.col(0).array() + 0.01;
  mesh.vertices << sheet.vertices, tilted;
  for (Eigen::Index v = 0; v < sheet.vertex_count(); ++v) mesh.vertices(v, 1) = 0.003 * std::sin(7.0 * v);
  mesh.faces.resize(2 * sheet.face_count(), 3);
  mesh.faces << sheet.faces, (sheet.faces.array() + static_cast<int>(sheet.vertex_count())).matrix();
  return mesh;
}

struct Scene {
  fs::path dir;
  fs::path mesh;
  clothcd::TriangleMesh geometry = crossing_sheets();

  explicit Scene(const std::string& name) : dir(fs::temp_directory_path() / name), mesh(dir / "sheets.ply") {
    fs::create_directories(dir);
    clothcd::save_mesh(geometry, mesh);
  }
  ~Scene() { fs::remove_all(dir); }
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;

  clothcd::CollisionDetector detector() const {
    return clothcd::CollisionDetector(geometry.faces, static_cast<int>(geometry.vertex_count()));
  }
};

}  // namespace

TEST_CASE("clothcd proximity reports the library's pairs within the distance", "[detection][cli][state]") {
  const Scene scene("clothcd_proximity_cli_test");
  const fs::path json = scene.dir / "out.json";
  REQUIRE(run("proximity " + scene.mesh.string() + " --distance 0.05 --contacts --out " + json.string(),
              scene.dir / "log.txt") == 0);
  CHECK_THAT(read(scene.dir / "log.txt"), Catch::Contains("vertex-face") && Catch::Contains("traversal"));
  const nlohmann::json out = read_json(json);
  clothcd::CollisionDetector detector = scene.detector();
  const std::vector<clothcd::Proximity> pairs = detector.proximity(scene.geometry.vertices, 0.05);
  REQUIRE(pairs.size() > 10);
  CHECK(out["command"] == "proximity");
  CHECK(out["distance"] == 0.05);
  REQUIRE(out["vertex_face"].size() + out["edge_edge"].size() == pairs.size());
  std::size_t vf = 0, ee = 0;
  for (const clothcd::Proximity& p : pairs) {
    const nlohmann::json& item =
        p.kind == clothcd::PairKind::VertexFace ? out["vertex_face"][vf++] : out["edge_edge"][ee++];
    CHECK(item["distance"].get<double>() == p.distance);
    if (p.kind == clothcd::PairKind::VertexFace) {
      CHECK(item["pair"][0] == p.vertices[0].vertex);
      const int face = item["pair"][1];
      for (int k = 0; k < 3; ++k) CHECK(scene.geometry.faces(face, k) == p.vertices[1 + k].vertex);
    } else {
      CHECK(item["pair"][1][0] == p.vertices[2].vertex);
    }
  }
  CHECK(out["counts"]["vertex_face"] == vf);
  CHECK(out["counts"]["contacts"] == clothcd::closest_feature_contacts(pairs).size());
  CHECK(out["contacts"].size() == out["counts"]["contacts"]);

  REQUIRE(run("proximity " + scene.mesh.string() + " --minimum --json", scene.dir / "min.json") == 0);
  const nlohmann::json minimum = read_json(scene.dir / "min.json");
  const clothcd::MinimumDistance m = detector.minimum_distance(scene.geometry.vertices);
  CHECK(minimum["minimum"]["found"] == true);
  CHECK(minimum["minimum"]["distance"].get<double>() == m.distance);
  CHECK(minimum["minimum"]["pair"]["distance"].get<double>() == m.distance);
  CHECK(minimum["distance"].is_null());
}

TEST_CASE("clothcd intersections reports the library's intersecting face pairs", "[detection][cli][state]") {
  const Scene scene("clothcd_intersections_cli_test");
  REQUIRE(run("intersections " + scene.mesh.string() + " --json", scene.dir / "out.json") == 0);
  const nlohmann::json out = read_json(scene.dir / "out.json");
  clothcd::CollisionDetector detector = scene.detector();
  const std::vector<clothcd::FaceIntersection> pairs = detector.intersections(scene.geometry.vertices);
  REQUIRE(!pairs.empty());
  CHECK(out["intersection_free"] == false);
  CHECK(out["counts"]["intersections"] == pairs.size());
  REQUIRE(out["intersections"].size() == pairs.size());
  const int sheet_faces = static_cast<int>(scene.geometry.face_count() / 2);
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    CHECK(out["intersections"][i]["faces"] == nlohmann::json::array({pairs[i].faces[0], pairs[i].faces[1]}));
    CHECK(out["intersections"][i]["edge_parameter"].get<double>() == pairs[i].edge_parameter);
    CHECK(pairs[i].faces[0] < sheet_faces);  // the flat sheet against the tilted one
    CHECK(pairs[i].faces[1] >= sheet_faces);
  }

  REQUIRE(run("intersections " + scene.mesh.string() + " --free", scene.dir / "log.txt") == 0);
  CHECK_THAT(read(scene.dir / "log.txt"), Catch::Contains("intersection-free: no"));
  clothcd::save_mesh(clothcd::make_grid(5, 5, 0.4, 0.4), scene.dir / "flat.obj");
  REQUIRE(run("intersections " + (scene.dir / "flat.obj").string() + " --free --json", scene.dir / "flat.json") == 0);
  CHECK(read_json(scene.dir / "flat.json")["intersection_free"] == true);
}

TEST_CASE("clothcd proximity and intersections refuse bad input", "[detection][cli][state]") {
  const Scene scene("clothcd_state_cli_errors_test");
  const std::string mesh = scene.mesh.string();
  const fs::path log = scene.dir / "log.txt";
  for (const std::string distance : {"0", "-1", "nan", "inf"}) {
    INFO("distance " << distance);
    CHECK(run("proximity " + mesh + " --distance " + distance, log) != 0);
    CHECK_THAT(read(log), Catch::Contains("clothcd: error:") && Catch::Contains("--distance"));
  }
  CHECK(run("proximity " + mesh, log) != 0);
  CHECK_THAT(read(log), Catch::Contains("--distance is required"));
  CHECK(run("proximity " + mesh + " --distance 0.1 --max-collisions 1", log) != 0);
  CHECK_THAT(read(log), Catch::Contains("clothcd: error:"));
  CHECK(run("intersections " + mesh + " --max-collisions 1", log) != 0);
  CHECK(run("intersections " + (scene.dir / "missing.obj").string(), log) != 0);
  CHECK_THAT(read(log), Catch::Contains("missing.obj"));
  std::ofstream(scene.dir / "nan.obj") << "v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n";
  CHECK(run("proximity " + (scene.dir / "nan.obj").string() + " --distance 0.1", log) != 0);
  CHECK_THAT(read(log), Catch::Contains("clothcd: error:"));
}
