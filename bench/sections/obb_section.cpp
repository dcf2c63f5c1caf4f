// Section "obb": Jin et al. Table 1 and Figures 10-11. Construction time of (a) the vertex-covariance OBB, (b) the fast
// adaptive OBB and (c) the fast adaptive OBB of the simplified model (per update at a moving pose), and compactness:
// volume / our tight reference and / CGAL's optimal box, on the rabbit, cat, dinosaur and human; plus the bunny
// simplified at the paper's 20/40/80/90/99% levels, rendered.
#include <CGAL/Simple_cartesian.h>
#include <CGAL/optimal_bounding_box.h>

#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "../suite/bench_section.hpp"
#include "../suite/bench_util.hpp"
#include "../suite/charts.hpp"
#include "clothcd/geometry/convex_hull.hpp"
#include "clothcd/geometry/mesh_volume.hpp"
#include "clothcd/geometry/obb.hpp"
#include "clothcd/geometry/simple_bounds.hpp"
#include "clothcd/mesh/mesh_io.hpp"
#include "clothcd/mesh/model_catalog.hpp"
#include "clothcd/render/rasterizer.hpp"

namespace clothcd::bench {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;

// Table 1 of the paper (seconds, model not named): (a) plain OBB, (b) fast adaptive, (c) on the simplified model.
constexpr double kPaperPlain = 2.817, kPaperAdaptive = 1.554, kPaperSimplified = 0.997;

// Volume of CGAL's optimal oriented bounding box of the vertices.
double cgal_optimal_box_volume(const TriangleMesh& mesh) {
  std::vector<Kernel::Point_3> points;
  for (Eigen::Index i = 0; i < mesh.vertex_count(); ++i)
    points.emplace_back(mesh.vertices(i, 0), mesh.vertices(i, 1), mesh.vertices(i, 2));
  std::array<Kernel::Point_3, 8> corners;
  CGAL::oriented_bounding_box(points, corners, CGAL::parameters::use_convex_hull(true));
  TriangleMesh box;
  box.vertices.resize(8, 3);
  for (int i = 0; i < 8; ++i) {
    const Kernel::Point_3& c = corners[static_cast<std::size_t>(i)];
    box.vertices.row(i) << c.x(), c.y(), c.z();
  }
  box.faces = geometry::compute_convex_hull(box.vertices).faces;
  return std::abs(geometry::mesh_volume(box));
}

struct ModelRow {
  std::string model;
  long faces = 0;
  double model_volume = 0, tight = 0, cgal = 0;
  double aabb = 0, covariance = 0, paper_b = 0, refined_b = 0, paper_c = 0, refined_c = 0;  // volumes
  double t_covariance = 0, t_paper_b = 0, t_refined_b = 0, t_paper_c = 0, t_refined_c = 0, t_once = 0;  // ms
  double t_tight = 0, t_cgal = 0;
};

// (c): the simplification once, then the per-update box at a pose turning by 0.01 rad per step about y.
double per_update_ms(geometry::SimplifiedObb& builder, int runs) {
  int step = 0;
  return median_ms(runs, [&] {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.rotate(Eigen::AngleAxisd(0.01 * step++, Eigen::Vector3d::UnitY()));
    (void)builder.update(pose);
  });
}

ModelRow measure_model(const std::string& name, const BenchContext& context) {
  const TriangleMesh mesh = load_mesh(fetch_model(name, context.obstacle_model_dir));
  const int runs = context.quick ? 3 : 31;
  ModelRow r;
  r.model = name;
  r.faces = static_cast<long>(mesh.face_count());
  r.model_volume = std::abs(geometry::mesh_volume(mesh));
  geometry::Obb box;
  r.t_tight = time_ms([&] { box = geometry::compute_obb(mesh, geometry::ObbMethod::Tight); });
  r.tight = box.volume();
  r.t_cgal = time_ms([&] { r.cgal = cgal_optimal_box_volume(mesh); });
  geometry::Aabb aabb = geometry::compute_aabb(mesh.vertices);
  r.aabb = aabb.volume();
  r.t_covariance = median_ms(runs, [&] { box = geometry::compute_obb(mesh, geometry::ObbMethod::Covariance); });
  r.covariance = box.volume();
  geometry::ObbSettings paper;
  paper.refine_axes = false;
  r.t_paper_b = median_ms(runs, [&] { box = geometry::compute_obb(mesh, geometry::ObbMethod::FastAdaptive, paper); });
  r.paper_b = box.volume();
  r.t_refined_b = median_ms(runs, [&] { box = geometry::compute_obb(mesh, geometry::ObbMethod::FastAdaptive); });
  r.refined_b = box.volume();
  std::unique_ptr<geometry::SimplifiedObb> builder;
  r.t_once = time_ms([&] { builder = std::make_unique<geometry::SimplifiedObb>(mesh, paper); });
  r.t_paper_c = per_update_ms(*builder, runs);
  r.paper_c = builder->update(Eigen::Isometry3d::Identity()).volume();
  builder = std::make_unique<geometry::SimplifiedObb>(mesh);
  r.t_refined_c = per_update_ms(*builder, runs);
  r.refined_c = builder->update(Eigen::Isometry3d::Identity()).volume();
  return r;
}

// Figure 10: the bunny and its simplified models; returns the Markdown rows (level, faces, box volume ratio).
std::vector<std::vector<std::string>> render_simplification_levels(const BenchContext& context,
                                                                   const std::filesystem::path& png) {
  const TriangleMesh rabbit = load_mesh(fetch_model("rabbit", context.obstacle_model_dir));
  const geometry::Obb full = geometry::compute_obb(rabbit, geometry::ObbMethod::FastAdaptive);
  const geometry::Aabb box = geometry::compute_aabb(rabbit.vertices);
  render::Camera camera = render::frame_box(box.min, box.max);
  camera.fov_degrees *= 0.75;  // closer framing: the model fills its cell
  render::RenderSettings settings;
  settings.width = 200;
  settings.height = 150;
  std::vector<render::Image> images{render::render({{&rabbit, {0.85, 0.75, 0.6}}}, camera, settings)};
  std::vector<std::vector<std::string>> rows{
      {"original", std::to_string(rabbit.face_count()), "1.000", "-"}};
  CsvFile csv(context.out_dir / "obb_simplified_levels.csv",
              "simplified_pct,faces,box_volume_ratio_to_full_model_box,simplification_ms");
  for (const double removed : {20.0, 40.0, 80.0, 90.0, 99.0}) {
    geometry::ObbSettings obb;
    obb.simplify_ratio = 1.0 - removed / 100.0;
    std::unique_ptr<geometry::SimplifiedObb> builder;
    const double ms = time_ms([&] { builder = std::make_unique<geometry::SimplifiedObb>(rabbit, obb); });
    const double ratio = builder->update(Eigen::Isometry3d::Identity()).volume() / full.volume();
    const TriangleMesh& simplified = builder->simplified();
    images.push_back(render::render({{&simplified, {0.85, 0.75, 0.6}}}, camera, settings));
    rows.push_back({number(removed, 3) + "%", std::to_string(simplified.face_count()), fixed(ratio, 3), number(ms, 4)});
    csv.row({number(removed, 3), std::to_string(simplified.face_count()), number(ratio, 5), number(ms, 5)});
  }
  render::write_png(render::contact_sheet(images, 3), png);
  return rows;
}

SectionReport run_obb(const BenchContext& context) {
  const std::vector<std::string> models =
      context.quick ? std::vector<std::string>{"cat", "dinosaur"}
                    : std::vector<std::string>{"rabbit", "cat", "dinosaur", "human"};
  std::vector<ModelRow> rows;
  for (std::size_t i = 0; i < models.size(); ++i) {
    context.progress(std::to_string(i + 1) + "/" + std::to_string(models.size() + 1) + " " + models[i] +
                     ": OBB methods, tight reference, CGAL optimal box");
    rows.push_back(measure_model(models[i], context));
  }
  context.progress(std::to_string(models.size() + 1) + "/" + std::to_string(models.size() + 1) +
                   " bunny simplified at 20/40/80/90/99%, rendered");
  const auto levels = render_simplification_levels(context, context.out_dir / "obb_simplified_bunny.png");

  CsvFile csv(context.out_dir / "obb.csv",
              "model,faces,method,time_ms,once_ms,volume,tau,ratio_to_tight,ratio_to_cgal_optimal");
  std::vector<std::vector<std::string>> time_rows{{"paper (model not named)", "-", number(1000 * kPaperPlain, 4),
                                                   number(1000 * kPaperAdaptive, 4), "-",
                                                   number(1000 * kPaperSimplified, 4), "-", "-",
                                                   number(kPaperPlain / kPaperAdaptive, 3),
                                                   number(kPaperPlain / kPaperSimplified, 3), "-"}};
  std::vector<std::vector<std::string>> fit_rows;
  std::vector<std::vector<double>> fit_chart, time_chart{{1.0, kPaperAdaptive / kPaperPlain,
                                                          kPaperSimplified / kPaperPlain}};
  double worst_refined = 0, worst_paper_c = 0, best_speedup = 0, worst_speedup = 1e300;
  double best_b = 0, worst_b = 1e300;  // (a) / (b) eqs. 11-18
  for (const ModelRow& r : rows) {
    struct Method {
      const char* name;
      double time, once, volume;
    };
    const Method methods[] = {{"aabb", 0, 0, r.aabb},
                              {"(a) covariance", r.t_covariance, 0, r.covariance},
                              {"(b) adaptive, eqs. 11-18", r.t_paper_b, 0, r.paper_b},
                              {"(b) adaptive + refine", r.t_refined_b, 0, r.refined_b},
                              {"(c) simplified, eqs. 11-18", r.t_paper_c, r.t_once, r.paper_c},
                              {"(c) simplified + refine", r.t_refined_c, 0, r.refined_c},
                              {"tight (ours)", r.t_tight, 0, r.tight},
                              {"cgal optimal", r.t_cgal, 0, r.cgal}};
    for (const Method& m : methods)
      csv.row({r.model, std::to_string(r.faces), csv_text(m.name), number(m.time, 5), number(m.once, 5),
               number(m.volume, 6), number(m.volume / r.model_volume, 5), number(m.volume / r.tight, 5),
               number(m.volume / r.cgal, 5)});
    time_rows.push_back({r.model, std::to_string(r.faces), number(r.t_covariance, 3), number(r.t_paper_b, 3),
                         number(r.t_refined_b, 3), number(r.t_paper_c, 3), number(r.t_refined_c, 3),
                         number(r.t_once, 4), number(r.t_covariance / r.t_paper_b, 3),
                         number(r.t_covariance / r.t_paper_c, 3), number(r.t_covariance / r.t_refined_c, 3)});
    fit_rows.push_back({r.model, fixed(r.tight / r.model_volume, 3), fixed(r.aabb / r.tight, 3),
                        fixed(r.covariance / r.tight, 3), fixed(r.paper_b / r.tight, 3),
                        fixed(r.refined_b / r.tight, 3),
                        fixed(r.paper_c / r.tight, 3), fixed(r.refined_c / r.tight, 3), fixed(r.cgal / r.tight, 3)});
    fit_chart.push_back({r.aabb / r.tight, r.covariance / r.tight, r.paper_b / r.tight, r.refined_b / r.tight,
                         r.paper_c / r.tight, r.refined_c / r.tight});
    time_chart.push_back({1.0, r.t_paper_b / r.t_covariance, r.t_paper_c / r.t_covariance});
    worst_refined = std::max(worst_refined, r.refined_c / r.tight);
    worst_paper_c = std::max(worst_paper_c, r.paper_c / r.tight);
    best_speedup = std::max(best_speedup, r.t_covariance / r.t_paper_c);
    worst_speedup = std::min(worst_speedup, r.t_covariance / r.t_paper_c);
    best_b = std::max(best_b, r.t_covariance / r.t_paper_b);
    worst_b = std::min(worst_b, r.t_covariance / r.t_paper_b);
  }
  std::vector<std::string> model_names;
  for (const ModelRow& r : rows) model_names.push_back(r.model);
  BarChart figure11;
  figure11.text = {"Figure 11: box volume / tight box volume (clipped at 1.4)", "obstacle model",
                   "volume / tight volume (ratio)", ""};
  figure11.categories = model_names;
  figure11.series = {"AABB", "(a) covariance", "(b) eqs. 11-18", "(b) + refine", "(c) eqs. 11-18", "(c) + refine"};
  figure11.values = fit_chart;
  figure11.y = {1.0, 1.4};
  write_bar_chart_svg((context.out_dir / "obb_tightness.svg").string(), figure11);
  BarChart table1;
  table1.text = {"Table 1: OBB build time relative to (a)", "obstacle model (paper: the paper's own ratios)",
                 "time / (a)'s time (ratio)", ""};
  table1.categories = {"paper"};
  table1.categories.insert(table1.categories.end(), model_names.begin(), model_names.end());
  table1.series = {"(a) covariance", "(b) eqs. 11-18", "(c) eqs. 11-18 per update"};
  table1.values = time_chart;
  write_bar_chart_svg((context.out_dir / "obb_time.svg").string(), table1);

  const int runs = context.quick ? 3 : 31;
  std::string md = "## OBB construction and compactness (Table 1, Figures 10-11)\n\n";
  md += "Methods: (a) vertex-covariance OBB; (b) the fast adaptive OBB, exactly eqs. 11-18 and with our per-axis "
        "minimum-area-rectangle refinement; (c) (b) on the QEM model simplified to 10% (the paper's 90%), per update "
        "at "
        "a moving pose (the simplification is done once, column *once*). Time: median of " +
        std::to_string(runs) + " builds, one thread, ms.\n\n### Table 1: construction time\n\n";
  md += markdown_table({"model", "faces", "(a) ms", "(b) eqs. ms", "(b) + refine ms", "(c) eqs. ms",
                        "(c) + refine ms", "(c) once ms", "(a) / (b)", "(a) / (c) eqs.", "(a) / (c) + refine"},
                       time_rows);
  md += "\nThe paper's (c) is " + number(kPaperPlain / kPaperSimplified, 3) + "x faster than (a); ours is " +
        number(worst_speedup, 3) + "x to " + number(best_speedup, 3) + "x with eqs. 11-18 (" +
        (worst_speedup >= kPaperPlain / kPaperSimplified ? "**reproduced**" : "**not reproduced** on every model") +
        "). The paper's (b) is " + number(kPaperPlain / kPaperAdaptive, 3) + "x faster than (a); ours is " +
        number(worst_b, 3) + "x to " + number(best_b, 3) + "x (" +
        (worst_b >= kPaperPlain / kPaperAdaptive ? "**reproduced**" : "**not reproduced**") +
        ": area weights, slabs and the triangles' covariance cost more than (a)'s plain vertex covariance). Our (a) "
        "is a "
        "two-pass O(#V) loop taking well under a millisecond, so there is far less to save than in the "
        "paper's 2.8 s; the paper's absolute times (seconds) are not comparable. (a) and (b) are timed through "
        "compute_obb, which first checks its input (finite coordinates, face indices: about a third of (a)'s time); "
        "(c) per update checks nothing (its model was checked once, when simplified).\n\n";
  md += "![Build time relative to (a)](obb_time.svg)\n\n";
  md += "### Figure 11: compactness\n\nBox volume / our tight reference (tau = tight box volume / model volume, the "
        "paper's measure, in the second column). The paper reports (c) as \"not as compact as the minimum-volume OBB, "
        "but the difference negligible\" without numbers.\n\n";
  md += markdown_table({"model", "tau tight", "AABB", "(a)", "(b) eqs.", "(b) + refine", "(c) eqs.", "(c) + refine",
                        "CGAL optimal"},
                       fit_rows);
  md += "\n(c) + refine stays within " + fixed(worst_refined, 3) + "x of the tight box (target 1.10: " +
        (worst_refined <= 1.10 ? "**met**" : "**missed**") + "); the paper's eqs. 11-18 alone reach " +
        fixed(worst_paper_c, 3) + "x" + (worst_paper_c > 1.10 ? " (the negligible difference is **not reproduced** "
                                                                  "without the refinement)" : "") + ".\n\n";
  md += "![Volume / tight volume](obb_tightness.svg)\n\n";
  md += "### Figure 10: the bunny simplified\n\nBox (c) + refine of each simplified model (grown to bound the "
        "original) "
        "/ box (b) + refine of the full model:\n\n";
  md += markdown_table({"simplified", "faces", "box volume ratio", "simplification ms"}, levels);
  md += "\n![The bunny simplified](obb_simplified_bunny.png)\n\n*obb_simplified_bunny.png: original, then 20, 40, 80, "
        "90 and 99% simplified.*\n";
  return {md, {"obb.csv", "obb_simplified_levels.csv", "obb_time.svg", "obb_tightness.svg",
               "obb_simplified_bunny.png"}};
}

const SectionRegistrar registrar{
    {20, "obb", "Table 1, Figures 10-11: OBB construction time and compactness on rabbit, cat, dinosaur, human",
     run_obb}};

}  // namespace
}  // namespace clothcd::bench
