// libFuzzer target: load_mesh_frames on two files of one format. The first byte picks the format ('0' PLY, '1' OBJ,
// '2' OFF, '3' STL, any byte by its value modulo 4), the rest is the two files separated by kFileSeparator. It returns
// two frames of equal vertex count with valid faces, or throws MeshError.
#include "clothcd/mesh/mesh_error.hpp"
#include "clothcd/mesh/mesh_frames.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static const char* const kExtensions[] = {".ply", ".obj", ".off", ".stl"};
  const std::string extension = kExtensions[data[0] % 4];
  const auto [first, second] = clothcd::fuzz::split_files(data + 1, size - 1);
  const auto t0 = clothcd::fuzz::scratch_file("t0" + extension, first);
  const auto t1 = clothcd::fuzz::scratch_file("t1" + extension, second);
  try {
    const clothcd::MeshFrames frames = clothcd::load_mesh_frames(t0, t1);
    clothcd::fuzz::require_valid(frames.start);
    if (frames.end.rows() != frames.start.vertex_count() || !frames.end.allFinite()) std::abort();
  } catch (const clothcd::MeshError&) {
  }
  return 0;
}
