// Reader of the CCD benchmark's rational CSV query files (Wang et al. 2021). Most coordinates are doubles written as
// n / 2^k with |n| < 2^53: those are read with 64-bit integers and converted exactly. The others (integers beyond 64
// bits, other denominators) are parsed with GMP and rounded to the nearest double by comparing the neighbours of GMP's
// truncated value.
#include "clothcd/ccd/query_file.hpp"

#include <gmpxx.h>

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

namespace clothcd::ccd {

namespace {

namespace fs = std::filesystem;

std::string trim(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return {};
  const auto last = text.find_last_not_of(" \t\r");
  return text.substr(first, last - first + 1);
}

std::vector<std::string> split_columns(const std::string& line) {
  std::vector<std::string> columns;
  std::size_t begin = 0;
  for (;;) {
    const std::size_t comma = line.find(',', begin);
    columns.push_back(trim(line.substr(begin, comma == std::string::npos ? std::string::npos : comma - begin)));
    if (comma == std::string::npos) return columns;
    begin = comma + 1;
  }
}

bool is_integer(const std::string& text) {
  const std::size_t digits_start = !text.empty() && (text[0] == '-' || text[0] == '+') ? 1 : 0;
  if (text.size() <= digits_start) return false;
  return std::all_of(text.begin() + static_cast<std::ptrdiff_t>(digits_start), text.end(),
                     [](char c) { return c >= '0' && c <= '9'; });
}

mpz_class parse_integer(const std::string& text) {
  return mpz_class(text[0] == '+' ? text.substr(1) : text, 10);
}

double nearest_double(const mpq_class& q) {
  const double truncated = q.get_d();
  double best = truncated;
  mpq_class best_error = abs(mpq_class(truncated) - q);
  for (double candidate : {std::nextafter(truncated, -std::numeric_limits<double>::infinity()),
                           std::nextafter(truncated, std::numeric_limits<double>::infinity())}) {
    if (!std::isfinite(candidate)) continue;
    const mpq_class error = abs(mpq_class(candidate) - q);
    if (error < best_error) {
      best = candidate;
      best_error = error;
    }
  }
  return best;
}

// The integer in `text` (checked by is_integer) if it fits in 62 bits.
std::optional<std::int64_t> small_integer(const std::string& text) {
  const char* begin = text.data() + (text[0] == '+' ? 1 : 0);
  const char* end = text.data() + text.size();
  std::int64_t value = 0;
  const auto [rest, error] = std::from_chars(begin, end, value);
  if (error != std::errc() || rest != end || value > (std::int64_t{1} << 62) || value < -(std::int64_t{1} << 62))
    return std::nullopt;
  return value;
}

// numerator / denominator as a double when that is exact without GMP: |numerator| <= 2^53 and the denominator a
// (signed) power of two up to 2^62, so the quotient is the numerator scaled by a power of two.
std::optional<double> exact_dyadic(std::int64_t numerator, std::int64_t denominator) {
  const std::uint64_t magnitude = static_cast<std::uint64_t>(denominator < 0 ? -denominator : denominator);
  const std::uint64_t top = std::uint64_t{1} << 53;
  const std::uint64_t size = static_cast<std::uint64_t>(numerator < 0 ? -numerator : numerator);
  if (magnitude == 0 || (magnitude & (magnitude - 1)) != 0 || size > top) return std::nullopt;
  int shift = 0;
  while ((std::uint64_t{1} << shift) != magnitude) ++shift;
  const double value = std::ldexp(static_cast<double>(numerator), -shift);
  return denominator < 0 ? -value : value;
}

struct Row {
  std::array<RationalText, 3> text;
  Eigen::Vector3d value;
  bool exact = true;
  int truth = -1;
  std::size_t line = 0;
};

Row parse_row(const std::string& file, std::size_t line_number, const std::string& line) {
  const std::vector<std::string> columns = split_columns(line);
  if (columns.size() != 6 && columns.size() != 7)
    throw QueryFileError(
        file, line_number,
        "expected 6 or 7 comma-separated integers, found " + std::to_string(columns.size()) + " columns");
  for (std::size_t c = 0; c < columns.size(); ++c)
    if (!is_integer(columns[c]))
      throw QueryFileError(file, line_number,
                           "column " + std::to_string(c + 1) + " is not an integer: '" + columns[c] + "'");
  Row row;
  row.line = line_number;
  for (int d = 0; d < 3; ++d) {
    const std::optional<std::int64_t> small_numerator = small_integer(columns[2 * d]);
    const std::optional<std::int64_t> small_denominator = small_integer(columns[2 * d + 1]);
    if (small_numerator && small_denominator) {
      if (const std::optional<double> value = exact_dyadic(*small_numerator, *small_denominator)) {
        row.text[d] = {std::to_string(*small_numerator), std::to_string(*small_denominator)};
        row.value[d] = *value;
        continue;
      }
    }
    const mpz_class numerator = parse_integer(columns[2 * d]);
    const mpz_class denominator = parse_integer(columns[2 * d + 1]);
    if (denominator == 0)
      throw QueryFileError(file, line_number, "zero denominator in column " + std::to_string(2 * d + 2));
    mpq_class q(numerator, denominator);
    q.canonicalize();
    if (abs(q) > mpq_class(std::numeric_limits<double>::max()))
      throw QueryFileError(file, line_number,
                           "the coordinate in columns " + std::to_string(2 * d + 1) + "-" + std::to_string(2 * d + 2) +
                               " is beyond the range of doubles (magnitude above 1.8e308)");
    row.text[d] = {numerator.get_str(), denominator.get_str()};
    row.value[d] = nearest_double(q);
    row.exact = row.exact && mpq_class(row.value[d]) == q;
  }
  if (columns.size() == 7) {
    if (columns[6] != "0" && columns[6] != "1")
      throw QueryFileError(file, line_number, "ground truth (column 7) must be 0 or 1, got '" + columns[6] + "'");
    row.truth = columns[6] == "1" ? 1 : 0;
  }
  return row;
}

QueryRecord make_record(const std::string& file, PairKind kind, const std::vector<Row>& rows, std::size_t first) {
  QueryRecord record;
  record.query.kind = kind;
  record.file = file;
  record.line = rows[first].line;
  record.truth = rows[first].truth;
  for (std::size_t i = 0; i < 8; ++i) {
    const Row& row = rows[first + i];
    if (row.truth != record.truth)
      throw QueryFileError(
          file, row.line, "ground truth differs from the query's first row (line " + std::to_string(record.line) + ")");
    record.rational[i] = row.text;
    record.exactly_representable = record.exactly_representable && row.exact;
    (i < 4 ? record.query.start[i] : record.query.end[i - 4]) = row.value;
  }
  return record;
}

}  // namespace

std::optional<PairKind> pair_kind_from_path(const std::string& path) {
  const fs::path p(path);
  std::optional<PairKind> kind;
  for (const fs::path& part : p) {
    if (part == "vertex-face") kind = PairKind::VertexFace;
    if (part == "edge-edge") kind = PairKind::EdgeEdge;
  }
  return kind;
}

std::vector<QueryRecord> read_query_file(const std::string& path, std::optional<PairKind> kind) {
  if (!kind) kind = pair_kind_from_path(path);
  if (!kind)
    throw QueryFileError(path, 0,
                         "pair type unknown: pass --type vf|ee or put the file under a vertex-face or edge-edge "
                         "folder");
  std::ifstream in(path);
  if (!in) throw QueryFileError(path, 0, "cannot open file");
  std::vector<Row> rows;
  std::string line;
  for (std::size_t line_number = 1; std::getline(in, line); ++line_number) {
    if (trim(line).empty()) continue;
    rows.push_back(parse_row(path, line_number, line));
  }
  if (rows.size() % 8 != 0)
    throw QueryFileError(path, 0, std::to_string(rows.size()) + " rows is not a multiple of 8 (8 rows per query)");
  std::vector<QueryRecord> records;
  records.reserve(rows.size() / 8);
  for (std::size_t first = 0; first < rows.size(); first += 8) records.push_back(make_record(path, *kind, rows, first));
  return records;
}

std::vector<std::string> query_files(const std::string& path) {
  std::error_code error;
  if (!fs::exists(path, error)) throw QueryFileError(path, 0, "no such file or folder");
  if (!fs::is_directory(path, error)) return {path};
  std::vector<std::string> files;
  for (const fs::directory_entry& entry :
       fs::recursive_directory_iterator(path, fs::directory_options::follow_directory_symlink))
    if (entry.is_regular_file() && entry.path().extension() == ".csv") files.push_back(entry.path().string());
  std::sort(files.begin(), files.end());
  if (files.empty()) throw QueryFileError(path, 0, "folder holds no .csv query files");
  return files;
}

std::vector<QueryRecord> read_queries(const std::string& path, std::optional<PairKind> kind) {
  std::vector<QueryRecord> records;
  for (const std::string& file : query_files(path)) {
    std::vector<QueryRecord> part = read_query_file(file, kind);
    records.insert(records.end(), std::make_move_iterator(part.begin()), std::make_move_iterator(part.end()));
  }
  return records;
}

}  // namespace clothcd::ccd
