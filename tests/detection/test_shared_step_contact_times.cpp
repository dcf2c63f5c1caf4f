// Exact answers on the shared real simulation steps (when that data is present): with the default settings every
// reported collision is a proven one (the exact rational reference confirms it), its time of impact is never later
// than the pair's exact earliest contact and at most 1e-6 of the step earlier, and the step's earliest time of impact
// is the exact one (reference values by rational root isolation), as is the earliest-impact search's answer.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <string>

#include "ccd/exact_reference.hpp"
#include "clothcd/detection/collision_detector.hpp"
#include "clothcd/mesh/mesh_frames.hpp"

namespace {

namespace fs = std::filesystem;

/// The shared data folder: $CLOTHCD_SHARED_DATA, else ../shared/data beside the source tree.
fs::path shared_data() {
  if (const char* dir = std::getenv("CLOTHCD_SHARED_DATA")) return dir;
  return fs::path(CLOTHCD_TEST_DATA_DIR).parent_path().parent_path().parent_path() / "shared" / "data";
}

/// The collision's eight points as exact rationals (start then end positions, CcdQuery order).
clothcd::ccd::exact::RationalPoints points_of(const clothcd::Collision& c, const clothcd::MeshFrames& frames) {
  clothcd::ccd::exact::RationalPoints points;
  for (int i = 0; i < 4; ++i) {
    for (int d = 0; d < 3; ++d) {
      points[i][d] = mpq_class(frames.start.vertices(c.vertices[i].vertex, d));
      points[i + 4][d] = mpq_class(frames.end(c.vertices[i].vertex, d));
    }
  }
  return points;
}

}  // namespace

TEST_CASE("shared steps: every reported collision is proven, with a tight time of impact",
          "[mesh][detection][shared][exact]") {
  struct Scene {
    std::string name;
    double earliest;  // the step's exact earliest contact time, to the digits given
    double digits;    // half a unit of its last digit
  };
  const fs::path root = shared_data() / "scalable-ccd-sample";
  for (const Scene& scene : {Scene{"cloth-funnel", 0.0452322204, 5e-11}, Scene{"rod-twist", 5.88845763e-5, 5e-14}}) {
    if (!fs::exists(root / scene.name / "t0.ply")) {
      WARN("skipped: no " << (root / scene.name).string());
      continue;
    }
    INFO(scene.name);
    const clothcd::MeshFrames frames =
        clothcd::load_mesh_frames(root / scene.name / "t0.ply", root / scene.name / "t1.ply");
    clothcd::CollisionDetector detector(frames.start.faces, static_cast<int>(frames.start.vertex_count()), {});
    const std::vector<clothcd::Collision> collisions = detector.detect(frames.start.vertices, frames.end);
    REQUIRE_FALSE(collisions.empty());
    double earliest_lo = 1.0, earliest_hi = 1.0, earliest_toi = 1.0;
    int late = 0, loose = 0, unconfirmed = 0, conservative = 0;
    for (const clothcd::Collision& c : collisions) {
      const clothcd::ccd::exact::ContactTimeBounds exact =
          clothcd::ccd::exact::exact_contact_time(c.kind, points_of(c, frames));
      conservative += c.conservative ? 1 : 0;
      unconfirmed += exact.hit ? 0 : 1;
      late += c.toi > exact.hi ? 1 : 0;
      loose += c.toi < exact.lo - 1e-6 ? 1 : 0;
      earliest_lo = std::min(earliest_lo, exact.lo);
      earliest_hi = std::min(earliest_hi, exact.hi);
      earliest_toi = std::min(earliest_toi, c.toi);
    }
    CHECK(conservative == 0);
    CHECK(unconfirmed == 0);
    CHECK(late == 0);
    CHECK(loose == 0);
    CHECK(earliest_toi <= earliest_hi);
    CHECK(earliest_toi >= earliest_lo - 1e-6);
    INFO("exact earliest contact in [" << std::setprecision(17) << earliest_lo << ", " << earliest_hi << "]");
    CHECK(scene.earliest >= earliest_lo - scene.digits);
    CHECK(scene.earliest <= earliest_hi + scene.digits);

    // The earliest-impact search gives the same bounds, and the same answer on one thread.
    const clothcd::EarliestImpact earliest = detector.earliest_impact(frames.start.vertices, frames.end);
    CHECK(earliest.hit);
    CHECK(earliest.toi <= earliest_hi);
    CHECK(earliest.toi >= earliest_lo - 1e-6);
    clothcd::DetectorSettings one_thread;
    one_thread.parallel = false;
    clothcd::CollisionDetector serial(frames.start.faces, static_cast<int>(frames.start.vertex_count()), one_thread);
    CHECK(serial.earliest_impact(frames.start.vertices, frames.end).toi == earliest.toi);
  }
}
