// Uses the installed core library: prints the library version, cloth C's triangle count (4802), and the collisions of
// a crumpling cloth found with the network culler (its model found in the installed share folder) and
// with the filters; the two counts must agree.
#include <clothcd/clothcd.hpp>

#include <cstdlib>
#include <iostream>

int main() {
  const clothcd::TriangleMesh cloth = clothcd::make_paper_cloth('C');
  std::cout << clothcd::version() << '\n' << cloth.face_count() << '\n';
  std::srand(1);  // Eigen's Random: moves every vertex by up to 0.03, more than the grid spacing (0.02)
  const clothcd::Vertices end = cloth.vertices + 0.03 * clothcd::Vertices::Random(cloth.vertex_count(), 3);
  std::size_t counts[2] = {0, 0};
  const clothcd::CullingMode modes[2] = {clothcd::CullingMode::Network, clothcd::CullingMode::Filters};
  for (int i = 0; i < 2; ++i) {
    clothcd::DetectorSettings settings;
    settings.culling = modes[i];
    clothcd::CollisionDetector detector(cloth.faces, static_cast<int>(cloth.vertex_count()), settings);
    counts[i] = detector.detect(cloth.vertices, end).size();
  }
  std::cout << (counts[0] == counts[1] ? "same collisions: " : "DIFFERENT collisions: ") << counts[0] << '\n';
  return counts[0] == counts[1] && counts[0] > 0 ? 0 : 1;
}
