// CollisionDetector and the CCD on query arrays for Python. detect(), the state queries and set_obstacle_positions()
// hand the (N, 3) float64 arrays to the detector as views of their memory (no copy here; the detector makes its one
// copy of the positions, as for a C++ caller), and detect(), earliest_impact() and the state queries run without the
// GIL, cancelled by Ctrl-C (KeyboardInterrupt).
#include <nanobind/stl/string.h>
#include <nanobind/stl/tuple.h>
#include <nanobind/stl/vector.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <thread>

#include "arrays.hpp"
#include "bindings.hpp"
#include "state_arrays.hpp"
#include "clothcd/ccd/ccd.hpp"
#include "clothcd/culling/network_culler.hpp"
#include "clothcd/detection/collision_detector.hpp"

namespace clothcd::python {
namespace {

HierarchyKind hierarchy_kind(const std::string& name) {
  if (name == "sphere-root-aabb") return HierarchyKind::SphereRootAabb;
  if (name == "aabb") return HierarchyKind::Aabb;
  if (name == "aabb-obb") return HierarchyKind::AabbObb;
  throw std::invalid_argument("unknown hierarchy '" + name + "' (sphere-root-aabb, aabb, aabb-obb)");
}

CullingMode culling_mode(const std::string& name) {
  if (name == "none") return CullingMode::None;
  if (name == "nonpenetration") return CullingMode::NonPenetration;
  if (name == "projection") return CullingMode::Projection;
  if (name == "filters") return CullingMode::Filters;
  if (name == "network") return CullingMode::Network;
  throw std::invalid_argument("unknown culling '" + name + "' (none, nonpenetration, projection, filters, network)");
}

ccd::CcdFilter ccd_filter(const std::string& name) {
  if (name == "none") return ccd::CcdFilter::None;
  if (name == "nonpenetration") return ccd::CcdFilter::NonPenetration;
  if (name == "projection") return ccd::CcdFilter::Projection;
  if (name == "combined") return ccd::CcdFilter::Combined;
  throw std::invalid_argument("unknown filter '" + name + "' (none, nonpenetration, projection, combined)");
}

Eigen::Isometry3d to_isometry(const DoubleArray& matrix, const char* what) {
  if (matrix.ndim() != 2 || matrix.shape(0) != 4 || matrix.shape(1) != 4)
    throw std::invalid_argument(std::string(what) + ": expected a (4, 4) rigid transform");
  Eigen::Isometry3d result;
  result.matrix() = Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(matrix.data());
  if (!result.matrix().allFinite()) throw std::invalid_argument(std::string(what) + ": non-finite entry");
  return result;
}

/// The detector, and where the positions of its last detect() call were read (what the tests check to see that
/// NumPy arrays reach the detector without a copy).
struct PyDetector {
  CollisionDetector detector;
  std::uintptr_t last_start = 0, last_end = 0;
};

/// Python's signal handlers run on the main thread while detect() is under way: the detector's cancel check, called by
/// the search's threads before each block, takes the GIL on the thread that called detect() (the main thread when
/// Ctrl-C is to reach it) at most every 50 ms and calls PyErr_CheckSignals; a handler that raises (KeyboardInterrupt)
/// cancels the call, and the raised exception is what Python sees. Cost: a clock read per block of pairs.
class SignalCheck {
 public:
  explicit SignalCheck(CollisionDetector& detector) : detector_(detector) {
    detector_.set_cancel_check([this] { return check(); });
  }
  ~SignalCheck() { detector_.set_cancel_check({}); }
  SignalCheck(const SignalCheck&) = delete;
  SignalCheck& operator=(const SignalCheck&) = delete;

  /// True when a signal handler raised an exception (then set as Python's error).
  [[nodiscard]] bool raised() const { return raised_.load(); }

 private:
  using Clock = std::chrono::steady_clock;
  static constexpr Clock::duration kPeriod = std::chrono::milliseconds(50);

  bool check() {
    if (raised_.load(std::memory_order_relaxed)) return true;
    if (std::this_thread::get_id() != caller_) return false;
    const Clock::time_point now = Clock::now();
    if (now - last_ < kPeriod) return false;
    last_ = now;
    nb::gil_scoped_acquire acquire;
    if (PyErr_CheckSignals() != 0) raised_.store(true);
    return raised_.load(std::memory_order_relaxed);
  }

  CollisionDetector& detector_;
  const std::thread::id caller_ = std::this_thread::get_id();
  Clock::time_point last_ = Clock::now();  // only the caller's thread reads and writes it
  std::atomic<bool> raised_{false};
};

/// `query()` on the detector without the GIL, cancelled by Ctrl-C: a signal handler's exception (KeyboardInterrupt)
/// is what Python sees.
template <class Query>
decltype(auto) run_cancellable(CollisionDetector& detector, Query query) {
  SignalCheck signals(detector);
  try {
    nb::gil_scoped_release release;
    return query();
  } catch (const DetectionCancelled&) {
    if (signals.raised()) throw nb::python_error();
    throw;
  }
}

/// The collisions as arrays: kind (0 vertex-face, 1 edge-edge), bodies (n, 4), vertices (n, 4), toi, parameters
/// (n, 2), normal (n, 3), conservative.
auto collision_arrays(const std::vector<Collision>& collisions) {
  const std::size_t n = collisions.size();
  std::vector<std::uint8_t> kind(n);
  std::vector<std::int32_t> bodies(4 * n), vertices(4 * n);
  std::vector<double> toi(n), parameters(2 * n), normal(3 * n);
  std::vector<std::uint8_t> conservative(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Collision& c = collisions[i];
    kind[i] = c.kind == PairKind::VertexFace ? 0 : 1;
    for (std::size_t k = 0; k < 4; ++k) {
      bodies[4 * i + k] = c.vertices[k].body;
      vertices[4 * i + k] = c.vertices[k].vertex;
    }
    toi[i] = c.toi;
    parameters[2 * i] = c.parameters[0];
    parameters[2 * i + 1] = c.parameters[1];
    for (std::size_t k = 0; k < 3; ++k) normal[3 * i + k] = c.normal[static_cast<Eigen::Index>(k)];
    conservative[i] = c.conservative ? 1 : 0;
  }
  return std::make_tuple(to_numpy(std::move(kind), {n}), to_numpy(std::move(bodies), {n, 4}),
                         to_numpy(std::move(vertices), {n, 4}), to_numpy(std::move(toi), {n}),
                         to_numpy(std::move(parameters), {n, 2}), to_numpy(std::move(normal), {n, 3}),
                         to_numpy(std::move(conservative), {n}));
}

}  // namespace

void bind_detection(nb::module_& m) {
  nb::class_<PyDetector>(m, "_CollisionDetector")
      .def(
          "__init__",
          [](PyDetector* self, const IntArray& faces, int vertex_count, const std::string& hierarchy,
             const std::string& culling, double thickness, bool self_collision, const std::string& model_path,
             int max_leaf_faces, bool parallel, bool reuse_unchanged, bool projection_normals, bool decide_exactly,
             long max_collisions) {
            DetectorSettings settings;
            settings.hierarchy = hierarchy_kind(hierarchy);
            settings.culling = culling_mode(culling);
            settings.thickness = thickness;
            settings.self_collision = self_collision;
            settings.max_leaf_faces = max_leaf_faces;
            settings.parallel = parallel;
            settings.reuse_unchanged = reuse_unchanged;
            settings.projection_normals = projection_normals;
            settings.decide_exactly = decide_exactly;
            settings.max_collisions = max_collisions;
            learning::attach_network_culler(settings, model_path);
            new (self) PyDetector{CollisionDetector(to_faces(faces, "faces"), vertex_count, settings)};
          },
          nb::arg("faces"), nb::arg("vertex_count"), nb::arg("hierarchy"), nb::arg("culling"), nb::arg("thickness"),
          nb::arg("self_collision"), nb::arg("model_path"), nb::arg("max_leaf_faces"), nb::arg("parallel"),
          nb::arg("reuse_unchanged"), nb::arg("projection_normals"), nb::arg("decide_exactly"),
          nb::arg("max_collisions"))
      .def(
          "add_obstacle",
          [](PyDetector& self, const DoubleArray& vertices, const IntArray& faces) {
            return self.detector.add_obstacle({to_vertices(vertices, "vertices"), to_faces(faces, "faces")});
          },
          nb::arg("vertices"), nb::arg("faces"))
      .def(
          "set_obstacle_transforms",
          [](PyDetector& self, int body, const DoubleArray& start, const DoubleArray& end) {
            self.detector.set_obstacle_transforms(body, to_isometry(start, "start"), to_isometry(end, "end"));
          },
          nb::arg("body"), nb::arg("start"), nb::arg("end"))
      .def(
          "set_obstacle_positions",
          [](PyDetector& self, int body, const PositionsArray& start, const PositionsArray& end) {
            self.detector.set_obstacle_positions(body, positions_view(start, "start"), positions_view(end, "end"));
          },
          nb::arg("body"), nb::arg("start"), nb::arg("end"))
      .def("obstacle_count", [](const PyDetector& self) { return self.detector.obstacle_count(); })
      .def(
          "detect",
          [](PyDetector& self, const PositionsArray& start, const PositionsArray& end) {
            const PositionsRef x0 = positions_view(start, "x0");
            const PositionsRef x1 = positions_view(end, "x1");
            self.last_start = reinterpret_cast<std::uintptr_t>(x0.data());
            self.last_end = reinterpret_cast<std::uintptr_t>(x1.data());
            return collision_arrays(run_cancellable(
                self.detector, [&]() -> const std::vector<Collision>& { return self.detector.detect(x0, x1); }));
          },
          nb::arg("x0"), nb::arg("x1"))
      .def(
          "earliest_impact",
          [](PyDetector& self, const PositionsArray& start, const PositionsArray& end) {
            const PositionsRef x0 = positions_view(start, "x0");
            const PositionsRef x1 = positions_view(end, "x1");
            const EarliestImpact earliest =
                run_cancellable(self.detector, [&] { return self.detector.earliest_impact(x0, x1); });
            const std::vector<Collision> pair = earliest.hit ? std::vector<Collision>{earliest.pair}
                                                             : std::vector<Collision>{};
            return std::make_tuple(earliest.toi, earliest.hit, earliest.windows, collision_arrays(pair));
          },
          nb::arg("x0"), nb::arg("x1"))
      .def(
          "proximity",
          [](PyDetector& self, const PositionsArray& positions, double distance) {
            const PositionsRef x = positions_view(positions, "x");
            return proximity_columns(run_cancellable(
                self.detector, [&]() -> const std::vector<Proximity>& { return self.detector.proximity(x, distance); }));
          },
          nb::arg("x"), nb::arg("distance"))
      .def(
          "minimum_distance",
          [](PyDetector& self, const PositionsArray& positions, double upper_bound) {
            const PositionsRef x = positions_view(positions, "x");
            const MinimumDistance minimum =
                run_cancellable(self.detector, [&] { return self.detector.minimum_distance(x, upper_bound); });
            const std::vector<Proximity> pair = minimum.found ? std::vector<Proximity>{minimum.pair}
                                                              : std::vector<Proximity>{};
            return std::make_tuple(minimum.found, minimum.distance, proximity_columns(pair));
          },
          nb::arg("x"), nb::arg("upper_bound"))
      .def(
          "intersections",
          [](PyDetector& self, const PositionsArray& positions) {
            const PositionsRef x = positions_view(positions, "x");
            return intersection_columns(run_cancellable(
                self.detector, [&]() -> const std::vector<FaceIntersection>& { return self.detector.intersections(x); }));
          },
          nb::arg("x"))
      .def(
          "is_intersection_free",
          [](PyDetector& self, const PositionsArray& positions) {
            const PositionsRef x = positions_view(positions, "x");
            return run_cancellable(self.detector, [&] { return self.detector.is_intersection_free(x); });
          },
          nb::arg("x"))
      .def("_last_detect_inputs",
           [](const PyDetector& self) { return std::make_tuple(self.last_start, self.last_end); },
           "Addresses of the x0 and x1 data the last detect() handed to the C++ detector.")
      .def("stats", [](const PyDetector& self) {
        const DetectionStats& s = self.detector.stats();
        nb::dict d;
        d["candidates_vertex_face"] = s.candidates_vertex_face;
        d["candidates_edge_edge"] = s.candidates_edge_edge;
        d["culled"] = s.culled;
        d["collisions"] = s.collisions;
        d["refit_ms"] = s.refit_ms;
        d["traversal_ms"] = s.traversal_ms;
        d["culling_ms"] = s.culling_ms;
        d["exact_ms"] = s.exact_ms;
        return d;
      });

  m.def(
      "_closest_feature_contacts",
      [](const nb::ndarray<const std::uint8_t, nb::c_contig, nb::device::cpu>& kind, const IntArray& bodies,
         const IntArray& vertices, const nb::ndarray<const double, nb::c_contig, nb::device::cpu>& distance,
         const nb::ndarray<const std::uint8_t, nb::c_contig, nb::device::cpu>& type) {
        return contact_columns(closest_feature_contacts(proximities_from_columns(kind, bodies, vertices, distance, type)));
      },
      nb::arg("kind"), nb::arg("bodies"), nb::arg("vertices"), nb::arg("distance"), nb::arg("type"));
  m.def(
      "_detect_loop_seconds",
      [](PyDetector& self, const std::vector<DoubleArray>& starts, const std::vector<DoubleArray>& ends) {
        if (starts.size() != ends.size()) throw std::invalid_argument("detect loop: as many starts as ends needed");
        std::vector<Vertices> x0, x1;
        for (std::size_t i = 0; i < starts.size(); ++i) {
          x0.push_back(to_vertices(starts[i], "x0"));
          x1.push_back(to_vertices(ends[i], "x1"));
        }
        nb::gil_scoped_release release;
        const auto begin = std::chrono::steady_clock::now();
        for (std::size_t i = 0; i < x0.size(); ++i) (void)self.detector.detect(x0[i], x1[i]);
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
      },
      nb::arg("detector"), nb::arg("starts"), nb::arg("ends"),
      "Benchmark peer of a Python loop over detect(): the same calls made from C++ on prepared Vertices; seconds.");
  m.def(
      "_ccd",
      [](const DoubleArray& queries, const std::string& kind, const std::string& filter, double thickness, bool exact) {
        if (queries.ndim() != 3 || queries.shape(1) != 8 || queries.shape(2) != 3)
          throw std::invalid_argument("ccd: expected queries of shape (N, 8, 3)");
        if (kind != "vf" && kind != "ee") throw std::invalid_argument("ccd: kind must be 'vf' or 'ee'");
        const std::size_t n = queries.shape(0);
        ccd::CcdSettings settings;
        settings.thickness = thickness;
        settings.decide_exactly = exact;
        const ccd::CcdFilter culling = ccd_filter(filter);
        // Each query is read from the array when it is needed: no copy of the whole batch.
        const PairKind pair_kind = kind == "vf" ? PairKind::VertexFace : PairKind::EdgeEdge;
        const double* p = queries.data();
        const auto query_at = [&](std::size_t i) {
          ccd::CcdQuery query;
          query.kind = pair_kind;
          for (std::size_t k = 0; k < 4; ++k) {
            query.start[k] = Eigen::Vector3d(p + 24 * i + 3 * k);
            query.end[k] = Eigen::Vector3d(p + 24 * i + 3 * (k + 4));
          }
          return query;
        };
        for (std::size_t i = 0; i < n; ++i) ccd::validate_query(query_at(i), settings);
        std::vector<std::uint8_t> hit(n), culled(n);
        std::vector<double> toi(n, 1.0);
        {
          nb::gil_scoped_release release;
          for (std::size_t i = 0; i < n; ++i) {
            const ccd::CcdQuery query = query_at(i);
            culled[i] = ccd::filter_culls(culling, query, settings) ? 1 : 0;
            if (culled[i]) continue;
            const ccd::CcdResult result = ccd::continuous_collision(query, settings);
            hit[i] = result.hit ? 1 : 0;
            toi[i] = result.toi;
          }
        }
        return std::make_tuple(to_numpy(std::move(hit), {n}), to_numpy(std::move(toi), {n}),
                               to_numpy(std::move(culled), {n}));
      },
      nb::arg("queries"), nb::arg("kind"), nb::arg("filter"), nb::arg("thickness"), nb::arg("exact"));
}

}  // namespace clothcd::python
