// libFuzzer target: the CCD query-file reader (the public benchmark's rational CSV) on any bytes, as vertex-face
// queries when the first byte is even, edge-edge ones when odd. It returns the queries or throws QueryFileError.
#include "clothcd/ccd/query_file.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const auto path = clothcd::fuzz::scratch_file(
      "queries.csv", std::string(reinterpret_cast<const char*>(data) + 1, size - 1));
  const auto kind = data[0] % 2 == 0 ? clothcd::PairKind::VertexFace : clothcd::PairKind::EdgeEdge;
  try {
    (void)clothcd::ccd::read_query_file(path.string(), kind);
  } catch (const clothcd::ccd::QueryFileError&) {
  }
  return 0;
}
