// The tar header parsing and zlib streaming of TarGzReader (see tar_gz_member.hpp).
#include "mesh/tar_gz_member.hpp"

#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <system_error>

namespace clothcd::detail {
namespace {

/// A tar archive is a sequence of 512-byte blocks: a header, then the entry's data padded to whole blocks.
constexpr std::size_t kBlockBytes = 512;
/// Bytes read from the gzip stream at a time.
constexpr std::size_t kChunkBytes = std::size_t{1} << 16;

/// A field of a header block: its first byte and its width.
struct HeaderField {
  std::size_t offset;  ///< First byte in the block.
  std::size_t width;   ///< Bytes.
};
constexpr HeaderField kNameField{0, 100};
constexpr HeaderField kSizeField{124, 12};
constexpr HeaderField kChecksumField{148, 8};
constexpr std::size_t kTypeflagOffset = 156;
constexpr std::size_t kMagicOffset = 257;
constexpr HeaderField kPrefixField{345, 155};  // POSIX ustar only (GNU tar keeps other fields there)

/// The bytes of `field` in `block`.
std::string_view field_bytes(const char* block, HeaderField field) {
  return std::string_view(block + field.offset, field.width);
}

/// A text field: its bytes up to the first NUL (all of them when it has none).
std::string field_text(const char* block, HeaderField field) {
  const std::string_view bytes = field_bytes(block, field);
  return std::string(bytes.substr(0, bytes.find('\0')));
}

/// Padding after `size` data bytes, up to a whole block.
std::uint64_t padding_after(std::uint64_t size) { return (kBlockBytes - size % kBlockBytes) % kBlockBytes; }

/// Parses a numeric header field into `value`: octal digits after optional spaces, ended by NULs or spaces (a blank
/// field is 0), or GNU tar's base-256 form (high bit of the first byte set, then a big-endian two's complement
/// number). False with `problem` set when the field is malformed, negative or beyond 64 bits.
bool parse_header_number(std::string_view field, std::uint64_t& value, std::string& problem) {
  const auto first = static_cast<unsigned char>(field.front());
  if ((first & 0x80) != 0) {
    if ((first & 0x40) != 0) {
      problem = "a negative base-256 number";
      return false;
    }
    value = first & 0x3f;
    for (std::size_t i = 1; i < field.size(); ++i) {
      if ((value >> 56) != 0) {
        problem = "a base-256 number beyond 64 bits";
        return false;
      }
      value = (value << 8) | static_cast<unsigned char>(field[i]);
    }
    return true;
  }
  std::size_t i = 0;
  while (i < field.size() && field[i] == ' ') ++i;
  value = 0;
  for (; i < field.size() && field[i] >= '0' && field[i] <= '7'; ++i) {
    if ((value >> 61) != 0) {
      problem = "an octal number beyond 64 bits";
      return false;
    }
    value = value * 8 + static_cast<std::uint64_t>(field[i] - '0');
  }
  while (i < field.size() && (field[i] == ' ' || field[i] == '\0')) ++i;
  if (i != field.size()) {
    problem = "not an octal number";
    return false;
  }
  return true;
}

/// True when the header's stored checksum is the sum of its bytes with the checksum field read as spaces (as
/// unsigned bytes, or as signed ones, which some old tar programs summed).
bool checksum_matches(const char* block) {
  std::uint64_t stored = 0;
  std::string ignored;
  if (!parse_header_number(field_bytes(block, kChecksumField), stored, ignored)) return false;
  std::uint64_t unsigned_sum = 0;
  std::int64_t signed_sum = 0;
  for (std::size_t i = 0; i < kBlockBytes; ++i) {
    const bool in_field = i >= kChecksumField.offset && i < kChecksumField.offset + kChecksumField.width;
    const char byte = in_field ? ' ' : block[i];
    unsigned_sum += static_cast<unsigned char>(byte);
    signed_sum += static_cast<signed char>(byte);
  }
  return stored == unsigned_sum || (signed_sum >= 0 && stored == static_cast<std::uint64_t>(signed_sum));
}

/// True for a block of zeros: the end-of-archive marker.
bool is_zero_block(const char* block) {
  return std::all_of(block, block + kBlockBytes, [](char byte) { return byte == '\0'; });
}

/// The entry's path as its header stores it: the name field, after the prefix field and a '/' in a POSIX ustar header.
std::string header_path(const char* block) {
  std::string name = field_text(block, kNameField);
  // POSIX ustar: magic "ustar\0"; GNU tar writes "ustar  \0" and has no prefix field.
  if (std::memcmp(block + kMagicOffset, "ustar\0", 6) != 0) return name;
  const std::string prefix = field_text(block, kPrefixField);
  return prefix.empty() ? name : prefix + "/" + name;
}

/// The records of a pax extended header that reading a file needs; the others are ignored.
struct PaxRecords {
  std::optional<std::string> path;    ///< "path": the next entry's path.
  std::optional<std::uint64_t> size;  ///< "size": the next entry's size (beyond the header's 8 GiB).
};

/// Parses the records "<length> <key>=<value>\n" of a pax extended header (the length, in decimal, counts the whole
/// record) into `records`; an empty value removes the record. False with `problem` set when a record is malformed.
bool parse_pax_records(std::string_view data, PaxRecords& records, std::string& problem) {
  while (!data.empty()) {
    if (data.find_first_not_of('\0') == std::string_view::npos) break;  // NUL padding after the last record
    const std::size_t space = data.find(' ');
    std::uint64_t length = 0;
    const char* digits_end = data.data() + std::min(space, data.size());
    const auto [stop, error] = std::from_chars(data.data(), digits_end, length);
    if (space == std::string_view::npos || error != std::errc() || stop != digits_end || length <= space + 1 ||
        length > data.size() || data[length - 1] != '\n') {
      problem = "a malformed pax record";
      return false;
    }
    const std::string_view record = data.substr(space + 1, length - space - 2);  // "<key>=<value>"
    const std::size_t equals = record.find('=');
    if (equals == std::string_view::npos || equals == 0) {
      problem = "a pax record without a key";
      return false;
    }
    const std::string_view key = record.substr(0, equals);
    const std::string_view value = record.substr(equals + 1);
    if (key == "path") {
      records.path = value.empty() ? std::nullopt : std::optional<std::string>(value);
    } else if (key == "size") {
      if (value.empty()) {
        records.size.reset();
      } else {
        std::uint64_t size = 0;
        const auto [size_stop, size_error] = std::from_chars(value.data(), value.data() + value.size(), size);
        if (size_error != std::errc() || size_stop != value.data() + value.size()) {
          problem = "a pax size record that is not a decimal number";
          return false;
        }
        records.size = size;
      }
    }
    data.remove_prefix(length);
  }
  return true;
}

}  // namespace

TarGzReader::TarGzReader(const std::filesystem::path& archive) : archive_(archive.string()) {
  errno = 0;
  stream_ = gzopen(archive_.c_str(), "rb");
  if (stream_ == nullptr) {
    const int error = errno;
    fail(error != 0 ? "cannot be opened: " + std::generic_category().message(error) : "cannot be opened");
  }
  gzbuffer(stream_, kChunkBytes);
}

TarGzReader::~TarGzReader() {
  if (stream_ != nullptr) gzclose(stream_);
}

void TarGzReader::fail(const std::string& problem) const { throw std::runtime_error(archive_ + ": " + problem); }

std::size_t TarGzReader::read_some(char* into, std::size_t count) {
  std::size_t done = 0;
  int zlib_error = Z_OK;
  while (done < count) {
    const auto chunk = static_cast<unsigned>(std::min(count - done, kChunkBytes));
    const int got = gzread(stream_, into + done, chunk);
    if (got > 0) {
      done += static_cast<std::size_t>(got);
      continue;
    }
    gzerror(stream_, &zlib_error);
    if (got < 0 && zlib_error == Z_OK) zlib_error = Z_DATA_ERROR;
    break;  // the end of the stream, or an error
  }
  // zlib decompresses ahead of the reads, so where it finds an error says little about where the error is.
  if (zlib_error != Z_OK) {
    if (zlib_error == Z_BUF_ERROR) fail("the gzip stream ends early (truncated archive)");
    int ignored = Z_OK;
    std::string message = gzerror(stream_, &ignored);
    const std::string own_prefix = archive_ + ": ";  // zlib's messages start with the path it was given
    if (message.rfind(own_prefix, 0) == 0) message.erase(0, own_prefix.size());
    if (zlib_error == Z_ERRNO) fail("cannot be read: " + message);
    fail("corrupt gzip stream: " + message);
  }
  // zlib reads a file without the gzip magic as it is; a .tar.gz must be compressed.
  if (offset_ == 0 && done > 0 && gzdirect(stream_) == 1) fail("not a gzip-compressed file");
  offset_ += done;
  return done;
}

void TarGzReader::read_exactly(char* into, std::size_t count, const std::string& what) {
  if (read_some(into, count) < count) {
    fail("the archive ends at byte " + std::to_string(offset_) + " of the tar stream, inside " + what);
  }
}

void TarGzReader::skip(std::uint64_t count, const std::string& what) {
  char buffer[kChunkBytes];
  while (count > 0) {
    const auto chunk = static_cast<std::size_t>(std::min<std::uint64_t>(count, sizeof buffer));
    read_exactly(buffer, chunk, what);
    count -= chunk;
  }
}

void TarGzReader::skip_rest_of_entry() {
  const std::uint64_t data = unread_data_;
  const std::uint64_t padding = unread_padding_;
  unread_data_ = 0;
  unread_padding_ = 0;
  if (data == 0 && padding == 0) return;
  const std::string what = "the data of '" + path_ + "' (" + std::to_string(size_) +
                           " bytes announced: a truncated archive or a size that runs past its end)";
  skip(data, what);
  skip(padding, what);
}

std::string TarGzReader::read_extension_data(std::uint64_t size, const std::string& what) {
  if (size > kMaxExtensionBytes) {
    fail(what + " announces " + std::to_string(size) + " bytes (more than " + std::to_string(kMaxExtensionBytes) +
         ": a corrupt archive)");
  }
  std::string data(static_cast<std::size_t>(size), '\0');
  read_exactly(data.data(), data.size(), what);
  skip(padding_after(size), what);
  return data;
}

bool TarGzReader::next_file() {
  if (ended_) return false;
  skip_rest_of_entry();
  path_.clear();
  size_ = 0;
  std::optional<std::string> long_name;  // GNU tar's 'L' entry, for the next header
  PaxRecords pax;                        // a pax 'x' header's records, for the next header
  bool extension_pending = false;
  char block[kBlockBytes];
  for (;;) {
    const std::string at = "at byte " + std::to_string(offset_) + " of the tar stream";
    const std::size_t got = read_some(block, kBlockBytes);
    if (got == 0 && offset_ == 0) fail("no tar header (an empty archive, or not a tar file)");
    if (got == 0) fail("the archive ends " + at + " without its end-of-archive block (truncated archive)");
    if (got < kBlockBytes) fail("the archive ends inside the header " + at + " (truncated archive)");
    if (is_zero_block(block)) {
      if (extension_pending) fail("the archive ends " + at + " right after an extended header, without its entry");
      ended_ = true;
      // The rest of the stream (the second zero block, a tar program's padding to whole records): reading it to its
      // end checks the gzip trailer (CRC-32 and length), so that a corrupt archive is not taken for one without the
      // member.
      char rest[kChunkBytes];
      while (read_some(rest, sizeof rest) == sizeof rest) {
      }
      return false;
    }
    if (!checksum_matches(block)) fail("bad header checksum " + at + " (a corrupt archive, or not a tar file)");
    std::uint64_t header_size = 0;
    std::string problem;
    if (!parse_header_number(field_bytes(block, kSizeField), header_size, problem)) {
      fail("the size field of the header " + at + " is " + problem);
    }
    const char type = block[kTypeflagOffset];
    if (type == 'L' || type == 'K' || type == 'x' || type == 'g') {
      const std::string what = std::string(type == 'L'   ? "a GNU long name"
                                            : type == 'K' ? "a GNU long link name"
                                            : type == 'x' ? "a pax extended header"
                                                          : "a pax global header") +
                               " (header " + at + ")";
      if (type == 'g') {  // defaults for every later entry; none of them matter here
        skip(header_size, what);
        skip(padding_after(header_size), what);
        continue;
      }
      const std::string data = read_extension_data(header_size, what);
      if (type == 'L') long_name = data.substr(0, data.find('\0'));
      if (type == 'x' && !parse_pax_records(data, pax, problem)) fail(what + " holds " + problem);
      extension_pending = true;  // a 'K' entry (a hard or symbolic link's long target) is read and dropped
      continue;
    }
    path_ = pax.path ? *pax.path : long_name ? *long_name : header_path(block);
    size_ = pax.size.value_or(header_size);
    unread_data_ = size_;
    unread_padding_ = padding_after(size_);
    // '0' and '7' (contiguous) are regular files, and so is '\0' (pre-POSIX tar) unless the name ends in '/'.
    const bool regular = type == '0' || type == '7' || (type == '\0' && (path_.empty() || path_.back() != '/'));
    if (regular) return true;
    skip_rest_of_entry();
    long_name.reset();
    pax = PaxRecords();
    extension_pending = false;
  }
}

bool TarGzReader::find(const std::string& member) {
  while (next_file()) {
    if (path_ == member) return true;
  }
  return false;
}

void TarGzReader::copy_to(std::ostream& out) {
  const std::string what = "the data of '" + path_ + "' (" + std::to_string(size_) +
                           " bytes announced: a truncated archive or a size that runs past its end)";
  char buffer[kChunkBytes];
  while (unread_data_ > 0) {
    const auto chunk = static_cast<std::size_t>(std::min<std::uint64_t>(unread_data_, sizeof buffer));
    read_exactly(buffer, chunk, what);
    unread_data_ -= chunk;
    out.write(buffer, static_cast<std::streamsize>(chunk));
    if (!out) fail("cannot copy '" + path_ + "' out: the output stream failed");
  }
}

}  // namespace clothcd::detail
