#pragma once
// A reader of the regular files inside a gzip-compressed tar archive, streamed through zlib (the archive is never held
// in memory): POSIX ustar names (with their prefix field), GNU long names and pax extended headers. The model catalog
// extracts libcgal-demo's obstacle models from its data archive with it. Internal.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <ostream>
#include <string>

struct gzFile_s;  // zlib's file handle (gzFile), kept out of this header

namespace clothcd::detail {

/// The regular files of a .tar.gz archive, one after another in archive order. Every problem of the archive (a file
/// that cannot be opened, a stream that is not gzip or is corrupt or truncated, a header with a bad checksum or a bad
/// number, a file that runs past the end of the archive, an archive without its end-of-archive block) throws
/// std::runtime_error "<archive>: <problem>" when the reader gets to it. Reading stops where the caller stops, so the
/// gzip trailer (CRC-32 and length) is checked only when the archive is read to its end.
class TarGzReader {
 public:
  /// Opens `archive`; throws when it cannot be opened.
  explicit TarGzReader(const std::filesystem::path& archive);
  /// Closes the archive.
  ~TarGzReader();
  /// Not copyable: one reader owns the open stream.
  TarGzReader(const TarGzReader&) = delete;
  /// Not copyable: one reader owns the open stream.
  TarGzReader& operator=(const TarGzReader&) = delete;

  /// Advances to the next regular file, past the unread rest of the current one and past every other kind of entry
  /// (directories, links, devices, extended headers); false at the end of the archive, once the rest of the gzip
  /// stream is read and its trailer checked.
  bool next_file();
  /// Advances to the first regular file from here on whose path is `member` (compared exactly as stored); false when
  /// none is, which leaves the reader at the end of the archive.
  bool find(const std::string& member);

  /// Path of the current file: its pax "path" record, else its GNU long name, else the ustar prefix, '/' and name.
  [[nodiscard]] const std::string& path() const { return path_; }
  /// Size of the current file in bytes.
  [[nodiscard]] std::uint64_t size() const { return size_; }
  /// Copies the bytes of the current file not read yet into `out`; throws when the archive ends first or `out` fails.
  void copy_to(std::ostream& out);

 private:
  /// Reads up to `count` bytes of the tar stream into `into`; fewer only at the end of the stream.
  std::size_t read_some(char* into, std::size_t count);
  /// Reads exactly `count` bytes of the tar stream into `into`; throws naming `what` when the archive ends first.
  void read_exactly(char* into, std::size_t count, const std::string& what);
  /// Reads and drops `count` bytes of the tar stream; throws naming `what` when the archive ends first.
  void skip(std::uint64_t count, const std::string& what);
  /// Skips the unread data and padding of the current entry.
  void skip_rest_of_entry();
  /// Reads the `size` data bytes (and padding) of a long-name or pax entry, at most kMaxExtensionBytes.
  std::string read_extension_data(std::uint64_t size, const std::string& what);
  /// Throws std::runtime_error "<archive>: <problem>".
  [[noreturn]] void fail(const std::string& problem) const;

  /// Largest long name or pax header read (larger ones are refused rather than allocated).
  static constexpr std::uint64_t kMaxExtensionBytes = std::uint64_t{1} << 20;

  std::string archive_;                ///< The archive's path, for errors.
  gzFile_s* stream_ = nullptr;         ///< The open gzip stream.
  std::uint64_t offset_ = 0;           ///< Bytes of the tar stream read so far.
  bool ended_ = false;                 ///< True once the end-of-archive block was read.
  std::string path_;                   ///< Path of the current file.
  std::uint64_t size_ = 0;             ///< Size of the current file.
  std::uint64_t unread_data_ = 0;      ///< Data bytes of the current entry not read yet.
  std::uint64_t unread_padding_ = 0;   ///< Padding bytes after the current entry's data, up to a 512-byte block.
};

}  // namespace clothcd::detail
