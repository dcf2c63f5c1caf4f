#pragma once
/// @file
/// Reader of the public CCD benchmark's query files (Wang et al. 2021, "A Large-Scale Benchmark and an Inclusion-Based
/// Algorithm for Continuous Collision Detection"): CSV, 8 rows per query (the four points at t = 0, then at t = 1, in
/// CcdQuery's order), each row "x_num,x_den,y_num,y_den,z_num,z_den[,truth]" with arbitrary-size integers and an
/// optional 0/1 ground truth.

#include <array>
#include <cstddef>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "clothcd/ccd/ccd.hpp"

namespace clothcd::ccd {

/// Thrown for unreadable or malformed query files; what() is "<file>:<line>: <problem>" (or "<file>: <problem>").
class QueryFileError : public std::runtime_error {
 public:
  /// Where a problem is: a file and a 1-based line (0 = no line).
  struct Place {
    const std::string& file;  ///< The file.
    std::size_t line;         ///< The line, or 0.
  };

  /// Builds the message from the file, the 1-based line (0 = no line) and the problem.
  QueryFileError(const std::string& file, std::size_t line, const std::string& problem)
      : std::runtime_error(file + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " + problem) {}

  /// Builds the message from the place and the problem.
  QueryFileError(const Place& place, const std::string& problem) : QueryFileError(place.file, place.line, problem) {}
};

/// One coordinate as read: decimal integer strings as in the file (a leading '+' dropped; not reduced), the
/// denominator non-zero.
using RationalText = std::array<std::string, 2>;

/// One query as read from a file.
struct QueryRecord {
  CcdQuery query;  ///< Coordinates rounded to the nearest double.
  /// The exact coordinates: rational[i][d] for point i (0..7, start points then end points) and axis d.
  std::array<std::array<RationalText, 3>, 8> rational;
  bool exactly_representable = true;  ///< True when every coordinate equals its double exactly.
  int truth = -1;                     ///< Ground truth: 1 colliding, 0 not, -1 absent.
  std::string file;                   ///< File the query came from.
  std::size_t line = 0;               ///< 1-based line of its first row.
};

/// The pair kind named by a `vertex-face` or `edge-edge` folder in path (the nearest one wins), if any.
[[nodiscard]] std::optional<PairKind> pair_kind_from_path(const std::string& path);

/// Reads one query file a query at a time, so that memory does not grow with the file (the public benchmark's
/// simulation sets hold files of millions of queries). Checks as read_query_file.
/// Threads: one reader belongs to one thread at a time (reading advances it); separate readers may run in parallel.
class QueryFileReader {
 public:
  /// Opens `path`. kind: the pair kind, or nullopt to take it from the path. Throws QueryFileError when the file
  /// cannot be opened or the kind is unknown.
  explicit QueryFileReader(const std::string& path, std::optional<PairKind> kind = {});

  /// Reads the next query into `record` (its storage is reused); false at the end of the file. Throws QueryFileError
  /// on malformed input, including a file that ends inside a query.
  bool next(QueryRecord& record);

 private:
  std::string path_;
  PairKind kind_ = PairKind::VertexFace;
  std::ifstream in_;
  std::string line_;
  std::size_t line_number_ = 0;
  std::size_t rows_ = 0;
};

/// Longest integer (decimal digits) a query file may hold. A double's exact fraction needs at most 324 digits; the
/// exact arithmetic on a query with 5,000-digit coordinates took 11 s, with 20,000-digit ones minutes.
inline constexpr std::size_t kMaxIntegerDigits = 1024;

/// Reads one CSV file. kind: the pair kind, or nullopt to take it from the path (QueryFileError when it cannot).
/// Throws QueryFileError on unreadable files, wrong column counts, non-integers, integers longer than
/// kMaxIntegerDigits, zero denominators, a ground truth other than 0/1 or differing within a query, and a row count
/// not divisible by 8.
[[nodiscard]] std::vector<QueryRecord> read_query_file(const std::string& path, std::optional<PairKind> kind = {});

/// The query files at `path`: the path itself when it is a file, else every *.csv file under the folder (recursively,
/// in sorted path order). Throws QueryFileError when the path does not exist or the folder holds no .csv file.
[[nodiscard]] std::vector<std::string> query_files(const std::string& path);

/// Reads a CSV file, or every *.csv file under a folder (query_files); kind as above.
[[nodiscard]] std::vector<QueryRecord> read_queries(const std::string& path, std::optional<PairKind> kind = {});

}  // namespace clothcd::ccd
