// The benchmark CSV reader: exact big-integer rationals, kind from the folder, and clear errors naming file and line.
#include <catch2/catch.hpp>
#include <gmpxx.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "clothcd/ccd/query_file.hpp"
#include "support/test_support.hpp"

using clothcd::PairKind;
using clothcd::test::TempDir;
using clothcd::test::write_file;
namespace ccd = clothcd::ccd;

namespace {

// One vertex-face query: the vertex drops through the unit triangle (colliding, truth 1).
const char* const kQuery =
    "1,4,1,4,1,1,1\n0,1,0,1,0,1,1\n1,1,0,1,0,1,1\n0,1,1,1,0,1,1\n"
    "1,4,1,4,-1,1,1\n0,1,0,1,0,1,1\n1,1,0,1,0,1,1\n0,1,1,1,0,1,1\n";

std::string error_of(const std::string& path) {
  try {
    (void)ccd::read_queries(path);
  } catch (const ccd::QueryFileError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST_CASE("reads rationals, ground truth and the pair kind from the folder", "[ccd][query-file]") {
  TempDir dir;
  std::filesystem::create_directories(dir / "scene/vertex-face");
  const auto file = write_file(dir / "scene/vertex-face/q.csv", kQuery);
  const auto records = ccd::read_queries(dir.path().string());
  REQUIRE(records.size() == 1);
  const ccd::QueryRecord& record = records[0];
  CHECK(record.query.kind == PairKind::VertexFace);
  CHECK(record.truth == 1);
  CHECK(record.line == 1);
  CHECK(record.exactly_representable);
  CHECK(record.query.start[0] == Eigen::Vector3d(0.25, 0.25, 1));
  CHECK(record.query.end[0] == Eigen::Vector3d(0.25, 0.25, -1));
  CHECK(record.rational[4][2] == ccd::RationalText{"-1", "1"});
  CHECK(ccd::exact_collision_reference(record.query.kind, record.rational));
  CHECK(ccd::continuous_collision(record.query).hit);
}

TEST_CASE("big integers become exact rationals and the nearest double", "[ccd][query-file]") {
  TempDir dir;
  // 2^100 / 2^102 = 1/4 exactly; 1/3 is not a double (rounded to nearest, flagged inexact).
  std::string text = "1267650600228229401496703205376,5070602400912917605986812821504,1,3,0,1\n";
  for (int i = 1; i < 8; ++i) text += "0,1,0,1,0,1\n";
  const auto records = ccd::read_query_file(write_file(dir / "q.csv", text).string(), PairKind::EdgeEdge);
  REQUIRE(records.size() == 1);
  CHECK(records[0].query.start[0].x() == 0.25);
  CHECK(records[0].query.start[0].y() == 1.0 / 3.0);
  CHECK_FALSE(records[0].exactly_representable);
  CHECK(records[0].truth == -1);
}

TEST_CASE("every coordinate is the nearest double of its rational, whichever way it is read", "[ccd][query-file]") {
  // Small dyadic rationals take the 64-bit path, the rest GMP: the values, texts and exactness flags must not depend
  // on which. Numerators and denominators of up to 22 digits, signs on either, powers of two and odd denominators.
  std::mt19937_64 random(2026);
  const std::vector<std::string> denominators{"1", "2", "-8", "1024", "4611686018427387904", "9223372036854775808",
                                              "3", "-7", "1000", "36028797018963968", "+64"};
  auto numerator = [&]() -> std::string {
    switch (random() % 5) {
      case 0: return std::to_string(static_cast<std::int64_t>(random() >> 11) - (std::int64_t{1} << 52));
      case 1: return std::to_string(static_cast<std::int64_t>(random() >> 10));  // up to 2^54: beyond 53 bits
      case 2: return "-" + std::to_string(random() >> 1);                         // up to 63 bits
      case 3: return "+" + std::to_string(random() % 1000);
      default: return std::to_string(random()) + std::to_string(random() % 1000);  // beyond 64 bits
    }
  };
  // One query per drawn coordinate, at a random place among zeros, so that the query's exactness flag is its own.
  TempDir dir;
  std::string text;
  std::vector<std::array<std::string, 2>> written;
  std::vector<int> place;
  for (int query = 0; query < 600; ++query) {
    written.push_back({numerator(), denominators[random() % denominators.size()]});
    place.push_back(static_cast<int>(random() % 24));
    for (int c = 0; c < 24; ++c) {
      text += c == place.back() ? written.back()[0] + "," + written.back()[1] : std::string("0,1");
      text += c % 3 == 2 ? "\n" : ",";
    }
  }
  const auto records = ccd::read_query_file(write_file(dir / "q.csv", text).string(), PairKind::VertexFace);
  REQUIRE(records.size() == written.size());
  for (std::size_t k = 0; k < records.size(); ++k) {
    const ccd::QueryRecord& record = records[k];
    const auto& [n, m] = written[k];
    const int i = place[k] / 3, d = place[k] % 3;
    INFO(n << " / " << m);
    mpq_class q{mpz_class{n[0] == '+' ? n.substr(1) : n}, mpz_class{m[0] == '+' ? m.substr(1) : m}};
    q.canonicalize();
    const double value = i < 4 ? record.query.start[i][d] : record.query.end[i - 4][d];
    const mpq_class error = abs(mpq_class(value) - q);
    CHECK(error <= abs(mpq_class(std::nextafter(value, HUGE_VAL)) - q));
    CHECK(error <= abs(mpq_class(std::nextafter(value, -HUGE_VAL)) - q));
    CHECK(record.exactly_representable == (error == 0));
    const ccd::RationalText& t = record.rational[i][d];
    mpq_class read{mpz_class{t[0]}, mpz_class{t[1]}};
    read.canonicalize();
    CHECK(read == q);
  }
}

TEST_CASE("malformed query files are errors naming the file and line", "[ccd][query-file][errors]") {
  TempDir dir;
  std::filesystem::create_directories(dir / "edge-edge");
  const auto path = [&](const char* name) { return (dir / "edge-edge" / name).string(); };
  write_file(path("columns.csv"), "1,1,1,1,1\n");
  CHECK_THAT(error_of(path("columns.csv")), Catch::Contains("columns.csv:1:") && Catch::Contains("found 5 columns"));
  write_file(path("zero.csv"), std::string(kQuery).replace(0, 3, "1,0"));
  CHECK_THAT(error_of(path("zero.csv")), Catch::Contains("zero.csv:1:") && Catch::Contains("zero denominator"));
  write_file(path("text.csv"), "1,1,x,1,1,1\n");
  CHECK_THAT(error_of(path("text.csv")), Catch::Contains("text.csv:1:") && Catch::Contains("not an integer"));
  write_file(path("float.csv"), "1,1,1.5,1,1,1\n");
  CHECK_THAT(error_of(path("float.csv")), Catch::Contains("not an integer"));
  write_file(path("rows.csv"), std::string(kQuery) + "1,1,1,1,1,1,1\n");
  CHECK_THAT(error_of(path("rows.csv")), Catch::Contains("rows.csv") && Catch::Contains("not a multiple of 8"));
  write_file(path("truth.csv"), std::string(kQuery).replace(12, 1, "2"));
  CHECK_THAT(error_of(path("truth.csv")), Catch::Contains("truth.csv:1:") && Catch::Contains("0 or 1"));
  write_file(path("range.csv"), std::string(kQuery).replace(0, 1, "1" + std::string(400, '0')));
  CHECK_THAT(error_of(path("range.csv")), Catch::Contains("range.csv:1:") && Catch::Contains("beyond the range"));
  // Integers beyond kMaxIntegerDigits (the exact arithmetic on them would take minutes); the limit itself is fine.
  const std::string longest(ccd::kMaxIntegerDigits, '7');
  write_file(path("long.csv"), std::string(kQuery).replace(2, 1, "-" + longest));
  CHECK_THAT(error_of(path("long.csv")), Catch::Contains("no error"));
  write_file(path("longer.csv"), std::string(kQuery).replace(2, 1, longest + "7"));
  CHECK_THAT(error_of(path("longer.csv")), Catch::Contains("longer.csv:1:") && Catch::Contains("1025 digits"));
  CHECK_THAT(error_of((dir / "missing.csv").string()), Catch::Contains("no such file"));
  // No --type and no vertex-face/edge-edge folder: the kind is unknown.
  write_file(dir / "plain.csv", kQuery);
  CHECK_THAT(error_of((dir / "plain.csv").string()), Catch::Contains("pair type unknown"));
}

TEST_CASE("the reader returns one query at a time and reuses the record", "[ccd][query-file]") {
  TempDir dir;
  // A query with a long big-integer coordinate, then one with short ones: nothing of the first may remain.
  std::string text = "1267650600228229401496703205376,5070602400912917605986812821504,1,3,0,1,0\n";
  for (int i = 1; i < 8; ++i) text += "0,1,0,1,0,1,0\n";
  text += "\n";  // blank lines are skipped
  text += kQuery;
  const std::string path = write_file(dir / "q.csv", text).string();
  ccd::QueryFileReader reader(path, PairKind::EdgeEdge);
  ccd::QueryRecord record;
  REQUIRE(reader.next(record));
  CHECK(record.line == 1);
  CHECK(record.truth == 0);
  CHECK_FALSE(record.exactly_representable);
  CHECK(record.rational[0][0] == ccd::RationalText{"1267650600228229401496703205376", "5070602400912917605986812821504"});
  REQUIRE(reader.next(record));
  CHECK(record.line == 10);
  CHECK(record.truth == 1);
  CHECK(record.exactly_representable);
  CHECK(record.query.kind == PairKind::EdgeEdge);
  CHECK(record.rational[0][0] == ccd::RationalText{"1", "4"});
  CHECK(record.query.start[0] == Eigen::Vector3d(0.25, 0.25, 1));
  CHECK(record.query.end[0] == Eigen::Vector3d(0.25, 0.25, -1));
  CHECK(record.file == path);
  CHECK_FALSE(reader.next(record));
  CHECK_FALSE(reader.next(record));
}

TEST_CASE("the reader returns the complete queries before a file that ends inside one", "[ccd][query-file][errors]") {
  TempDir dir;
  const std::string path = write_file(dir / "q.csv", std::string(kQuery) + "1,1,1,1,1,1,1\n0,1,0,1,0,1,1\n").string();
  ccd::QueryFileReader reader(path, PairKind::VertexFace);
  ccd::QueryRecord record;
  REQUIRE(reader.next(record));
  CHECK(record.truth == 1);
  CHECK_THROWS_WITH(reader.next(record), Catch::Contains("q.csv") && Catch::Contains("10 rows is not a multiple of 8"));
}
