// validate_mesh's index check at the ends of the valid range: the largest valid index passes, the vertex count (one
// past the end), INT_MAX and INT_MIN are refused with the face and the index named, in every corner of a face.
#include <catch2/catch.hpp>

#include <climits>
#include <string>

#include "clothcd/mesh/mesh_error.hpp"
#include "clothcd/mesh/mesh_generators.hpp"
#include "clothcd/mesh/mesh_validation.hpp"

using clothcd::TriangleMesh;

TEST_CASE("validate_mesh refuses a face index equal to the vertex count, INT_MAX and INT_MIN", "[mesh][validation]") {
  const TriangleMesh box = clothcd::make_box();
  const int vertices = static_cast<int>(box.vertex_count());
  const int face = static_cast<int>(box.face_count()) - 1;
  for (int corner = 0; corner < 3; ++corner) {
    TriangleMesh last = box;
    last.faces(face, corner) = vertices - 1;  // the largest valid index
    CHECK_NOTHROW(clothcd::validate_mesh(last, "box"));
    for (const int index : {vertices, vertices + 1, INT_MAX, INT_MIN}) {
      INFO("corner " << corner << " index " << index);
      TriangleMesh bad = box;
      bad.faces(face, corner) = index;
      CHECK_THROWS_AS(clothcd::validate_mesh(bad, "box"), clothcd::MeshError);
      CHECK_THROWS_WITH(clothcd::validate_mesh(bad, "box"),
                        Catch::Contains("face " + std::to_string(face)) &&
                            Catch::Contains("vertex " + std::to_string(index)) && Catch::Contains("box"));
    }
  }
}
