// Reader of the CCD benchmark's rational CSV query files (Wang et al. 2021), one query at a time. Most coordinates are
// doubles written as n / 2^k with |n| < 2^53: those are read with 64-bit integers and converted exactly. The others
// (integers beyond 64 bits, other denominators) are parsed with GMP and rounded to the nearest double by comparing the
// neighbours of GMP's truncated value.
#include "clothcd/ccd/query_file.hpp"

#include <gmpxx.h>

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string_view>

namespace clothcd::ccd {

namespace {

namespace fs = std::filesystem;

std::string_view trim(std::string_view text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  const auto last = text.find_last_not_of(" \t\r");
  return text.substr(first, last - first + 1);
}

// The comma-separated, trimmed columns of `line` into `columns` (the first kMaxColumns of them); returns how many there
// are in all.
constexpr int kMaxColumns = 7;
int split_columns(std::string_view line, std::array<std::string_view, kMaxColumns>& columns) {
  int count = 0;
  for (std::size_t begin = 0;;) {
    const std::size_t comma = line.find(',', begin);
    const std::string_view column = trim(line.substr(begin, comma == std::string_view::npos ? line.npos : comma - begin));
    if (count < kMaxColumns) columns[count] = column;
    ++count;
    if (comma == std::string_view::npos) return count;
    begin = comma + 1;
  }
}

bool is_integer(std::string_view text) {
  const std::size_t digits_start = !text.empty() && (text[0] == '-' || text[0] == '+') ? 1 : 0;
  if (text.size() <= digits_start) return false;
  return std::all_of(text.begin() + digits_start, text.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// The integer text without a leading '+' (checked by is_integer).
std::string_view unsigned_plus(std::string_view text) { return text[0] == '+' ? text.substr(1) : text; }

mpz_class parse_integer(std::string_view text) { return mpz_class(std::string(unsigned_plus(text)), 10); }

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
std::optional<std::int64_t> small_integer(std::string_view text) {
  text = unsigned_plus(text);
  std::int64_t value = 0;
  const auto [rest, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || rest != text.data() + text.size() || value > (std::int64_t{1} << 62) ||
      value < -(std::int64_t{1} << 62))
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

// One coordinate from its numerator and denominator columns (integers): its text into `text`, its nearest double into
// `value`; returns whether that double is exact. `column` (1-based, of the numerator) is for messages.
bool parse_coordinate(const QueryFileError::Place& place, std::string_view numerator_text,
                      std::string_view denominator_text, int column, RationalText& text, double& value) {
  text[0].assign(unsigned_plus(numerator_text));
  text[1].assign(unsigned_plus(denominator_text));
  const std::optional<std::int64_t> small_numerator = small_integer(numerator_text);
  const std::optional<std::int64_t> small_denominator = small_integer(denominator_text);
  if (small_numerator && small_denominator) {
    if (const std::optional<double> dyadic = exact_dyadic(*small_numerator, *small_denominator)) {
      value = *dyadic;
      return true;
    }
  }
  const mpz_class numerator = parse_integer(numerator_text);
  const mpz_class denominator = parse_integer(denominator_text);
  if (denominator == 0) throw QueryFileError(place, "zero denominator in column " + std::to_string(column + 1));
  mpq_class q(numerator, denominator);
  q.canonicalize();
  if (abs(q) > mpq_class(std::numeric_limits<double>::max()))
    throw QueryFileError(place, "the coordinate in columns " + std::to_string(column) + "-" +
                                    std::to_string(column + 1) +
                                    " is beyond the range of doubles (magnitude above 1.8e308)");
  value = nearest_double(q);
  return mpq_class(value) == q;
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

QueryFileReader::QueryFileReader(const std::string& path, std::optional<PairKind> kind) : path_(path) {
  if (!kind) kind = pair_kind_from_path(path);
  if (!kind)
    throw QueryFileError(path, 0,
                         "pair type unknown: pass --type vf|ee or put the file under a vertex-face or edge-edge "
                         "folder");
  kind_ = *kind;
  in_.open(path);
  if (!in_) throw QueryFileError(path, 0, "cannot open file");
}

bool QueryFileReader::next(QueryRecord& record) {
  record.query.kind = kind_;
  record.exactly_representable = true;
  int row = 0;
  std::array<std::string_view, kMaxColumns> columns;
  while (row < 8 && std::getline(in_, line_)) {
    ++line_number_;
    const std::string_view line = trim(line_);
    if (line.empty()) continue;
    const QueryFileError::Place place{path_, line_number_};
    const int count = split_columns(line, columns);
    if (count != 6 && count != 7)
      throw QueryFileError(place, "expected 6 or 7 comma-separated integers, found " + std::to_string(count) +
                                      " columns");
    for (int c = 0; c < count; ++c) {
      if (!is_integer(columns[c]))
        throw QueryFileError(place, "column " + std::to_string(c + 1) + " is not an integer: '" +
                                        std::string(columns[c]) + "'");
      const std::size_t digits = columns[c].size() - (columns[c][0] == '-' || columns[c][0] == '+' ? 1 : 0);
      if (digits > kMaxIntegerDigits)
        throw QueryFileError(place, "column " + std::to_string(c + 1) + " holds an integer of " +
                                        std::to_string(digits) + " digits, more than the " +
                                        std::to_string(kMaxIntegerDigits) + " clothcd accepts");
    }
    Eigen::Vector3d& point = row < 4 ? record.query.start[row] : record.query.end[row - 4];
    for (int d = 0; d < 3; ++d) {
      const bool exact =
          parse_coordinate(place, columns[2 * d], columns[2 * d + 1], 2 * d + 1, record.rational[row][d], point[d]);
      record.exactly_representable = record.exactly_representable && exact;
    }
    int truth = -1;
    if (count == 7) {
      if (columns[6] != "0" && columns[6] != "1")
        throw QueryFileError(place, "ground truth (column 7) must be 0 or 1, got '" + std::string(columns[6]) + "'");
      truth = columns[6] == "1" ? 1 : 0;
    }
    if (row == 0) {
      record.line = line_number_;
      record.truth = truth;
    } else if (truth != record.truth) {
      throw QueryFileError(place,
                           "ground truth differs from the query's first row (line " + std::to_string(record.line) + ")");
    }
    ++row;
    ++rows_;
  }
  if (row == 0) return false;
  if (row < 8)
    throw QueryFileError(path_, 0, std::to_string(rows_) + " rows is not a multiple of 8 (8 rows per query)");
  record.file = path_;
  return true;
}

std::vector<QueryRecord> read_query_file(const std::string& path, std::optional<PairKind> kind) {
  QueryFileReader reader(path, kind);
  std::vector<QueryRecord> records;
  QueryRecord record;
  while (reader.next(record)) records.push_back(record);
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
