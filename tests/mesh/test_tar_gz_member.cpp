// The .tar.gz reader of the model catalog: archives written here header by header (ustar with and without the prefix
// field, GNU long names, pax headers, base-256 sizes) and gzip-compressed with zlib, exact bytes out, a missing member,
// and one clear error naming the archive for each kind of broken archive; libcgal-demo's own archive against tar.
#include <zlib.h>

#include <catch2/catch.hpp>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "mesh/tar_gz_member.hpp"
#include "support/test_support.hpp"

using clothcd::detail::TarGzReader;
using clothcd::test::TempDir;
using clothcd::test::write_file;

namespace {

/// The magic a header is written with.
enum class TarFormat { posix_ustar, gnu, v7 };

/// Writes `value` as `width - 1` octal digits and a NUL at `block + offset`.
void put_octal(std::string& block, std::size_t offset, std::size_t width, std::uint64_t value) {
  for (std::size_t i = width - 1; i-- > 0;) {
    block[offset + i] = static_cast<char>('0' + (value & 7));
    value >>= 3;
  }
  block[offset + width - 1] = '\0';
}

/// Stores the header's checksum (its bytes summed with the checksum field as spaces), as tar writes it.
void put_checksum(std::string& block) {
  std::memset(&block[148], ' ', 8);
  unsigned sum = 0;
  for (const char byte : block) sum += static_cast<unsigned char>(byte);
  put_octal(block, 148, 7, sum);
  block[155] = ' ';
}

/// A 512-byte header block of an entry of `type` and `size` bytes named `name` (and `prefix`, POSIX ustar only).
std::string tar_header(const std::string& name, char type, std::uint64_t size,
                       TarFormat format = TarFormat::posix_ustar, const std::string& prefix = "") {
  std::string block(512, '\0');
  block.replace(0, std::min<std::size_t>(name.size(), 100), name, 0, 100);
  put_octal(block, 100, 8, 0644);
  put_octal(block, 108, 8, 1000);
  put_octal(block, 116, 8, 1000);
  put_octal(block, 124, 12, size);
  put_octal(block, 136, 12, 1700000000);
  block[156] = type;
  if (format == TarFormat::posix_ustar) {
    block.replace(257, 8, std::string("ustar\0" "00", 8));
    block.replace(345, prefix.size(), prefix);
  } else if (format == TarFormat::gnu) {
    block.replace(257, 8, std::string("ustar  \0", 8));
  }
  block.replace(265, 4, "user");
  block.replace(297, 5, "group");
  put_checksum(block);
  return block;
}

/// `data` padded with zeros to whole 512-byte blocks.
std::string padded(const std::string& data) { return data + std::string((512 - data.size() % 512) % 512, '\0'); }

/// A whole entry: `header` then `data` padded to whole blocks.
std::string tar_entry(const std::string& header, const std::string& data) { return header + padded(data); }

/// A regular file entry in POSIX ustar form.
std::string file_entry(const std::string& name, const std::string& data) {
  return tar_entry(tar_header(name, '0', data.size()), data);
}

/// The end-of-archive marker: two zero blocks.
std::string end_blocks() { return std::string(1024, '\0'); }

/// One pax record "<length> <key>=<value>\n", the length counting the whole record.
std::string pax_record(const std::string& key, const std::string& value) {
  const std::string body = " " + key + "=" + value + "\n";
  std::size_t length = body.size() + 1;
  while (std::to_string(length).size() + body.size() != length) ++length;
  return std::to_string(length) + body;
}

/// Bytes that are neither text nor zero-free: every byte value, twice, and a few more.
std::string binary_bytes(std::size_t count) {
  std::string bytes(count, '\0');
  for (std::size_t i = 0; i < count; ++i) bytes[i] = static_cast<char>((i * 7 + i / 256) & 0xff);
  return bytes;
}

/// Writes `tar` gzip-compressed with zlib to `path` and returns the path.
std::filesystem::path write_tar_gz(const std::filesystem::path& path, const std::string& tar, int level = 6) {
  gzFile out = gzopen(path.c_str(), ("wb" + std::to_string(level)).c_str());
  REQUIRE(out != nullptr);
  REQUIRE(gzwrite(out, tar.data(), static_cast<unsigned>(tar.size())) == static_cast<int>(tar.size()));
  REQUIRE(gzclose(out) == Z_OK);
  return path;
}

/// The bytes of `member` read from `archive`, or nothing when the archive has no such regular file.
std::optional<std::string> extract(const std::filesystem::path& archive, const std::string& member) {
  TarGzReader reader(archive);
  if (!reader.find(member)) return std::nullopt;
  std::ostringstream out;
  reader.copy_to(out);
  return out.str();
}

/// The paths of every regular file of `archive`, reading (and dropping) each one's bytes.
std::vector<std::string> file_paths(const std::filesystem::path& archive) {
  TarGzReader reader(archive);
  std::vector<std::string> paths;
  while (reader.next_file()) {
    paths.push_back(reader.path());
    std::ostringstream out;
    reader.copy_to(out);
    CHECK(out.str().size() == reader.size());
  }
  return paths;
}

/// The message of the std::runtime_error that extracting `member` from `archive` throws ("" when none).
std::string extract_error(const std::filesystem::path& archive, const std::string& member) {
  try {
    (void)extract(archive, member);
  } catch (const std::runtime_error& error) {
    return error.what();
  }
  return "";
}

}  // namespace

TEST_CASE("tar.gz reader: POSIX ustar members, found by path with their exact bytes", "[mesh][tar]") {
  TempDir dir;
  const std::string text = "OFF\n8 6 0\n" + std::string(700, 'x') + "\n";  // two blocks, padded
  const std::string binary = binary_bytes(1536);                          // exactly three blocks, no padding
  const std::string tar = tar_entry(tar_header("data/", '5', 0), "") + file_entry("data/a.txt", text) +
                          file_entry("data/b.bin", binary) + tar_entry(tar_header("data/link", '2', 0), "") +
                          file_entry("data/empty", "") + end_blocks();
  const auto archive = write_tar_gz(dir / "a.tar.gz", tar);

  CHECK(extract(archive, "data/a.txt") == text);
  CHECK(extract(archive, "data/b.bin") == binary);
  CHECK(extract(archive, "data/empty") == std::string());
  // Only regular files match: not the directory, not the symbolic link.
  CHECK_FALSE(extract(archive, "data/").has_value());
  CHECK_FALSE(extract(archive, "data/link").has_value());
  CHECK(file_paths(archive) == std::vector<std::string>{"data/a.txt", "data/b.bin", "data/empty"});

  SECTION("a member read after another one was read in part or not at all") {
    TarGzReader reader(archive);
    REQUIRE(reader.next_file());
    CHECK(reader.path() == "data/a.txt");
    CHECK(reader.size() == text.size());
    REQUIRE(reader.find("data/empty"));
    CHECK(reader.size() == 0);
    CHECK_FALSE(reader.next_file());
    CHECK_FALSE(reader.next_file());
  }
  SECTION("any compression level, and a file in the old (pre-POSIX) form") {
    CHECK(extract(write_tar_gz(dir / "stored.tar.gz", tar, 0), "data/b.bin") == binary);
    const std::string v7 = tar_entry(tar_header("dir/", '\0', 0, TarFormat::v7), "") +
                           tar_entry(tar_header("dir/old.off", '\0', text.size(), TarFormat::v7), text) + end_blocks();
    const auto old = write_tar_gz(dir / "v7.tar.gz", v7);
    CHECK(extract(old, "dir/old.off") == text);
    CHECK(file_paths(old) == std::vector<std::string>{"dir/old.off"});
  }
}

TEST_CASE("tar.gz reader: a path split between the ustar prefix and name fields", "[mesh][tar]") {
  TempDir dir;
  const std::string data = "prefix member\n";
  const std::string prefix = "data/" + std::string(120, 'p');
  const std::string name = std::string(96, 'n') + ".off";  // the name field full, without a NUL
  const std::string tar = tar_entry(tar_header(name, '0', data.size(), TarFormat::posix_ustar, prefix), data) +
                          tar_entry(tar_header("cube.off", '0', 4, TarFormat::posix_ustar, "data/meshes"), "cube") +
                          end_blocks();
  const auto archive = write_tar_gz(dir / "prefix.tar.gz", tar);
  CHECK(extract(archive, prefix + "/" + name) == data);
  CHECK(extract(archive, "data/meshes/cube.off") == std::string("cube"));
  CHECK_FALSE(extract(archive, "cube.off").has_value());
  CHECK_FALSE(extract(archive, name).has_value());
}

TEST_CASE("tar.gz reader: GNU long names", "[mesh][tar]") {
  TempDir dir;
  const std::string long_name = "data/" + std::string(150, 'l') + "/bunny.off";
  const std::string data = binary_bytes(1000);
  const std::string tar = tar_entry(tar_header("././@LongLink", 'L', long_name.size() + 1, TarFormat::gnu),
                                    long_name + '\0') +
                          tar_entry(tar_header(long_name.substr(0, 100), '0', data.size(), TarFormat::gnu), data) +
                          // A symbolic link with a GNU long link name ('K'), then a short name again.
                          tar_entry(tar_header("././@LongLink", 'K', 201, TarFormat::gnu),
                                    std::string(200, 't') + '\0') +
                          tar_entry(tar_header("data/link", '2', 0, TarFormat::gnu), "") +
                          tar_entry(tar_header("data/short.off", '0', 5, TarFormat::gnu), "short") + end_blocks();
  const auto archive = write_tar_gz(dir / "gnu.tar.gz", tar);
  CHECK(extract(archive, long_name) == data);
  CHECK(extract(archive, "data/short.off") == std::string("short"));
  CHECK_FALSE(extract(archive, long_name.substr(0, 100)).has_value());
  CHECK(file_paths(archive) == std::vector<std::string>{long_name, "data/short.off"});
}

TEST_CASE("tar.gz reader: pax extended headers", "[mesh][tar]") {
  TempDir dir;
  const std::string pax_path = "data/" + std::string(300, 'x') + "/man.off";
  const std::string data = binary_bytes(777);
  const std::string global = pax_record("comment", "a global header, skipped") + pax_record("path", "not/this/one");
  const std::string extended = pax_record("mtime", "1700000000.5") + pax_record("path", pax_path) +
                               pax_record("comment", "a value with = and\nnew lines");
  const std::string tar = tar_entry(tar_header("pax_global_header", 'g', global.size()), global) +
                          tar_entry(tar_header("PaxHeaders/man.off", 'x', extended.size()), extended) +
                          tar_entry(tar_header("data/truncated-name.off", '0', data.size()), data) +
                          file_entry("data/after.off", "after") + end_blocks();
  const auto archive = write_tar_gz(dir / "pax.tar.gz", tar);
  CHECK(extract(archive, pax_path) == data);
  CHECK(extract(archive, "data/after.off") == std::string("after"));
  CHECK_FALSE(extract(archive, "data/truncated-name.off").has_value());
  CHECK_FALSE(extract(archive, "not/this/one").has_value());
  CHECK(file_paths(archive) == std::vector<std::string>{pax_path, "data/after.off"});

  SECTION("a pax size record overrides the header's size field") {
    const std::string sized = pax_record("size", std::to_string(data.size()));
    const auto big = write_tar_gz(dir / "pax-size.tar.gz",
                                  tar_entry(tar_header("PaxHeaders/big", 'x', sized.size()), sized) +
                                      tar_entry(tar_header("big", '0', 0), data) + file_entry("next", "n") +
                                      end_blocks());
    CHECK(extract(big, "big") == data);
    CHECK(extract(big, "next") == std::string("n"));
  }
  SECTION("a malformed pax record is an error") {
    for (const std::string& bad : {std::string("99 path=x\n"), std::string("abc path=x\n"), std::string("8 path=x"),
                                  std::string("7 =abc\n"), pax_record("size", "12x")}) {
      INFO(bad);
      const auto broken = write_tar_gz(dir / "bad-pax.tar.gz",
                                       tar_entry(tar_header("PaxHeaders/x", 'x', bad.size()), bad) +
                                           file_entry("x", "x") + end_blocks());
      CHECK_THAT(extract_error(broken, "x"), Catch::Contains(broken.string()) && Catch::Contains("pax"));
    }
  }
}

TEST_CASE("tar.gz reader: sizes in GNU tar's base-256 form", "[mesh][tar]") {
  TempDir dir;
  const std::string data = binary_bytes(600);
  std::string header = tar_header("data/base256.off", '0', 0, TarFormat::gnu);
  std::memset(&header[124], 0, 12);
  header[124] = static_cast<char>(0x80);
  header[134] = static_cast<char>(600 >> 8);
  header[135] = static_cast<char>(600 & 0xff);
  put_checksum(header);
  const auto archive = write_tar_gz(dir / "base256.tar.gz", tar_entry(header, data) + end_blocks());
  CHECK(extract(archive, "data/base256.off") == data);

  header[124] = static_cast<char>(0xff);  // negative
  put_checksum(header);
  const auto negative = write_tar_gz(dir / "negative.tar.gz", tar_entry(header, data) + end_blocks());
  CHECK_THAT(extract_error(negative, "data/base256.off"),
             Catch::Contains(negative.string()) && Catch::Contains("negative base-256"));
}

TEST_CASE("tar.gz reader: a member that is not in the archive", "[mesh][tar]") {
  TempDir dir;
  const auto archive = write_tar_gz(dir / "a.tar.gz", file_entry("data/meshes/cube.off", "cube") + end_blocks());
  CHECK_FALSE(extract(archive, "data/meshes/sphere.off").has_value());
  CHECK_FALSE(extract(archive, "data/meshes/cube.of").has_value());
  CHECK_FALSE(extract(archive, "./data/meshes/cube.off").has_value());
  // Only the first zero block is needed: the archive ends there.
  const auto lone = write_tar_gz(dir / "lone.tar.gz", file_entry("a", "a") + std::string(512, '\0'));
  CHECK_FALSE(extract(lone, "b").has_value());
  CHECK(extract(lone, "a") == std::string("a"));
  const auto empty_archive = write_tar_gz(dir / "empty.tar.gz", end_blocks());
  CHECK_FALSE(extract(empty_archive, "a").has_value());
}

TEST_CASE("tar.gz reader: broken archives throw std::runtime_error naming the archive", "[mesh][tar]") {
  TempDir dir;
  const std::string data = binary_bytes(5000);
  const std::string tar = file_entry("data/first.off", "first") + file_entry("data/big.off", data) +
                          file_entry("data/last.off", "last") + end_blocks();
  const auto whole = write_tar_gz(dir / "whole.tar.gz", tar);
  REQUIRE(extract(whole, "data/last.off") == std::string("last"));
  const auto error = [&](const std::filesystem::path& archive, const std::string& member = "data/last.off") {
    return extract_error(archive, member);
  };

  SECTION("a tar stream cut inside a member's data") {
    const auto cut = write_tar_gz(dir / "cut.tar.gz", tar.substr(0, 512 + 512 + 512 + 3000));
    CHECK_THAT(error(cut), Catch::Contains(cut.string()) && Catch::Contains("inside the data of 'data/big.off'"));
    CHECK_THAT(error(cut, "data/big.off"),
               Catch::Contains(cut.string()) && Catch::Contains("inside the data of 'data/big.off'"));
    CHECK(extract(cut, "data/first.off") == std::string("first"));  // what comes before the cut is read
  }
  SECTION("a tar stream cut inside a header, or at a header without the end-of-archive block") {
    const auto in_header = write_tar_gz(dir / "header.tar.gz", tar.substr(0, 1024 + 100));
    CHECK_THAT(error(in_header), Catch::Contains(in_header.string()) && Catch::Contains("inside the header"));
    const auto no_end = write_tar_gz(dir / "no-end.tar.gz", tar.substr(0, tar.size() - 1024));
    CHECK_THAT(error(no_end, "data/missing"),
               Catch::Contains(no_end.string()) && Catch::Contains("without its end-of-archive block"));
    const auto empty = write_tar_gz(dir / "empty.tar.gz", "");
    CHECK_THAT(error(empty), Catch::Contains(empty.string()) && Catch::Contains("no tar header"));
  }
  SECTION("a gzip file cut short") {
    const std::string compressed = clothcd::test::read_file(whole);
    for (const std::size_t length : {std::size_t{5}, std::size_t{20}, compressed.size() / 2, compressed.size() - 4}) {
      INFO(length);
      const auto cut = write_file(dir / "cut-gzip.tar.gz", compressed.substr(0, length));
      CHECK_THAT(error(cut, "data/missing"),
                 Catch::Contains(cut.string()) && Catch::Contains("gzip stream ends early"));
    }
  }
  SECTION("a corrupt gzip stream") {
    std::string compressed = clothcd::test::read_file(whole);
    compressed[10] = static_cast<char>(0xff);  // the first deflate block: a block type that does not exist
    const auto corrupt = write_file(dir / "corrupt.tar.gz", compressed);
    CHECK_THAT(error(corrupt), Catch::Contains(corrupt.string()) && Catch::Contains("corrupt gzip stream"));
    compressed = clothcd::test::read_file(whole);
    compressed[compressed.size() - 8] ^= 0x01;  // the CRC-32 of the data
    const auto bad_crc = write_file(dir / "bad-crc.tar.gz", compressed);
    CHECK_THAT(error(bad_crc, "data/missing"),
               Catch::Contains(bad_crc.string()) && Catch::Contains("corrupt gzip stream"));
  }
  SECTION("an uncompressed tar, a file that cannot be opened") {
    const auto plain = write_file(dir / "plain.tar.gz", tar);
    CHECK_THAT(error(plain), Catch::Contains(plain.string()) && Catch::Contains("not a gzip-compressed file"));
    CHECK_THAT(error(dir / "absent.tar.gz"),
               Catch::Contains((dir / "absent.tar.gz").string()) && Catch::Contains("cannot be opened"));
  }
  SECTION("a bad header checksum") {
    std::string broken = tar;
    broken[1024 + 10] ^= 0x20;  // a byte of the second header's name, its checksum left as it was
    const auto archive = write_tar_gz(dir / "checksum.tar.gz", broken);
    CHECK_THAT(error(archive),
               Catch::Contains(archive.string()) && Catch::Contains("bad header checksum at byte 1024"));
    const auto garbage = write_tar_gz(dir / "garbage.tar.gz", std::string(2048, 'g'));
    CHECK_THAT(error(garbage), Catch::Contains(garbage.string()) && Catch::Contains("bad header checksum at byte 0"));
  }
  SECTION("a size that runs past the end of the archive, a size field that is not a number") {
    std::string broken = tar;
    broken.replace(1024, 512, tar_header("data/big.off", '0', 077777777777));
    const auto archive = write_tar_gz(dir / "size.tar.gz", broken);
    CHECK_THAT(error(archive), Catch::Contains(archive.string()) && Catch::Contains("inside the data of") &&
                                   Catch::Contains("8589934591 bytes announced"));
    CHECK_THAT(error(archive, "data/big.off"),
               Catch::Contains(archive.string()) && Catch::Contains("inside the data of 'data/big.off'"));
    std::string header = tar_header("data/big.off", '0', data.size());
    header.replace(124, 4, "12x4");
    put_checksum(header);
    broken.replace(1024, 512, header);
    const auto not_octal = write_tar_gz(dir / "not-octal.tar.gz", broken);
    CHECK_THAT(error(not_octal), Catch::Contains(not_octal.string()) && Catch::Contains("not an octal number"));
  }
  SECTION("a long name or pax header too large to be one") {
    const auto huge = write_tar_gz(dir / "huge.tar.gz",
                                   tar_header("././@LongLink", 'L', 077777777777, TarFormat::gnu) + end_blocks());
    CHECK_THAT(error(huge), Catch::Contains(huge.string()) && Catch::Contains("GNU long name") &&
                                Catch::Contains("announces 8589934591 bytes"));
    const auto dangling = write_tar_gz(dir / "dangling.tar.gz",
                                       tar_entry(tar_header("././@LongLink", 'L', 3, TarFormat::gnu), "ab") +
                                           end_blocks());
    CHECK_THAT(error(dangling), Catch::Contains(dangling.string()) && Catch::Contains("without its entry"));
  }
}

TEST_CASE("tar.gz reader: every prefix of an archive reads in full or throws std::runtime_error", "[mesh][tar]") {
  TempDir dir;
  const std::string long_name = std::string(120, 'l');
  const std::string path_record = pax_record("path", "pax/" + long_name);
  const std::string tar = tar_entry(tar_header("././@LongLink", 'L', long_name.size() + 1, TarFormat::gnu),
                                    long_name + '\0') +
                          tar_entry(tar_header(long_name.substr(0, 100), '0', 3, TarFormat::gnu), "gnu") +
                          tar_entry(tar_header("PaxHeaders/p", 'x', path_record.size()), path_record) +
                          tar_entry(tar_header("p", '0', 700), binary_bytes(700)) + end_blocks();
  const std::size_t first_zero_block = tar.size() - 1024;  // the archive ends with it
  for (std::size_t length = 0; length <= tar.size(); length += 128) {
    INFO(length);
    const auto archive = write_tar_gz(dir / "prefix.tar.gz", tar.substr(0, length));
    if (length >= first_zero_block + 512) {
      CHECK(file_paths(archive) == std::vector<std::string>{long_name, "pax/" + long_name});
    } else {
      CHECK_THROWS_AS(file_paths(archive), std::runtime_error);
    }
  }
}

TEST_CASE("tar.gz reader: libcgal-demo's data archive, as tar extracts it", "[mesh][tar][models]") {
  const std::filesystem::path archive = "/usr/share/doc/libcgal-dev/data.tar.gz";
  if (!std::filesystem::exists(archive)) {
    WARN("skipped: no " << archive.string() << " (the Debian package libcgal-demo)");
    return;
  }
  for (const std::string member : {"data/meshes/cube.off", "data/meshes/bunny00.off"}) {
    INFO(member);
    std::string expected;
    FILE* pipe = popen(("tar -xzOf '" + archive.string() + "' '" + member + "'").c_str(), "r");
    REQUIRE(pipe != nullptr);
    char buffer[4096];
    std::size_t got = 0;
    while ((got = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) expected.append(buffer, got);
    REQUIRE(pclose(pipe) == 0);
    REQUIRE_FALSE(expected.empty());
    CHECK(extract(archive, member) == expected);
  }
  CHECK_FALSE(extract(archive, "data/meshes/no-such-mesh.off").has_value());
}
