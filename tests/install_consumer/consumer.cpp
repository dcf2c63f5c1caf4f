// Uses the installed core library: prints the library version and cloth C's triangle count (4802), then detects the
// collisions of a crumpling cloth with the filters and with the network culler (its model found in the installed share
// folder). The network may only add conservative hits (pairs the interval CCD could not decide, which it sends to the
// CCD without the filters); every collision the filters find must be among its own.
#include <clothcd/clothcd.hpp>

#include <cstdlib>
#include <iostream>
#include <set>
#include <tuple>

namespace {

using Key = std::tuple<int, int, int, int, int, int, int, int, int>;

Key key_of(const clothcd::Collision& c) {
  const auto& v = c.vertices;
  return {static_cast<int>(c.kind), v[0].body, v[0].vertex, v[1].body, v[1].vertex, v[2].body, v[2].vertex,
          v[3].body, v[3].vertex};
}

}  // namespace

int main() {
  const clothcd::TriangleMesh cloth = clothcd::make_paper_cloth('C');
  std::cout << clothcd::version() << '\n' << cloth.face_count() << '\n';
  std::srand(1);  // Eigen's Random: moves every vertex by up to 0.03, more than the grid spacing (0.02)
  const clothcd::Vertices end = cloth.vertices + 0.03 * clothcd::Vertices::Random(cloth.vertex_count(), 3);
  std::set<Key> with_network;
  long extra_conservative = 0, missing = 0, filters_count = 0;
  for (const clothcd::CullingMode mode : {clothcd::CullingMode::Network, clothcd::CullingMode::Filters}) {
    clothcd::DetectorSettings settings;
    settings.culling = mode;
    clothcd::learning::attach_network_culler(settings, "");  // the installed default network
    clothcd::CollisionDetector detector(cloth.faces, static_cast<int>(cloth.vertex_count()), settings);
    for (const clothcd::Collision& c : detector.detect(cloth.vertices, end)) {
      if (mode == clothcd::CullingMode::Network) {
        with_network.insert(key_of(c));
        extra_conservative += c.conservative ? 1 : 0;
      } else {
        ++filters_count;
        missing += with_network.count(key_of(c)) == 0 ? 1 : 0;
        extra_conservative -= c.conservative ? 1 : 0;
      }
    }
  }
  const long extra = static_cast<long>(with_network.size()) - filters_count;
  std::cout << "collisions: " << filters_count << " with the filters, " << with_network.size() << " with the network ("
            << missing << " missing, " << extra << " more, all conservative: " << (extra == extra_conservative) << ")\n";
  return filters_count > 0 && missing == 0 && extra == extra_conservative ? 0 : 1;
}
