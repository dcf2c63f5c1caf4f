// Section "scale": whole detection on real and generated steps of millions of candidate pairs, each step run by
// `clothcd detect T0 T1` in a child process, in the new default mode (exact decisions) on one CPU and on two and in
// the old default (approximate) on one CPU (stage times, peak resident memory, a digest of the collisions, false
// reports by the exact rational reference), beside the IPC Toolkit (the `ipctk` wheel, in a Python environment the
// section creates under .cache/bench-venv) on the same frames in the same run: its LBVH candidate search and its
// Tight-Inclusion narrow phase on those candidates; with the targets of the scaling and exact-default issues as rows.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "../suite/bench_section.hpp"
#include "../suite/bench_util.hpp"
#include "../suite/charts.hpp"
#include "../suite/child_process.hpp"
#include "../suite/detect_run.hpp"
#include "../suite/false_reports.hpp"
#include "../suite/ipctk_peer.hpp"
#include "../suite/thrown_bodies.hpp"
#include "clothcd/mesh/mesh_frames.hpp"
#include "clothcd/mesh/mesh_io.hpp"

namespace clothcd::bench {
namespace {

namespace fs = std::filesystem;

constexpr long kMillion = 1000000;
constexpr long kHugeCandidates = 30 * kMillion;  // the memory target's size of step
constexpr double kMemoryTargetMb = 256;
constexpr double kSpeedupTarget = 1.8;
constexpr double kExactUsPerPairTarget = 0.8;  // exact stage, per pair reaching it
// Reported collisions of a generated step checked by the exact reference (GMP, tens of microseconds each): an evenly
// spaced sample of at most this many per mode; the shared steps are checked in full.
constexpr std::size_t kGeneratedChecks = 2000;

// The rows of a Markdown table.
using Rows = std::vector<std::vector<std::string>>;

// One step to measure: its frames on disk and what is known about it.
struct Scene {
  std::string name;
  fs::path t0, t1;
  std::optional<fs::path> truth;
  long vertices = 0, faces = 0;
  bool generated = false;
};

// Everything measured on one step.
struct SceneResult {
  Scene scene;
  // Best whole-detection run of the new default (exact decisions) on one and on two CPUs (two.candidates == 0: not
  // run), and of the old default (approximate) on one CPU.
  DetectRun one, two, approximate;
  double peak_rss_one = 0, peak_rss_two = 0;
  bool same_collisions = true;  // every run of a mode, one CPU or two, gave that mode's digest
  std::optional<TruthCheck> truth, approximate_truth;
  FalseReportCheck false_reports, approximate_false_reports;  // of one / approximate
  std::optional<PeerCandidateSearch> peer_one, peer_two;
  // Best earliest-impact search (clothcd detect --earliest, new default) on one and on two CPUs.
  std::optional<EarliestRun> earliest_one, earliest_two;
  std::optional<PeerNarrowPhase> peer_narrow;
  FalseReportCheck peer_false_reports;
  std::optional<TruthCheck> peer_truth;
};

// The programs a step is measured with.
struct Programs {
  fs::path clothcd;                            ///< clothcd, for `clothcd detect`.
  std::vector<std::string> exact_flags;        ///< Its flags for the new default (exact decisions).
  std::vector<std::string> approximate_flags;  ///< Its flags for the old default (approximate).
  std::optional<fs::path> python;              ///< The peer's Python, when it imports ipctk.
  std::string peer_status;                     ///< The peer's version, or why it is not run.
  fs::path peer_script;                        ///< bench/peers/ipctk_candidates.py.
  fs::path narrow_phase_script;                ///< bench/peers/ipctk_narrow_phase.py.
  bool earliest = false;                       ///< clothcd detect has --earliest.
};

// What the section's tables read: how the steps were measured and what was measured on each.
struct ScaleRun {
  Programs programs;
  int rounds = 1;                    // rounds of clothcd detect and the peer's candidate search per step
  std::vector<SceneResult> results;  // one per step, in the order they were measured
  double reference_ms = 0;           // the exact reference's time over every check of every step
  double peer_narrow_ms = 0;         // the peer's narrow phase over every step
};

// The generated steps: `quick` one small one; else from about 1M to 30M+ candidate pairs, the two largest (minutes
// and gigabytes at present) only when the section runs alone.
std::vector<ThrownBodiesSpec> generated_specs(const BenchContext& context) {
  if (context.quick) return {{"thrown-8-small", 8, 8, 1.0, 1}};
  std::vector<ThrownBodiesSpec> specs{{"thrown-8", 8, 14, 1.0, 1}, {"thrown-16", 16, 16, 1.0, 2}};
  if (context.part_of_all) return specs;
  specs.push_back({"thrown-32", 32, 18, 1.0, 3});
  specs.push_back({"thrown-64", 64, 17, 1.0, 4});
  return specs;
}

// The clothcd program to measure: --clothcd, else the one beside this program. Throws std::runtime_error when it
// cannot be run, or when the run is not made inside the repository (the peer's scripts are in bench/peers).
fs::path measured_clothcd(const BenchContext& context) {
  const fs::path clothcd = context.clothcd_program.empty()
                               ? fs::read_symlink("/proc/self/exe").parent_path() / "clothcd"
                               : fs::absolute(context.clothcd_program);
  if (access(clothcd.c_str(), X_OK) != 0) throw std::runtime_error("cannot run " + clothcd.string());
  if (context.repository.empty())
    throw std::runtime_error("scale: run clothcd bench inside the repository (its peer scripts are in bench/peers)");
  return clothcd;
}

// The steps to measure: the shared real steps when present (cloth-funnel alone in a quick run), then the generated
// ones, written into `scratch` as PLY frames.
std::vector<Scene> scenes_to_measure(const BenchContext& context, const fs::path& scratch) {
  std::vector<Scene> scenes;
  if (context.scalable_ccd) {
    for (const char* name : {"cloth-funnel", "rod-twist"}) {
      const fs::path dir = *context.scalable_ccd / name;
      if (context.quick && std::string(name) == "rod-twist") continue;
      if (fs::exists(dir / "t0.ply")) scenes.push_back({name, dir / "t0.ply", dir / "t1.ply", dir / "truth.json"});
    }
  }
  for (const ThrownBodiesSpec& spec : generated_specs(context)) {
    context.progress("generating " + spec.name);
    const ThrownBodiesStep step = make_thrown_bodies(spec);
    Scene scene;
    scene.name = spec.name;
    scene.t0 = scratch / (spec.name + "-t0.ply");
    scene.t1 = scratch / (spec.name + "-t1.ply");
    scene.generated = true;
    save_mesh(step.start, scene.t0);
    save_mesh({step.end, step.start.faces}, scene.t1);
    scenes.push_back(scene);
  }
  return scenes;
}

// `clothcd` with its flags for either mode and its searches, and the peer: its Python (its environment created on
// first use) and its scripts in the repository's bench/peers.
Programs measuring_programs(const BenchContext& context, const fs::path& clothcd) {
  const fs::path peers = context.repository / "bench" / "peers";
  Programs programs;
  programs.clothcd = clothcd;
  programs.exact_flags = detect_mode_flags(clothcd, DetectMode::Exact);
  programs.approximate_flags = detect_mode_flags(clothcd, DetectMode::Approximate);
  programs.peer_script = peers / "ipctk_candidates.py";
  programs.python = peer_python(context, programs.peer_script, programs.peer_status);
  programs.narrow_phase_script = peers / "ipctk_narrow_phase.py";
  programs.earliest = detect_has_earliest(clothcd);
  return programs;
}

// Keeps the faster of `best` and `run`, and the larger peak memory; notes the run's digest.
void keep_best(std::optional<DetectRun>& best, DetectRun run, double& peak_rss, std::vector<std::string>& digests) {
  peak_rss = std::max(peak_rss, run.peak_rss_mb);
  digests.push_back(run.digest);
  if (!best || run.whole_ms() < best->whole_ms()) best = std::move(run);
}

// Keeps the faster of `best` and `run`.
void keep_best(std::optional<EarliestRun>& best, const EarliestRun& run) {
  if (!best || run.whole_ms() < best->whole_ms()) best = run;
}

// Keeps the faster of `best` and `run`.
void keep_best(std::optional<PeerCandidateSearch>& best, const PeerCandidateSearch& run) {
  if (!best || run.ms < best->ms) best = run;
}

// `repeats` rounds, each running clothcd detect in the old default on one CPU, in the new default on one CPU and on
// two, and the peer's candidate search on one and on two in turn (so a change of the shared machine's load affects
// them all alike); the best time of each over the rounds.
SceneResult measure_scene(const BenchContext& context, const Scene& scene, const fs::path& peer_file,
                          const Programs& programs, int repeats, bool two_cpus) {
  SceneResult result;
  result.scene = scene;
  std::optional<DetectRun> one, two, approximate;
  std::vector<std::string> digests, approximate_digests;
  double approximate_rss = 0;
  const fs::path collisions = peer_file.parent_path() / "collisions.json";
  for (int round = 1; round <= repeats; ++round) {
    context.progress(scene.name + " (" + std::to_string(scene.faces) + " faces): round " + std::to_string(round) +
                     " of " + std::to_string(repeats) + (programs.python ? ", clothcd detect and ipctk" : ""));
    keep_best(approximate, run_detect(programs.clothcd, scene.t0, scene.t1, collisions, 1, programs.approximate_flags),
              approximate_rss, approximate_digests);
    keep_best(one, run_detect(programs.clothcd, scene.t0, scene.t1, collisions, 1, programs.exact_flags),
              result.peak_rss_one, digests);
    if (two_cpus)
      keep_best(two, run_detect(programs.clothcd, scene.t0, scene.t1, collisions, 2, programs.exact_flags),
                result.peak_rss_two, digests);
    if (programs.earliest) {
      keep_best(result.earliest_one, run_earliest(programs.clothcd, scene.t0, scene.t1, collisions, 1));
      if (two_cpus) keep_best(result.earliest_two, run_earliest(programs.clothcd, scene.t0, scene.t1, collisions, 2));
    }
    if (!programs.python) continue;
    keep_best(result.peer_one, run_peer_candidates(*programs.python, programs.peer_script, peer_file, 1));
    if (two_cpus) keep_best(result.peer_two, run_peer_candidates(*programs.python, programs.peer_script, peer_file, 2));
  }
  result.one = *one;
  result.approximate = *approximate;
  if (two) result.two = *two;
  const auto alike = [](const std::vector<std::string>& d) {
    return std::all_of(d.begin(), d.end(), [&](auto& digest) { return digest == d[0]; });
  };
  result.same_collisions = alike(digests) && alike(approximate_digests);
  if (scene.truth) {
    result.truth = check_truth(*scene.truth, result.one.collisions);
    result.approximate_truth = check_truth(*scene.truth, result.approximate.collisions);
  }
  return result;
}

// The peer's narrow phase on the step in `peer_file`: batch, and on a shared step also one candidate at a time (the
// Python pass, tens of microseconds a candidate), those hits checked like ours; adds its time and the reference's to
// `run`.
void measure_peer_narrow_phase(const BenchContext& context, const MeshFrames& frames, const fs::path& peer_file,
                               SceneResult& result, ScaleRun& run) {
  const Scene& scene = result.scene;
  context.progress(scene.name + ": the peer's Tight-Inclusion narrow phase" +
                   (scene.generated ? "" : ", batch and one candidate at a time"));
  run.peer_narrow_ms += time_ms([&] {
    result.peer_narrow = run_peer_narrow_phase(*run.programs.python, run.programs.narrow_phase_script, peer_file,
                                               peer_file.parent_path() / "peer-hits.txt", !scene.generated, 1);
  });
  if (!result.peer_narrow->per_pair) return;
  result.peer_false_reports = check_false_reports(frames, result.peer_narrow->hits, SIZE_MAX);
  run.reference_ms += result.peer_false_reports.ms;
  if (scene.truth) result.peer_truth = check_truth(*scene.truth, result.peer_narrow->hits);
}

// Measures one step (measure_scene), checks what either mode reported with the exact reference (all of it on a shared
// step, a sample on a generated one) and runs the peer's narrow phase on it; adds the result to `run`.
void measure_step(const BenchContext& context, Scene scene, const fs::path& scratch, bool two_cpus, ScaleRun& run) {
  const MeshFrames frames = load_mesh_frames(scene.t0, scene.t1);
  scene.vertices = static_cast<long>(frames.start.vertex_count());
  scene.faces = static_cast<long>(frames.start.face_count());
  const fs::path peer_file = scratch / "peer-scene.bin";
  if (run.programs.python) write_peer_scene(frames, peer_file);
  SceneResult result = measure_scene(context, scene, peer_file, run.programs, run.rounds, two_cpus);
  context.progress(scene.name + ": false reports by the exact reference");
  const std::size_t checks = scene.generated ? kGeneratedChecks : SIZE_MAX;
  result.false_reports = check_false_reports(frames, result.one.collisions, checks);
  result.approximate_false_reports = check_false_reports(frames, result.approximate.collisions, checks);
  run.reference_ms += result.false_reports.ms + result.approximate_false_reports.ms;
  if (run.programs.python) measure_peer_narrow_phase(context, frames, peer_file, result, run);
  run.results.push_back(std::move(result));
}

// Every step measured in turn with `programs`, in one round in a quick run, else three.
ScaleRun measure_scenes(const BenchContext& context, const std::vector<Scene>& scenes, const Programs& programs,
                        const fs::path& scratch) {
  ScaleRun run;
  run.programs = programs;
  run.rounds = context.quick ? 1 : 3;
  const bool two_cpus = have_cpus(2);
  for (const Scene& scene : scenes) measure_step(context, scene, scratch, two_cpus, run);
  return run;
}

std::string verdict(bool met) {
  return met ? "met" : "**missed**";
}

// Pairs that reach the exact stage (candidates the culling stage kept).
long reaching(const DetectRun& run) {
  return run.candidates - run.culled;
}

// Exact-stage time per pair reaching it, in microseconds.
double us_per_pair(const DetectRun& run) {
  return 1e3 * run.exact_ms / static_cast<double>(std::max(1L, reaching(run)));
}

// Time per candidate pair, in nanoseconds.
double ns_per_candidate(double milliseconds, long candidates) {
  return 1e6 * milliseconds / static_cast<double>(std::max(1L, candidates));
}

// The new default was also run on two CPUs.
bool ran_on_two_cpus(const SceneResult& r) {
  return r.two.candidates > 0;
}

// "n" when every reported collision was checked, "n of k checked" for a sample.
std::string false_count(const FalseReportCheck& check) {
  return std::to_string(check.not_colliding) + (check.complete() ? ""
                                                                 : " (" + std::to_string(check.checked) + " of " +
                                                                       std::to_string(check.reported) + " checked)");
}

std::string mb(double value) {
  return fixed(value, 1) + " MB";
}

std::string ms(double value) {
  return number(value, 4) + " ms";
}

std::string join_flags(const std::vector<std::string>& flags) {
  std::string text;
  for (const std::string& flag : flags) text += (text.empty() ? "" : " ") + flag;
  return text.empty() ? "none" : text;
}

// One step's row of scale.csv (the header in write_scale_csv).
std::vector<std::string> scale_csv_row(const SceneResult& r) {
  const double whole = r.one.whole_ms(), per = ns_per_candidate(whole, r.one.candidates);
  const bool has_two = ran_on_two_cpus(r);
  const double speedup = has_two ? whole / r.two.whole_ms() : 0;
  const double peer_ratio = r.peer_one ? r.peer_one->ms / whole : 0;
  const auto opt = [](bool has, double v, int digits) { return has ? number(v, digits) : std::string(); };
  const std::optional<PeerNarrowPhase>& narrow = r.peer_narrow;
  const bool per_pair = narrow && narrow->per_pair;
  return {r.scene.name,
          std::to_string(r.scene.vertices),
          std::to_string(r.scene.faces),
          std::to_string(r.one.candidates),
          number(r.one.refit_ms, 6),
          number(r.one.traversal_ms, 6),
          number(r.one.culling_ms, 6),
          number(r.one.exact_ms, 6),
          number(whole, 6),
          number(per, 4),
          opt(has_two, r.two.whole_ms(), 6),
          opt(has_two, speedup, 4),
          number(r.peak_rss_one, 5),
          opt(has_two, r.peak_rss_two, 5),
          std::to_string(r.one.collisions.size()),
          r.one.digest,
          r.same_collisions ? "yes" : "no",
          r.truth ? std::to_string(r.truth->listed) : "",
          r.truth ? std::to_string(r.truth->missed) : "",
          r.peer_one ? std::to_string(r.peer_one->candidates) : "",
          opt(r.peer_one.has_value(), r.peer_one ? r.peer_one->ms : 0, 6),
          opt(r.peer_two.has_value(), r.peer_two ? r.peer_two->ms : 0, 6),
          opt(r.peer_one.has_value(), peer_ratio, 4),
          std::to_string(reaching(r.one)),
          number(us_per_pair(r.one), 4),
          number(r.one.earliest_toi, 10),
          std::to_string(r.false_reports.not_colliding),
          std::to_string(r.false_reports.checked),
          number(r.approximate.exact_ms, 6),
          number(r.approximate.whole_ms(), 6),
          number(us_per_pair(r.approximate), 4),
          std::to_string(r.approximate.collisions.size()),
          std::to_string(r.approximate.conservative),
          number(r.approximate.earliest_toi, 10),
          std::to_string(r.approximate_false_reports.not_colliding),
          std::to_string(r.approximate_false_reports.checked),
          r.approximate_truth ? std::to_string(r.approximate_truth->missed) : "",
          r.approximate.digest,
          narrow ? number(narrow->stepsize_ms, 6) : "",
          narrow ? number(narrow->stepsize, 9) : "",
          per_pair ? std::to_string(narrow->hits.size()) : "",
          per_pair ? std::to_string(r.peer_false_reports.not_colliding) : "",
          r.peer_truth ? std::to_string(r.peer_truth->missed) : "",
          per_pair ? number(narrow->earliest_toi, 10) : "",
          per_pair ? std::to_string(narrow->clean_candidates) : "",
          per_pair ? number(narrow->clean_ms, 6) : "",
          per_pair ? number(narrow->loop_ms, 6) : "",
          r.earliest_one ? number(r.earliest_one->toi, 10) : "",
          r.earliest_one ? std::to_string(r.earliest_one->windows) : "",
          r.earliest_one ? std::to_string(r.earliest_one->candidates) : "",
          r.earliest_one ? number(r.earliest_one->whole_ms(), 6) : "",
          r.earliest_two ? number(r.earliest_two->whole_ms(), 6) : ""};
}

// scale.csv: every measure of every step, one row per step.
void write_scale_csv(const fs::path& path, const std::vector<SceneResult>& results) {
  CsvFile csv(path,
              "scene,vertices,faces,candidates,refit_ms,traversal_ms,culling_ms,exact_ms,whole_1t_ms,"
              "ns_per_candidate_1t,whole_2t_ms,speedup_2t,peak_rss_1t_mb,peak_rss_2t_mb,collisions,digest,"
              "same_collisions_all_runs,truth_pairs,truth_missed,ipctk_candidates,ipctk_1t_ms,ipctk_2t_ms,"
              "ipctk_1t_over_ours_1t,reaching_exact,exact_us_per_pair,earliest_toi,false_reports,false_checked,"
              "approx_exact_ms,approx_whole_1t_ms,approx_exact_us_per_pair,approx_collisions,approx_conservative,"
              "approx_earliest_toi,approx_false_reports,approx_false_checked,approx_truth_missed,approx_digest,"
              "ipctk_stepsize_ms,ipctk_stepsize,ipctk_hits,ipctk_false_positives,ipctk_truth_missed,"
              "ipctk_earliest_toi,ipctk_clean_candidates,ipctk_clean_ms,ipctk_loop_ms,earliest_search_toi,"
              "earliest_windows,earliest_candidates,earliest_1t_ms,earliest_2t_ms");
  for (const SceneResult& r : results) csv.row(scale_csv_row(r));
}

// The report's opening: how the steps were measured, what they are and what this run left out.
std::string scale_introduction(const BenchContext& context, const ScaleRun& run) {
  const Programs& programs = run.programs;
  std::string md = "## Scaling to large steps: generated and real steps against the IPC Toolkit\n\n";
  md +=
      "Each step is given to `clothcd detect T0 T1 --out FILE` (thickness 0, the default hierarchy and combined "
      "filters) as one multi-body mesh, in a child process pinned to one CPU (old default, then new default) and "
      "then to two (new default; TBB sizes its pool to them), then to the peer on one CPU and on two, in turn, " +
      std::to_string(run.rounds) +
      " rounds; best round of each by whole-detection time (build/refit + candidate search + culling + exact test, "
      "the detector's own stage times; loading excluded). Peak memory: the child's peak resident set (wait4), "
      "loading and writing the JSON included. Digest: FNV-1a over the sorted collisions (pairs, conservative flags, "
      "tois), to compare two detector versions bit for bit. Peer: " +
      (programs.python ? programs.peer_status +
                             ", `Candidates.build(mesh, V0, V1, 0.0, LBVH())` alone on the same positions, "
                             "`ipctk.set_num_threads` and the same CPU pinning, best round"
                       : programs.peer_status) +
      ". Generated steps: N bodies (UV spheres, cloth sheets, fish of about 1 unit) on a lattice of 1.5-unit "
      "cells, each thrown about a cell in a random direction with a turn (bench/suite/thrown_bodies.hpp; the same "
      "bits from the same seed), written as ASCII PLY.";
  if (context.scalable_ccd)
    md += " Real steps: rod-twist and cloth-funnel of " + context.scalable_ccd->filename().string() +
          " (real simulation steps with ground truth).";
  else
    md += " Real steps: not run (no ../shared/data/scalable-ccd-sample; see --scalable-ccd).";
  if (context.part_of_all && !context.quick)
    md +=
        " Part of `clothcd bench all`: the two largest generated steps (20M and 34M candidates) run only in "
        "`clothcd bench scale`.";
  if (!context.clothcd_program.empty()) md += " Detector measured: " + programs.clothcd.string() + " (`--clothcd`).";
  if (context.quick) md += " Quick run: small steps only, one run each, no peer set-up.";
  return md + "\n\n";
}

// One step's row of the detection table.
std::vector<std::string> detection_row(const SceneResult& r, const std::string& peer_status) {
  const double whole = r.one.whole_ms(), per = ns_per_candidate(whole, r.one.candidates);
  const bool has_two = ran_on_two_cpus(r);
  return {r.scene.name,
          std::to_string(r.scene.faces),
          std::to_string(r.one.candidates),
          fixed(r.one.refit_ms, 1) + " / " + fixed(r.one.traversal_ms, 1) + " / " + fixed(r.one.culling_ms, 1) + " / " +
              fixed(r.one.exact_ms, 1),
          ms(whole),
          fixed(per, 1),
          has_two ? ms(r.two.whole_ms()) : "-",
          has_two ? fixed(whole / r.two.whole_ms(), 2) + "x" : "-",
          fixed(r.peak_rss_one, 1) + (has_two ? " / " + fixed(r.peak_rss_two, 1) : "") + " MB",
          std::to_string(r.one.collisions.size()) + (r.same_collisions ? "" : " (**runs differ**)"),
          "`" + r.one.digest + "`",
          r.peer_one ? std::to_string(r.peer_one->candidates) : "-",
          r.peer_one ? ms(r.peer_one->ms) : peer_status,
          r.peer_two ? ms(r.peer_two->ms) : "-",
          r.peer_one ? fixed(r.peer_one->ms / whole, 2) : "-"};
}

// The new default's whole detection per step: stage times, one and two CPUs, memory, digest, beside the peer's
// candidate search.
std::string detection_table(const ScaleRun& run) {
  Rows rows;
  for (const SceneResult& r : run.results) rows.push_back(detection_row(r, run.programs.peer_status));
  return "The table's detector runs are the new default (exact decisions); the old default is compared below.\n\n" +
         markdown_table(
             {"step", "faces", "candidates", "ms build+refit / search / culling / exact (1 thread)", "whole, 1 thread",
              "ns / candidate", "whole, 2 threads", "2T speed-up", "peak RSS 1T / 2T", "collisions", "digest",
              "ipctk candidates", "ipctk, 1 thread", "ipctk, 2 threads", "ipctk 1T / ours 1T"},
             rows);
}

// The chart of whole detection per candidate pair (ours and the peer's, one and two threads) written to `svg`, and
// its place in the report.
std::string ns_per_candidate_chart(const fs::path& svg, const std::vector<SceneResult>& results) {
  BarChart chart;
  chart.text = {"Whole detection per candidate pair, per step", "step (scene)", "time per candidate pair (ns)", ""};
  chart.series = {"ours, one thread", "ours, two threads", "ipctk LBVH, one thread", "ipctk LBVH, two threads"};
  const double none = std::nan("");  // draws no bar
  std::string steps;
  for (const SceneResult& r : results) {
    chart.categories.push_back(r.scene.name);
    chart.values.push_back({ns_per_candidate(r.one.whole_ms(), r.one.candidates),
                            ran_on_two_cpus(r) ? ns_per_candidate(r.two.whole_ms(), r.one.candidates) : none,
                            r.peer_one ? ns_per_candidate(r.peer_one->ms, r.peer_one->candidates) : none,
                            r.peer_two ? ns_per_candidate(r.peer_two->ms, r.peer_one->candidates) : none});
    steps += (steps.empty() ? "" : ", ") + r.scene.name;
  }
  write_bar_chart_svg(svg.string(), chart);
  return "\n![ns per candidate pair, per step](" + svg.filename().string() + ")\n\n*Steps left to right: " + steps +
         "; ipctk per its own candidate count.*\n\n";
}

// The memory target: a row per step of at least 30M candidates, or one saying there is none.
void add_memory_targets(Rows& targets, const BenchContext& context, const std::vector<SceneResult>& results) {
  bool huge_seen = false;
  for (const SceneResult& r : results) {
    if (r.one.candidates < kHugeCandidates) continue;
    huge_seen = true;
    const double peak = std::max(r.peak_rss_one, r.peak_rss_two);
    targets.push_back({"peak resident memory of `clothcd detect`, " + r.scene.name, mb(peak), "-", "-",
                       "<= 256 MB at >= 30M candidates", verdict(peak <= kMemoryTargetMb)});
  }
  if (!huge_seen)
    targets.push_back({"peak resident memory of `clothcd detect` at >= 30M candidates", "no such step in this run", "-",
                       "-", "<= 256 MB",
                       context.part_of_all ? "not measured (`clothcd bench scale` runs it)" : "not measured"});
}

// Whole detection against the peer's candidate search alone, on the generated steps and rod-twist.
void add_peer_targets(Rows& targets, const std::vector<SceneResult>& results, const std::string& peer_status) {
  for (const SceneResult& r : results) {
    if (!r.scene.generated && r.scene.name != "rod-twist") continue;
    const std::string measure = "whole detection, one thread, " + r.scene.name;
    if (!r.peer_one) {
      targets.push_back({measure, ms(r.one.whole_ms()), peer_status, "-", "<= ipctk LBVH candidates", "-"});
      continue;
    }
    const double ratio = r.peer_one->ms / r.one.whole_ms();
    targets.push_back({measure, ms(r.one.whole_ms()), ms(r.peer_one->ms) + " (candidates alone, one thread)",
                       fixed(ratio, 2), "ipctk / ours >= 1", verdict(ratio >= 1)});
  }
}

// Two threads against one, on the steps of at least 1M candidates.
void add_two_thread_targets(Rows& targets, const std::vector<SceneResult>& results) {
  for (const SceneResult& r : results) {
    if (r.one.candidates < kMillion) continue;
    const std::string measure = "two threads against one, " + r.scene.name;
    if (!ran_on_two_cpus(r)) {
      targets.push_back({measure, "-", "-", "-", ">= 1.8x", "not measured (one CPU)"});
      continue;
    }
    const double speedup = r.one.whole_ms() / r.two.whole_ms();
    targets.push_back({measure, ms(r.two.whole_ms()) + " vs " + ms(r.one.whole_ms()), "-", fixed(speedup, 2) + "x",
                       ">= 1.8x", verdict(speedup >= kSpeedupTarget)});
  }
}

// One digest over every run of a step, and no ground-truth pair missed where the step has ground truth.
void add_collision_targets(Rows& targets, const std::vector<SceneResult>& results) {
  for (const SceneResult& r : results) {
    targets.push_back({"same collisions in every run (one and two threads), " + r.scene.name, "`" + r.one.digest + "`",
                       "-", "-", "one digest", verdict(r.same_collisions)});
    if (r.truth)
      targets.push_back({"ground-truth pairs missed, " + r.scene.name,
                         std::to_string(r.truth->missed) + " of " + std::to_string(r.truth->listed), "-", "-", "0",
                         verdict(r.truth->missed == 0)});
  }
}

// The scaling issue's targets, one row per step they apply to.
std::string scaling_targets_table(const BenchContext& context, const ScaleRun& run) {
  Rows targets;
  add_memory_targets(targets, context, run.results);
  add_peer_targets(targets, run.results, run.programs.peer_status);
  add_two_thread_targets(targets, run.results);
  add_collision_targets(targets, run.results);
  return "Targets of the scaling issue:\n\n" +
         markdown_table({"measure", "ours", "peer", "ratio", "target", "verdict"}, targets);
}

// One step's row of the table of the old default against the new.
std::vector<std::string> exact_modes_row(const SceneResult& r) {
  const auto pair_of = [](const std::string& a, const std::string& b) { return a + " / " + b; };
  const auto missed = [](const std::optional<TruthCheck>& t) { return t ? std::to_string(t->missed) : "-"; };
  return {r.scene.name,
          pair_of(std::to_string(reaching(r.approximate)), std::to_string(reaching(r.one))),
          pair_of(fixed(r.approximate.exact_ms, 1), fixed(r.one.exact_ms, 1)),
          pair_of(number(us_per_pair(r.approximate), 3), number(us_per_pair(r.one), 3)),
          pair_of(ms(r.approximate.whole_ms()), ms(r.one.whole_ms())),
          fixed(r.one.whole_ms() / r.approximate.whole_ms(), 3),
          pair_of(std::to_string(r.approximate.collisions.size()), std::to_string(r.one.collisions.size())),
          pair_of(std::to_string(r.approximate.conservative), std::to_string(r.one.conservative)),
          pair_of(false_count(r.approximate_false_reports), false_count(r.false_reports)),
          pair_of(missed(r.approximate_truth), missed(r.truth)),
          pair_of(number(r.approximate.earliest_toi, 9), number(r.one.earliest_toi, 9))};
}

// The old default (approximate) against the new (exact decisions) per step: the exact stage, reports, false reports.
std::string exact_modes_table(const ScaleRun& run) {
  Rows rows;
  for (const SceneResult& r : run.results) rows.push_back(exact_modes_row(r));
  return "\n### Exact decisions: old default, new default and the peer's narrow phase\n\n"
         "Old default: `clothcd detect` with the pieces the floating-point fast tier leaves undecided reported as "
         "`conservative` hits (flags: `" +
         join_flags(run.programs.approximate_flags) + "`); new default: every piece decided exactly (flags: `" +
         join_flags(run.programs.exact_flags) +
         "`); the flags are chosen from what the program's `detect --help` lists. Both on one CPU in the same rounds "
         "as above, best round each. *False reports*: reported collisions that the exact rational reference "
         "(`ccd::exact_collision_reference`, GMP, on the pair's two frames) says do not touch during the step; every "
         "one on the shared steps, an evenly spaced sample of at most " +
         std::to_string(kGeneratedChecks) + " per mode on the generated ones (" + fixed(run.reference_ms / 1000, 1) +
         " s of reference time in all). *Missed*: ground-truth pairs not reported.\n\n" +
         markdown_table(
             {"step", "pairs reaching the exact stage, old / new", "exact stage ms, old / new",
              "us per pair reaching it, old / new", "whole, 1 thread, old / new", "new / old", "reported, old / new",
              "conservative, old / new", "false reports, old / new", "missed, old / new", "earliest toi, old / new"},
             rows);
}

// How the peer's narrow phase was run and what its columns mean (or why it was not run).
std::string peer_narrow_phase_method(const ScaleRun& run) {
  const std::string& status = run.programs.peer_status;
  if (!run.programs.python) return status + ".";
  return status +
         " `TightInclusionCCD()` (its defaults: tolerance 1e-6, 1e7 iterations, conservative rescaling 0.8, which "
         "makes it report a pair that comes within min(0.2 x its initial distance, 1e-4) and rescales its toi by 0.8) "
         "at minimum distance 0, one thread, on its own LBVH candidates (`ipctk.Candidates.build`, inflation 0) of the "
         "same frames (bench/peers/ipctk_narrow_phase.py), after the rounds above. Timed inside C++, one run each (a "
         "decided pass over rod-twist's candidates takes about a minute): *batch* = "
         "`Candidates.compute_collision_free_stepsize` over every candidate (each search limited to the earliest toi "
         "found so far, so it is cheaper after a hit than a full decision); *decided* = "
         "`Candidates.is_step_collision_free` over the candidates without the peer's own hits (it stops at the first "
         "hit, so with none it decides every candidate; the hits' own cost is left out). Its hits are its per-pair CCD "
         "(`point_triangle_ccd` / `edge_edge_ccd`, called for every candidate from Python, shared steps only: tens of "
         "seconds on rod-twist, " +
         fixed(run.peer_narrow_ms / 1000, 1) +
         " s for the peer's narrow phase in all), checked like ours with the exact reference. Ours: the exact stage "
         "of the new default per pair reaching it (after the culling stage; the peer has no culling stage, so its "
         "candidates are all the pairs it decides). Peer whole = its LBVH candidates (one thread, above) + its "
         "decided (or batch) narrow phase.";
}

// One step's row of the peer's narrow phase against our exact stage (the step has peer_narrow).
std::vector<std::string> peer_narrow_phase_row(const SceneResult& r) {
  const PeerNarrowPhase& p = *r.peer_narrow;
  const double stepsize_ns = ns_per_candidate(p.stepsize_ms, p.candidates);
  const double clean_ns = ns_per_candidate(p.clean_ms, p.clean_candidates);
  const double ours_ns = 1e3 * us_per_pair(r.one);
  const double peer_whole = r.peer_one ? r.peer_one->ms + (p.per_pair ? p.clean_ms : p.stepsize_ms) : 0;
  const auto per_pair_only = [&](const std::string& text) { return p.per_pair ? text : "-"; };
  return {r.scene.name,
          std::to_string(p.candidates),
          number(stepsize_ns, 4) + " (" + fixed(p.stepsize_ms, 1) + " ms)",
          per_pair_only(number(clean_ns, 4) + " (" + fixed(p.clean_ms, 1) + " ms)"),
          per_pair_only(std::to_string(p.hits.size())),
          per_pair_only(std::to_string(r.peer_false_reports.not_colliding)),
          per_pair_only(std::to_string(r.false_reports.not_colliding) + " / " +
                        std::to_string(r.approximate_false_reports.not_colliding)),
          r.peer_truth ? std::to_string(r.peer_truth->missed) : "-",
          per_pair_only(number(p.earliest_toi, 9)),
          number(p.stepsize, 9),
          number(ours_ns, 4),
          fixed(ours_ns / (p.per_pair ? clean_ns : stepsize_ns), 3),
          r.peer_one ? ms(peer_whole) : "-",
          r.peer_one ? fixed(r.one.whole_ms() / peer_whole, 3) : "-"};
}

// The peer's narrow phase on its own candidates against our exact stage, on the steps it ran on.
std::string peer_narrow_phase_table(const ScaleRun& run) {
  Rows rows;
  for (const SceneResult& r : run.results)
    if (r.peer_narrow) rows.push_back(peer_narrow_phase_row(r));
  std::string md = "\nThe peer's narrow phase: " + peer_narrow_phase_method(run) + "\n\n";
  if (!rows.empty())
    md += markdown_table({"step", "peer candidates", "peer ns / candidate, batch", "peer ns / candidate, decided",
                          "peer hits", "peer false positives", "ours false reports, new / old", "peer missed",
                          "peer earliest toi", "peer stepsize (toi x 0.8)", "ours ns / pair reaching the exact stage",
                          "ours / peer per pair", "peer whole, 1 thread", "ours new / peer whole"},
                         rows) +
          "\n";
  return md;
}

// The exact-default issue's targets: the new default against the old one and the peer, per step (the exact stage's
// time per pair on the densest generated step and rod-twist).
std::string exact_default_targets_table(const std::vector<SceneResult>& results) {
  Rows targets;
  const SceneResult* densest = nullptr;
  for (const SceneResult& r : results)
    if (r.scene.generated && (!densest || reaching(r.one) > reaching(densest->one))) densest = &r;
  for (const SceneResult& r : results) {
    const double ratio = r.one.whole_ms() / r.approximate.whole_ms();
    targets.push_back({"whole detection, one thread, new default against old, " + r.scene.name,
                       ms(r.one.whole_ms()) + " vs " + ms(r.approximate.whole_ms()), fixed(ratio, 3), "new / old <= 1",
                       verdict(ratio <= 1)});
    if (&r == densest || r.scene.name == "rod-twist")
      targets.push_back({"exact stage per pair reaching it, new default, " + r.scene.name,
                         number(us_per_pair(r.one), 3) + " us (" + std::to_string(reaching(r.one)) + " pairs)",
                         fixed(us_per_pair(r.one) / us_per_pair(r.approximate), 2) + " of the old default's",
                         "<= 0.8 us", verdict(us_per_pair(r.one) <= kExactUsPerPairTarget)});
    targets.push_back(
        {"false reports, new default, " + r.scene.name, false_count(r.false_reports),
         r.peer_narrow && r.peer_narrow->per_pair ? "peer " + std::to_string(r.peer_false_reports.not_colliding) : "-",
         "0", verdict(r.false_reports.not_colliding == 0)});
    targets.push_back({"conservative (undecided) reports, new default, " + r.scene.name,
                       std::to_string(r.one.conservative), "-", "0", verdict(r.one.conservative == 0)});
  }
  return "Targets of the exact-default issue:\n\n" +
         markdown_table({"measure", "ours", "against", "target", "verdict"}, targets);
}

// The peer's whole answer to the earliest-impact question on a step: its LBVH candidates (one thread) plus
// compute_collision_free_stepsize over them; nothing when either was not run.
std::optional<double> peer_stepsize_whole_ms(const SceneResult& r) {
  if (!r.peer_one || !r.peer_narrow) return std::nullopt;
  return r.peer_one->ms + r.peer_narrow->stepsize_ms;
}

// One step's row of the earliest-impact table (the step has earliest_one).
std::vector<std::string> earliest_impact_row(const SceneResult& r) {
  const EarliestRun& e = *r.earliest_one;
  const bool has_two = r.earliest_two.has_value();
  const std::optional<double> peer_whole = peer_stepsize_whole_ms(r);
  return {r.scene.name,
          number(e.toi, 10),
          number(r.one.earliest_toi, 10),
          std::to_string(e.windows),
          std::to_string(e.candidates),
          ms(e.whole_ms()),
          has_two ? ms(r.earliest_two->whole_ms()) : "-",
          has_two ? fixed(e.whole_ms() / r.earliest_two->whole_ms(), 2) + "x" : "-",
          fixed(e.whole_ms() / r.one.whole_ms(), 3),
          peer_whole ? ms(*peer_whole) : "-",
          peer_whole ? number(r.peer_narrow->stepsize, 9) : "-",
          peer_whole ? fixed(*peer_whole / e.whole_ms(), 1) + "x" : "-"};
}

// The collision-free step: our earliest-impact search against our detection and the peer's step size.
std::string earliest_impact_table(const ScaleRun& run) {
  Rows rows;
  for (const SceneResult& r : run.results)
    if (r.earliest_one) rows.push_back(earliest_impact_row(r));
  const std::string heading = "\n### The collision-free step: earliest time of impact\n\n";
  if (rows.empty()) return heading + "Not measured: the program's `detect --help` lists no `--earliest`.\n";
  return heading +
         "`clothcd detect T0 T1 --earliest` (CollisionDetector::earliest_impact: consecutive time windows sized from "
         "the motion and the candidate counts, each pair tested only up to the earliest contact found so far) in the "
         "same rounds as above, on one CPU and on two, best round; times are the detector's own stage times, as for "
         "detection. Peer: its whole answer to the same question, its LBVH candidates (one thread, above) plus "
         "`Candidates.compute_collision_free_stepsize` over them (the batch column above; it returns its earliest toi "
         "times 0.8). Ours has no safety factor.\n\n" +
         markdown_table({"step", "earliest toi", "detect()'s earliest toi", "windows", "candidates (all windows)",
                         "ours, 1 thread", "ours, 2 threads", "2T speed-up", "ours / our detection",
                         "peer whole, 1 thread", "peer step size", "peer / ours"},
                        rows);
}

// The collision-free-step issue's targets, per step with an earliest-impact search (none without one).
std::string earliest_impact_targets_table(const std::vector<SceneResult>& results) {
  Rows targets;
  for (const SceneResult& r : results) {
    if (!r.earliest_one) continue;
    const EarliestRun& e = *r.earliest_one;
    const double of_detect = e.whole_ms() / r.one.whole_ms();
    targets.push_back({"earliest impact against our detection, one thread, " + r.scene.name,
                       ms(e.whole_ms()) + " vs " + ms(r.one.whole_ms()), fixed(of_detect, 3), "<= 0.5",
                       verdict(of_detect <= 0.5)});
    targets.push_back({"the same toi as detect()'s earliest collision, " + r.scene.name, number(e.toi, 10),
                       number(r.one.earliest_toi, 10), "equal", verdict(e.toi == r.one.earliest_toi)});
    if (const std::optional<double> peer_whole = peer_stepsize_whole_ms(r))
      targets.push_back(
          {"ipctk step size (candidates + compute_collision_free_stepsize) against ours, one thread, " + r.scene.name,
           ms(e.whole_ms()) + " vs " + ms(*peer_whole), fixed(*peer_whole / e.whole_ms(), 1), ">= 10",
           verdict(*peer_whole / e.whole_ms() >= 10)});
    if (r.earliest_two && r.one.candidates >= kMillion) {
      const double speedup = e.whole_ms() / r.earliest_two->whole_ms();
      targets.push_back({"earliest impact, two threads against one, " + r.scene.name,
                         ms(r.earliest_two->whole_ms()) + " vs " + ms(e.whole_ms()), fixed(speedup, 2) + "x", ">= 1.7x",
                         verdict(speedup >= 1.7)});
    }
  }
  if (targets.empty()) return "";
  return "\nTargets of the collision-free-step issue:\n\n" +
         markdown_table({"measure", "ours", "against", "target", "verdict"}, targets);
}

SectionReport run_scale(const BenchContext& context) {
  const ScratchFolder scratch("scale");
  const fs::path clothcd = measured_clothcd(context);
  const std::vector<Scene> scenes = scenes_to_measure(context, scratch.path());
  const ScaleRun run = measure_scenes(context, scenes, measuring_programs(context, clothcd), scratch.path());
  write_scale_csv(context.out_dir / "scale.csv", run.results);
  std::string md = scale_introduction(context, run);
  md += detection_table(run);
  md += ns_per_candidate_chart(context.out_dir / "scale_ns_per_candidate.svg", run.results);
  md += scaling_targets_table(context, run);
  md += exact_modes_table(run);
  md += peer_narrow_phase_table(run);
  md += exact_default_targets_table(run.results);
  md += earliest_impact_table(run);
  md += earliest_impact_targets_table(run.results);
  return {md, {"scale.csv", "scale_ns_per_candidate.svg"}};
}

const SectionRegistrar registrar{
    {57, "scale",
     "Large steps (real and generated, millions of candidate pairs): stage times, peak memory, one and two threads, "
     "old and new default (approximate / exact) with false reports, against the IPC Toolkit's LBVH and "
     "Tight-Inclusion narrow phase",
     run_scale}};

}  // namespace
}  // namespace clothcd::bench
