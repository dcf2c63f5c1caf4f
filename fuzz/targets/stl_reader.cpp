// libFuzzer target: the STL reader on any bytes. It returns a mesh whose indices and coordinates are valid, or throws
// MeshError.
#include "clothcd/mesh/mesh_error.hpp"
#include "fuzz_support.hpp"
#include "mesh/mesh_readers.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    clothcd::fuzz::require_valid(
        clothcd::detail::read_stl(std::string_view(reinterpret_cast<const char*>(data), size), "input.stl"));
  } catch (const clothcd::MeshError&) {
  }
  return 0;
}
