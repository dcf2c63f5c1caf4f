// `clothcd detect`: two frames of one mesh in, collisions and stage counts out; mismatched frames are a clear error.
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "clothcd/mesh/mesh_generators.hpp"
#include "clothcd/mesh/mesh_io.hpp"

namespace fs = std::filesystem;

namespace {

int run(const std::string& arguments, const fs::path& log) {
  const std::string command = std::string(CLOTHCD_CLI_PATH) + " " + arguments + " > " + log.string() + " 2>&1";
  return std::system(command.c_str());
}

std::string read(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// One mesh holding a still 2 x 2 plate (y = 0, its vertices first) and a 0.5 x 0.5 cloth of kClothVertices
// vertices 0.1 above it (its vertices last).
constexpr Eigen::Index kClothVertices = 16;
clothcd::TriangleMesh plate_and_cloth() {
  const clothcd::TriangleMesh plate = clothcd::make_grid(3, 3, 2.0, 2.0);
  const clothcd::TriangleMesh cloth = clothcd::make_grid(4, 4, 0.5, 0.5);
  clothcd::TriangleMesh mesh;
  mesh.vertices.resize(plate.vertex_count() + cloth.vertex_count(), 3);
  mesh.vertices << plate.vertices, cloth.vertices;
  mesh.vertices.bottomRows(kClothVertices).col(1).array() += 0.1;
  mesh.faces.resize(plate.face_count() + cloth.face_count(), 3);
  mesh.faces << plate.faces, (cloth.faces.array() + static_cast<int>(plate.vertex_count())).matrix();
  return mesh;
}

}  // namespace

TEST_CASE("clothcd detect reports a cloth falling through a plate", "[detection][cli]") {
  const fs::path dir = fs::temp_directory_path() / "clothcd_detect_cli_test";
  fs::create_directories(dir);
  // One mesh holding a still plate (y = 0) and a small cloth above it that falls through it during the step.
  const clothcd::TriangleMesh t0 = plate_and_cloth();
  clothcd::TriangleMesh t1 = t0;
  t1.vertices.bottomRows(kClothVertices).col(1).array() -= 0.2;
  clothcd::save_mesh(t0, dir / "t0.obj");
  clothcd::save_mesh(t1, dir / "t1.obj");

  const fs::path json = dir / "out.json";
  for (const std::string approximate : {"", " --approximate"}) {
    INFO("options:" << approximate);
    REQUIRE(run("detect " + (dir / "t0.obj").string() + " " + (dir / "t1.obj").string() + " --bvh aabb --out " +
                    json.string() + approximate,
                dir / "log.txt") == 0);
    const std::string out = read(json);
    // Each of the 16 cloth vertices crosses the plate at t = 0.5 (some exactly through a plate vertex or edge, which
    // are conservative hits with --approximate): every toi is a lower bound of that, and a tight one.
    CHECK(out.find("\"vertex_face\": [") != std::string::npos);
    int tois = 0;
    for (std::size_t at = out.find("\"toi\": "); at != std::string::npos; at = out.find("\"toi\": ", at + 1)) {
      const double toi = std::stod(out.substr(at + 7));
      CHECK(toi <= 0.5);
      CHECK(toi > 0.5 - 1e-6);
      ++tois;
    }
    CHECK(tois >= 16);
    CHECK(out.find("\"vertex_face\": 0") == std::string::npos);
    CHECK((out.find("\"exact\": true") != std::string::npos) == approximate.empty());
    if (approximate.empty()) CHECK(out.find("\"conservative\": true") == std::string::npos);
  }

  // A frame with one face fewer does not describe the same mesh.
  clothcd::TriangleMesh other = t1;
  other.faces.conservativeResize(other.faces.rows() - 1, 3);
  clothcd::save_mesh(other, dir / "bad.obj");
  CHECK(run("detect " + (dir / "t0.obj").string() + " " + (dir / "bad.obj").string(), dir / "log.txt") != 0);
  CHECK(read(dir / "log.txt").find("clothcd: error:") != std::string::npos);
  CHECK(run("detect " + (dir / "t0.obj").string() + " " + (dir / "t1.obj").string() + " --bvh octree",
            dir / "log.txt") != 0);
  fs::remove_all(dir);
}

TEST_CASE("clothcd detect names each copy of a face listed twice", "[detection][cli]") {
  const fs::path dir = fs::temp_directory_path() / "clothcd_detect_cli_duplicate_test";
  fs::create_directories(dir);
  // Faces 0 and 1 are the same triangle; vertex 3 falls through it during the step.
  const std::string faces = "f 1 2 3\nf 1 2 3\nf 4 4 4\n";
  std::ofstream(dir / "t0.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0.2 0.2 0.5\n" << faces;
  std::ofstream(dir / "t1.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0.2 0.2 -0.5\n" << faces;
  const fs::path json = dir / "out.json";
  REQUIRE(run("detect " + (dir / "t0.obj").string() + " " + (dir / "t1.obj").string() + " --out " + json.string(),
              dir / "log.txt") == 0);
  const nlohmann::json out = nlohmann::json::parse(read(json));
  REQUIRE(out["vertex_face"].size() == 2);
  CHECK(out["vertex_face"][0]["pair"] == nlohmann::json::array({3, 0}));
  CHECK(out["vertex_face"][1]["pair"] == nlohmann::json::array({3, 1}));
  CHECK(out["counts"]["vertex_face"] == 2);
  for (const nlohmann::json& c : out["vertex_face"]) {
    CHECK(c["bodies"] == nlohmann::json::array({0, 0, 0, 0}));
    CHECK(c["face_vertices"] == nlohmann::json::array({0, 1, 2}));
    // The vertex (0.2, 0.2) crosses the triangle (0,0), (1,0), (0,1) at barycentric weights 0.6, 0.2, 0.2.
    CHECK(c["barycentric"][0].get<double>() == Approx(0.6));
    CHECK(c["barycentric"][1].get<double>() == Approx(0.2));
    CHECK(c["barycentric"][2].get<double>() == Approx(0.2));
    CHECK(std::abs(c["normal"][2].get<double>()) == Approx(1.0));
  }
  fs::remove_all(dir);
}

TEST_CASE("clothcd detect refuses OBJ frames whose faces differ and output it cannot write", "[detection][cli]") {
  const fs::path dir = fs::temp_directory_path() / "clothcd_detect_cli_frames_test";
  fs::create_directories(dir);
  // The OBJ reader gives one vertex per face corner, so faces that name other vertices (here the second triangle's
  // winding reversed) looked like the same mesh with moved vertices and gave made-up collisions.
  const std::string vertices = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n";
  std::ofstream(dir / "t0.obj") << vertices << "f 1 2 3\nf 2 4 3\n";
  std::ofstream(dir / "reversed.obj") << vertices << "f 1 2 3\nf 3 4 2\n";
  std::ofstream(dir / "relative.obj") << vertices << "f -4 -3 -2\nf -3 -1 -2\n";  // the same faces, counted back
  CHECK(run("detect " + (dir / "t0.obj").string() + " " + (dir / "reversed.obj").string(), dir / "log.txt") != 0);
  CHECK_THAT(read(dir / "log.txt"), Catch::Contains("faces differ"));
  CHECK(run("detect " + (dir / "t0.obj").string() + " " + (dir / "relative.obj").string(), dir / "log.txt") == 0);
  CHECK_THAT(read(dir / "log.txt"), Catch::Contains("collisions:  0 vertex-face, 0 edge-edge"));
  if (fs::exists("/dev/full")) {  // every write to it fails (Linux)
    CHECK(run("detect " + (dir / "t0.obj").string() + " " + (dir / "t0.obj").string() + " --out /dev/full",
              dir / "log.txt") != 0);
    CHECK_THAT(read(dir / "log.txt"), Catch::Contains("write failed"));
  }
  fs::remove_all(dir);
}

TEST_CASE("clothcd detect --earliest reports the step's earliest time of impact", "[detection][cli][earliest]") {
  const fs::path dir = fs::temp_directory_path() / "clothcd_detect_earliest_cli_test";
  fs::create_directories(dir);
  // A still plate (y = 0) and a cloth 0.1 above it falling by `drop`: through the plate at t = 0.1 / drop when
  // drop > 0.1, no contact otherwise.
  const clothcd::TriangleMesh t0 = plate_and_cloth();
  clothcd::save_mesh(t0, dir / "t0.obj");
  const std::string frames = (dir / "t0.obj").string() + " " + (dir / "t1.obj").string();
  for (const double drop : {0.4, 0.05}) {
    INFO("drop " << drop);
    clothcd::TriangleMesh t1 = t0;
    t1.vertices.bottomRows(kClothVertices).col(1).array() -= drop;
    clothcd::save_mesh(t1, dir / "t1.obj");
    REQUIRE(run("detect " + frames + " --earliest --json", dir / "out.json") == 0);
    const nlohmann::json report = nlohmann::json::parse(read(dir / "out.json"));
    const nlohmann::json& earliest = report.at("earliest");
    const bool contact = drop > 0.1;
    CHECK(earliest.at("hit") == contact);
    CHECK(report.at("counts").count("vertex_face") == 0);
    const double toi = earliest.at("toi");
    if (contact) {
      CHECK(toi <= 0.25);
      CHECK(toi >= 0.25 - 1e-6);
      CHECK(earliest.at("windows") >= 2);  // the first window, at most 1/16 of the step, holds no contact
      CHECK(earliest.at("pair").at("toi") == toi);
    } else {
      CHECK(toi == 1.0);
      CHECK(earliest.at("windows") >= 2);
      CHECK(earliest.at("pair").is_null());
    }
    REQUIRE(run("detect " + frames + " --earliest", dir / "log.txt") == 0);
    CHECK(read(dir / "log.txt").find(contact ? "earliest:    toi 0.2499" : "earliest:    toi 1 (no contact") !=
          std::string::npos);
  }
  fs::remove_all(dir);
}
