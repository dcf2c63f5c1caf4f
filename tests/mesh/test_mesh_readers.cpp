// The own OBJ, PLY, OFF and STL readers: every variant of each format, exact doubles, exact round trips through the
// writers, and one clear error (file and line or byte offset) for every kind of malformed file.
#include <array>
#include <catch2/catch.hpp>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <tuple>

#include "clothcd/mesh/mesh_error.hpp"
#include "clothcd/mesh/mesh_frames.hpp"
#include "clothcd/mesh/mesh_generators.hpp"
#include "clothcd/mesh/mesh_io.hpp"
#include "support/test_support.hpp"

using clothcd::load_mesh;
using clothcd::MeshError;
using clothcd::TriangleMesh;
using clothcd::test::TempDir;
using clothcd::test::write_file;

namespace {

clothcd::LoadOptions keep_all() {
  clothcd::LoadOptions options;
  options.join_identical_vertices = false;
  options.drop_degenerate_faces = false;
  return options;
}

/// True when both matrices hold the same bits (so -0 differs from +0 and the test sees any rounding).
bool same_bits(const clothcd::Vertices& a, const clothcd::Vertices& b) {
  return a.rows() == b.rows() &&
         std::memcmp(a.data(), b.data(), static_cast<std::size_t>(a.size()) * sizeof(double)) == 0;
}

/// The MeshError message load_mesh throws for `path` (fails the test when it loads).
std::string load_error(const std::filesystem::path& path) {
  try {
    (void)load_mesh(path, keep_all());
  } catch (const MeshError& e) {
    const std::string message = e.what();
    CHECK(message.find(path.string()) != std::string::npos);
    return message;
  }
  FAIL("expected an error for " << path);
  return {};
}

/// The shortest decimal that reads back as `value`.
std::string shortest_text(double value) {
  std::array<char, 32> digits;
  return std::string(digits.data(), std::to_chars(digits.data(), digits.data() + digits.size(), value).ptr);
}

/// A value of `type` in a PLY body: text (with a trailing space) or bytes in the given order.
void put(std::string& out, const std::string& type, double value, const std::string& format) {
  if (format == "ascii") {
    out += shortest_text(value) + ' ';
    return;
  }
  std::uint64_t bits = 0;
  int size = 0;
  if (type == "char" || type == "int8" || type == "uchar" || type == "uint8") {
    size = 1, bits = static_cast<std::uint8_t>(static_cast<int>(value));
  } else if (type == "short" || type == "int16" || type == "ushort" || type == "uint16") {
    size = 2, bits = static_cast<std::uint16_t>(static_cast<int>(value));
  } else if (type == "int" || type == "int32" || type == "uint" || type == "uint32") {
    size = 4, bits = static_cast<std::uint32_t>(static_cast<long long>(value));
  } else if (type == "float" || type == "float32") {
    const float single = static_cast<float>(value);
    std::uint32_t word = 0;
    std::memcpy(&word, &single, 4);
    size = 4, bits = word;
  } else {
    size = 8, std::memcpy(&bits, &value, 8);
  }
  for (int i = 0; i < size; ++i) {
    const int shift = 8 * (format == "binary_big_endian" ? size - 1 - i : i);
    out += static_cast<char>((bits >> shift) & 0xff);
  }
}

/// Ends a row of a PLY body (a line end in ASCII).
void end_row(std::string& out, const std::string& format) {
  if (format == "ascii") out.back() = '\n';
}

/// A PLY file of a square (a quad and a triangle over 5 vertices) with x, y, z of `type`, extra properties around
/// them, a list in the vertex element, a face list of the given count and index types between other face properties,
/// and other elements (with lists) before, between and after.
std::string square_ply(const std::string& format, const std::string& type, const std::string& count_type,
                       const std::string& index_type) {
  std::string out = "ply\nformat " + format + " 1.0\ncomment test\nobj_info none\n";
  out += "element camera 2\nproperty float view\nproperty list uchar int mask\n";
  out += "element vertex 5\nproperty float nx\nproperty " + type + " y\nproperty uchar red\nproperty " + type +
         " x\nproperty list ushort double weights\nproperty " + type + " z\n";
  out += "element edge 1\nproperty int vertex1\nproperty int vertex2\n";
  out += "element face 2\nproperty int flags\nproperty list " + count_type + " " + index_type +
         " vertex_indices\nproperty list uchar float texcoord\n";
  out += "element material 1\nproperty list uint8 uint8 name\nend_header\n";
  for (int camera = 0; camera < 2; ++camera) {
    put(out, "float", 0.5, format), put(out, "uchar", 2, format), put(out, "int", 7, format), put(out, "int", -7, format);
    end_row(out, format);
  }
  const double positions[5][3] = {{0, 0, 1}, {2, 0, 1}, {2, 2, 1}, {0, 2, 1}, {1, 1, 2}};
  for (const auto& p : positions) {
    put(out, "float", 9, format), put(out, type, p[1], format), put(out, "uchar", 255, format), put(out, type, p[0], format);
    put(out, "ushort", 2, format), put(out, "double", 0.25, format), put(out, "double", -3, format);
    put(out, type, p[2], format);
    end_row(out, format);
  }
  put(out, "int", 0, format), put(out, "int", 1, format);
  end_row(out, format);
  put(out, "int", 3, format), put(out, count_type, 4, format);
  for (const int index : {0, 1, 2, 3}) put(out, index_type, index, format);
  put(out, "uchar", 0, format);
  end_row(out, format);
  put(out, "int", 3, format), put(out, count_type, 3, format);
  for (const int index : {4, 0, 1}) put(out, index_type, index, format);
  put(out, "uchar", 2, format), put(out, "float", 0.5, format), put(out, "float", 0.5, format);
  end_row(out, format);
  put(out, "uint8", 1, format), put(out, "uint8", 65, format);
  end_row(out, format);
  return out;
}

/// Random doubles of every kind: any exponent, subnormals, signed zeros, values no float holds.
clothcd::Vertices random_doubles(int rows, std::uint32_t seed) {
  std::mt19937_64 random(seed);
  clothcd::Vertices vertices(rows, 3);
  for (Eigen::Index i = 0; i < vertices.size(); ++i) {
    double value = 0.0;
    do {
      const std::uint64_t bits = random();
      std::memcpy(&value, &bits, sizeof value);
      switch (i % 4) {
        case 0: break;                                                                     // any bits
        case 1: value = std::ldexp(static_cast<double>(bits >> 11) / 0x1p53, -1074 + static_cast<int>(bits % 52)); break;  // subnormal
        case 2: value = 0.1 * static_cast<double>(static_cast<std::int64_t>(bits) >> 30); break;  // not a float
        case 3: value = (bits & 1) ? -0.0 : std::nextafter(1.0, 2.0); break;
      }
    } while (!std::isfinite(value));
    vertices.data()[i] = value;
  }
  return vertices;
}

}  // namespace

TEST_CASE("writers and readers round-trip random doubles bit for bit", "[mesh][readers]") {
  TempDir dir;
  TriangleMesh mesh;
  mesh.vertices = random_doubles(300, 23);
  mesh.faces.resize(100, 3);
  for (int f = 0; f < 100; ++f) mesh.faces.row(f) << 3 * f, 3 * f + 1, 3 * f + 2;
  REQUIRE(mesh.vertices.cwiseAbs().minCoeff() == 0.0);
  const std::pair<std::string, clothcd::PlyEncoding> cases[] = {{"a.obj", clothcd::PlyEncoding::ascii},
                                                                 {"a.ply", clothcd::PlyEncoding::ascii},
                                                                 {"b.ply", clothcd::PlyEncoding::binary_little_endian}};
  for (const auto& [name, encoding] : cases) {
    INFO(name);
    clothcd::save_mesh(mesh, dir / name, encoding);
    const TriangleMesh loaded = load_mesh(dir / name, keep_all());
    CHECK(same_bits(loaded.vertices, mesh.vertices));
    CHECK(loaded.faces == mesh.faces);
  }
}

TEST_CASE("PLY: every encoding, scalar type, list type, extra properties and elements", "[mesh][readers][ply]") {
  TempDir dir;
  const auto format = GENERATE(as<std::string>{}, "ascii", "binary_little_endian", "binary_big_endian");
  const auto type = GENERATE(as<std::string>{}, "char", "uchar", "short", "ushort", "int", "uint", "float", "double",
                             "int8", "uint8", "int16", "uint16", "int32", "uint32", "float32", "float64");
  const auto lists = GENERATE(as<std::pair<std::string, std::string>>{}, std::make_pair("uchar", "int"),
                              std::make_pair("uint8", "uint32"), std::make_pair("int", "ushort"),
                              std::make_pair("ushort", "char"), std::make_pair("uint", "int16"));
  INFO(format << " " << type << " list " << lists.first << " " << lists.second);
  const auto path = write_file(dir / "square.ply", square_ply(format, type, lists.first, lists.second));
  const TriangleMesh mesh = load_mesh(path, keep_all());
  REQUIRE(mesh.vertex_count() == 5);
  CHECK(mesh.vertices.row(2) == Eigen::RowVector3d(2, 2, 1));
  CHECK(mesh.vertices.row(4) == Eigen::RowVector3d(1, 1, 2));
  REQUIRE(mesh.face_count() == 3);  // the quad as a fan of two, then the triangle
  CHECK(mesh.faces.row(0) == Eigen::RowVector3i(0, 1, 2));
  CHECK(mesh.faces.row(1) == Eigen::RowVector3i(0, 2, 3));
  CHECK(mesh.faces.row(2) == Eigen::RowVector3i(4, 0, 1));
}

TEST_CASE("OBJ: corner forms, negative numbers, polygons, comments and ignored lines", "[mesh][readers][obj]") {
  TempDir dir;
  const auto path = write_file(dir / "forms.OBJ",
                               "# comment\nmtllib a.mtl\no thing\ng group\nusemtl red\ns off\n"
                               "v 0 0 0\nv 1 0 0 1.0\nv 1 1 0 0.5 0.5 0.5\nvt 0 0\nvn 0 0 1\n"
                               "f 1/1/1 2/1/1 3/1/1 # a comment after a face\n"
                               "v\t0\t1\t0\r\nf -4//1 -2//1 -1//1\r\nf 1/1 3/1 4/1\nl 1 2\np 1\nf 5 1 2\n"
                               "v 0.1 0.2 0.30000000000000004\nf 1 2 3 4\n");
  const TriangleMesh mesh = load_mesh(path, keep_all());
  REQUIRE(mesh.vertex_count() == 5);
  CHECK(mesh.vertices(4, 2) == 0.30000000000000004);
  CHECK(mesh.vertices(4, 0) == 0.1);
  REQUIRE(mesh.face_count() == 6);
  CHECK(mesh.faces.row(1) == Eigen::RowVector3i(0, 2, 3));  // -4, -2, -1 with four vertices so far
  CHECK(mesh.faces.row(3) == Eigen::RowVector3i(4, 0, 1));  // a vertex defined further down
  CHECK(mesh.faces.row(5) == Eigen::RowVector3i(0, 2, 3));  // fan of the quad
}

TEST_CASE("OFF: counts with and without edges, on the header line, comments, colours", "[mesh][readers][off]") {
  TempDir dir;
  const std::string body = "0 0 0\n1 0 0\n1 1 0\n0 1 0.1000000000000000055511151231257827\n4 0 1 2 3\n";
  for (const std::string head : {"OFF\n4 1 0\n", "OFF\n4 1\n", "OFF 4 1 6\n", "# c\nOFF # c\n\n# c\n 4  1  0 # c\n"}) {
    INFO(head);
    const TriangleMesh mesh = load_mesh(write_file(dir / "a.off", head + body), keep_all());
    CHECK(mesh.face_count() == 2);
    CHECK(mesh.vertices(3, 2) == 0.1);
  }
  const TriangleMesh coloured =
      load_mesh(write_file(dir / "c.off", "COFF\n3 1 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n0 1 0 0 0 255 255\n"
                                          "3 0 1 2 0.5 0.5 0.5\n"),
                keep_all());
  CHECK(coloured.face_count() == 1);
  CHECK(coloured.vertices(1, 0) == 1.0);
}

TEST_CASE("STL: ASCII and binary, corners joined by position", "[mesh][readers][stl]") {
  TempDir dir;
  const std::string ascii =
      "solid square\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n   vertex 1 1 0.1\n"
      "  endloop\n endfacet\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 1 0.1\n   vertex 0 1 0\n"
      "  endloop\n endfacet\nendsolid square\n";
  std::string binary = "solid but binary" + std::string(64, ' ');
  const auto put_float = [&binary](float value) { binary.append(reinterpret_cast<const char*>(&value), 4); };
  binary.append("\x02\0\0\0", 4);
  const float corners[2][9] = {{0, 0, 0, 1, 0, 0, 1, 1, 0.1f}, {0, 0, 0, 1, 1, 0.1f, 0, 1, 0}};
  for (const auto& triangle : corners) {
    for (int i = 0; i < 3; ++i) put_float(0.0f);
    for (const float value : triangle) put_float(value);
    binary.append("\0\0", 2);
  }
  for (const auto& [name, text, z] : {std::make_tuple("a.stl", ascii, 0.1), std::make_tuple("b.STL", binary, double(0.1f))}) {
    INFO(name);
    const auto path = write_file(dir / name, text);
    const TriangleMesh soup = load_mesh(path, keep_all());
    CHECK(soup.vertex_count() == 6);
    CHECK(soup.vertices(2, 2) == z);
    clothcd::LoadReport report;
    const TriangleMesh joined = load_mesh(path, {}, &report);
    CHECK(joined.vertex_count() == 4);
    CHECK(report.vertices_joined == 2);
    CHECK(joined.face_count() == 2);
  }
}

TEST_CASE("load_mesh_frames keeps the file's numbering and doubles", "[mesh][readers][frames]") {
  TempDir dir;
  TriangleMesh start = clothcd::make_uv_sphere(1.0, 7, 5);
  start.vertices.row(3) = start.vertices.row(4);  // two vertices at one position stay two
  TriangleMesh end = start;
  end.vertices = start.vertices.array() + 1e-13;
  for (const std::string extension : {".obj", ".ply"}) {
    clothcd::save_mesh(start, dir / ("t0" + extension));
    clothcd::save_mesh(end, dir / ("t1" + extension), clothcd::PlyEncoding::binary_little_endian);
    const clothcd::MeshFrames frames = clothcd::load_mesh_frames(dir / ("t0" + extension), dir / ("t1" + extension));
    CHECK(same_bits(frames.start.vertices, start.vertices));
    CHECK(same_bits(frames.end, end.vertices));
    CHECK(frames.start.faces == start.faces);
  }
}

TEST_CASE("malformed files: one clear error naming the file and the place", "[mesh][readers][errors]") {
  TempDir dir;
  const std::string ply_head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
                               "property double z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const std::string vertices = "0 0 0\n1 0 0\n0 1 0\n";
  const auto error = [&dir](const std::string& name, const std::string& contents) {
    return load_error(write_file(dir / name, contents));
  };
  SECTION("indices equal to the vertex count, INT_MAX, negative") {
    for (const std::string index : {"3", "2147483647", "-1", "4294967296"}) {
      INFO(index);
      CHECK_THAT(error("i.ply", ply_head + vertices + "3 0 1 " + index + "\n"),
                 Catch::Contains("line 13") && Catch::Contains("out of range"));
      CHECK_THAT(error("i.off", "OFF\n3 1\n" + vertices + "3 0 " + index + " 1\n"),
                 Catch::Contains("line 6") && Catch::Contains("out of range"));
    }
    for (const std::string number : {"4", "2147483648", "-4", "0"}) {
      CHECK_THAT(error("i.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 " + number + "\n"),
                 Catch::Contains("line 4") && Catch::Contains("out of range"));
    }
    for (const std::uint32_t index : {3u, 2147483647u, 4294967295u}) {
      std::string binary = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                           "property float z\nelement face 1\nproperty list uchar uint vertex_indices\nend_header\n";
      const std::size_t body = binary.size();
      binary += std::string(36, '\0') + '\x03' + std::string(8, '\0');
      binary.append(reinterpret_cast<const char*>(&index), 4);
      CHECK_THAT(error("i.ply", binary), Catch::Contains("byte offset " + std::to_string(body + 45)) &&
                                             Catch::Contains("out of range"));
    }
  }
  SECTION("faces of fewer than three corners") {
    CHECK_THAT(error("c.ply", ply_head + vertices + "2 0 1\n"), Catch::Contains("needs 3"));
    CHECK_THAT(error("c.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n"), Catch::Contains("line 3") && Catch::Contains("needs 3"));
    CHECK_THAT(error("c.off", "OFF\n3 1\n" + vertices + "0\n"), Catch::Contains("needs 3"));
    CHECK_THAT(error("c.stl", "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\n"
                              "endfacet\nendsolid s\n"),
               Catch::Contains("line 6") && Catch::Contains("needs 3"));
  }
  SECTION("NaN and infinite coordinates") {
    for (const std::string bad : {"nan", "-inf", "infinity", "1e999"}) {
      INFO(bad);
      CHECK_THAT(error("n.ply", ply_head + "0 0 0\n1 " + bad + " 0\n0 1 0\n3 0 1 2\n"),
                 Catch::Contains("line 11") && Catch::Contains("non-finite"));
      CHECK_THAT(error("n.obj", "v 0 0 0\nv 1 0 " + bad + "\nv 0 1 0\nf 1 2 3\n"),
                 Catch::Contains("line 2") && Catch::Contains("non-finite"));
      CHECK_THAT(error("n.off", "OFF\n3 1\n0 0 0\n" + bad + " 0 0\n0 1 0\n3 0 1 2\n"), Catch::Contains("non-finite"));
      CHECK_THAT(error("n.stl", "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 " + bad +
                                    " 0\nendloop\nendfacet\nendsolid s\n"),
                 Catch::Contains("line 6") && Catch::Contains("non-finite"));
    }
  }
  SECTION("NaN and infinity in binary bodies, named by byte offset") {
    std::string ply = "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
                      "property double z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
    const std::size_t body = ply.size();
    ply += std::string(32, '\0') + "\x7f\xf8" + std::string(6, '\0') + std::string(32, '\0');  // y of vertex 1: NaN
    ply += std::string("\x03", 1) + std::string(3, '\0') + std::string("\0\0\0\x01\0\0\0\x02", 8);
    CHECK_THAT(error("nan.ply", ply), Catch::Contains("byte offset " + std::to_string(body + 32)) &&
                                          Catch::Contains("non-finite"));
    std::string stl(80, ' ');
    stl += std::string("\x01\0\0\0", 4) + std::string(12 + 20, '\0') + std::string("\0\0\x80\x7f", 4) +
           std::string(12 + 2, '\0');
    CHECK_THAT(error("inf.stl", stl), Catch::Contains("byte offset 116") && Catch::Contains("non-finite"));
    CHECK_THAT(error("long.stl", stl + "xy"), Catch::Contains("byte offset 80") && Catch::Contains("trailing bytes"));
  }
  SECTION("counts far beyond the file's size are refused before anything is allocated") {
    CHECK_THAT(error("h.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 2147483648\nproperty double x\n"
                              "property double y\nproperty double z\nend_header\n" + std::string(24, '\0')),
               Catch::Contains("truncated"));
    CHECK_THAT(error("h2.ply", "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                               "property float z\nelement face 2147483647\nproperty list uchar int vertex_indices\n"
                               "end_header\n" + std::string(40, '\0')),
               Catch::Contains("line 7") && Catch::Contains("truncated"));
    CHECK_THAT(error("h.off", "OFF\n2147483648 1\n0 0 0\n"), Catch::Contains("truncated"));
    std::string stl(84, '\0');
    stl[83] = '\x7f';  // about 2^31 triangles
    CHECK_THAT(error("h.stl", stl), Catch::Contains("byte offset 80") && Catch::Contains("truncated"));
  }
  SECTION("trailing bytes after a binary body") {
    std::string binary = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                         "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
    const std::size_t body = binary.size();
    const float corners[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const int face[3] = {0, 1, 2};
    binary.append(reinterpret_cast<const char*>(corners), sizeof corners);
    binary += '\x03';
    binary.append(reinterpret_cast<const char*>(face), sizeof face);
    CHECK(load_mesh(write_file(dir / "ok.ply", binary)).face_count() == 1);
    CHECK_THAT(error("t.ply", binary + "xy"), Catch::Contains("byte offset " + std::to_string(body + 49)) &&
                                                  Catch::Contains("2 bytes after the last PLY element"));
    CHECK_THAT(error("t.ply", ply_head + vertices + "3 0 1 2\n3 0 1 2\n"), Catch::Contains("line 14"));
    CHECK_THAT(error("t.off", "OFF\n3 1\n" + vertices + "3 0 1 2\nmore\n"), Catch::Contains("line 7"));
  }
  SECTION("the PLY headers that crashed or hung assimp") {
    CHECK_THAT(error("s.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
                              "property float y\nproperty float z\nend_header\x01\x02\n" + std::string(36, '\0')),
               Catch::Contains("line 7") && Catch::Contains("malformed PLY header"));
    CHECK_THAT(error("h.ply", "\nply\nformat ascii 1.0\nelement"), Catch::Contains("not a PLY file"));
    CHECK_THAT(error("h.ply", "ply\nformat ascii 1.0\nelement"), Catch::Contains("line 3"));
    CHECK_THAT(error("h.ply", "ply\nformat ascii 1.0\nelement vertex 3\n"), Catch::Contains("no end_header"));
  }
  SECTION("text where numbers belong") {
    CHECK_THAT(error("x.obj", "v 0 0 0\nv 1 zero 0\nv 0 1 0\nf 1 2 3\n"), Catch::Contains("line 2"));
    CHECK_THAT(error("x.ply", ply_head + vertices + "3 0 one 2\n"), Catch::Contains("line 13"));
    CHECK_THAT(error("x.stl", "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0\n"), Catch::Contains("line 5"));
    CHECK_THAT(error("x.stl", "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n"), Catch::Contains("truncated"));
    CHECK_THAT(error("x.off", "OFF\n3 1\n" + vertices + "3 0 1 2.5\n"), Catch::Contains("line 6"));
  }
  SECTION("the four formats are never handed to assimp (a double no float holds comes back exactly)") {
    const double exact = 0.1;
    CHECK(load_mesh(write_file(dir / "d.obj", "v 0.1 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")).vertices(0, 0) == exact);
    CHECK(load_mesh(write_file(dir / "d.ply", ply_head + "0.1 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")).vertices(0, 0) == exact);
    CHECK(load_mesh(write_file(dir / "d.off", "OFF\n3 1\n0.1 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")).vertices(0, 0) == exact);
    CHECK(load_mesh(write_file(dir / "d.stl", "solid\nfacet normal 0 0 1\nouter loop\nvertex 0.1 0 0\nvertex 1 0 0\n"
                                              "vertex 0 1 0\nendloop\nendfacet\nendsolid\n"))
              .vertices(0, 0) == exact);
  }
}

TEST_CASE("every prefix of a file of each format loads or fails with a MeshError", "[mesh][readers][errors]") {
  TempDir dir;
  const TriangleMesh mesh = clothcd::make_uv_sphere(1.0, 5, 4);
  std::vector<std::pair<std::string, std::string>> files;
  for (const auto& [name, encoding] : {std::make_pair("a.obj", clothcd::PlyEncoding::ascii),
                                       std::make_pair("a.ply", clothcd::PlyEncoding::ascii),
                                       std::make_pair("b.ply", clothcd::PlyEncoding::binary_little_endian)}) {
    clothcd::save_mesh(mesh, dir / name, encoding);
    files.emplace_back(name, clothcd::test::read_file(dir / name));
  }
  files.emplace_back("c.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n4 0 2 3 1\n");
  files.emplace_back("d.ply", square_ply("binary_big_endian", "double", "uchar", "int"));
  files.emplace_back("e.stl", "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
                              "endloop\nendfacet\nendsolid s\n");
  std::string binary_stl(80, 'x');
  binary_stl += std::string("\x01\0\0\0", 4) + std::string(12, '\0');
  for (const float value : {0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f})
    binary_stl.append(reinterpret_cast<const char*>(&value), 4);
  files.emplace_back("f.stl", binary_stl + std::string(2, '\0'));
  for (const auto& [name, bytes] : files) {
    for (std::size_t cut = 1; cut < bytes.size(); cut += 1 + cut % 7) {  // every byte near the start, then a stride
      const auto path = write_file(dir / ("cut-" + name), bytes.substr(0, cut));
      INFO(name << " cut at " << cut);
      try {
        const TriangleMesh loaded = load_mesh(path, keep_all());
        CHECK(loaded.face_count() >= 1);
      } catch (const MeshError& e) {
        CHECK(std::string(e.what()).find(path.string()) != std::string::npos);
      }
    }
  }
}
