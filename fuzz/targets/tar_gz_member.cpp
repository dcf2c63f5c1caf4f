// libFuzzer target: the .tar.gz reader of the model catalog on any bytes, gzip-compressed here unless they start with
// the gzip magic (so that most mutations reach the tar headers rather than zlib's checks). It reads every regular file
// to its end, its announced size exactly, or throws std::runtime_error.
#include <zlib.h>

#include <cstdlib>
#include <ostream>
#include <stdexcept>
#include <streambuf>

#include "fuzz_support.hpp"
#include "mesh/tar_gz_member.hpp"

namespace {

/// An output buffer that only counts the bytes written to it.
struct CountingBuffer : std::streambuf {
  std::uint64_t count = 0;  ///< Bytes written.
  std::streamsize xsputn(const char*, std::streamsize size) override {
    count += static_cast<std::uint64_t>(size);
    return size;
  }
  int_type overflow(int_type byte) override {
    ++count;
    return byte;
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  std::filesystem::path archive;
  if (input.rfind("\x1f\x8b", 0) == 0) {
    archive = clothcd::fuzz::scratch_file("input.tar.gz", input);
  } else {
    archive = clothcd::fuzz::scratch_dir() / "input.tar.gz";
    gzFile out = gzopen(archive.c_str(), "wb1");
    if (out == nullptr || gzwrite(out, input.data(), static_cast<unsigned>(input.size())) != static_cast<int>(size) ||
        gzclose(out) != Z_OK) {
      std::abort();  // the scratch folder cannot be written: no input can be tested
    }
  }
  try {
    clothcd::detail::TarGzReader reader(archive);
    while (reader.next_file()) {
      CountingBuffer counter;
      std::ostream out(&counter);
      reader.copy_to(out);
      if (counter.count != reader.size()) std::abort();
    }
  } catch (const std::runtime_error&) {
  }
  return 0;
}
