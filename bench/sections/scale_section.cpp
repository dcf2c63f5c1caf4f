// Section "scale": whole detection on real and generated steps of millions of candidate pairs, each step run by
// `clothcd detect T0 T1` in a child process on one CPU and on two (stage times, peak resident memory, a digest of the
// collisions), beside the IPC Toolkit's LBVH candidate search (the `ipctk` wheel, in a Python environment the section
// creates under .cache/bench-venv) on the same frames in the same run; with the targets of the scaling issue as rows.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "../suite/bench_section.hpp"
#include "../suite/bench_util.hpp"
#include "../suite/charts.hpp"
#include "../suite/child_process.hpp"
#include "../suite/detect_run.hpp"
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

// One step to measure: its frames on disk and what is known about it.
struct Scene {
  std::string name;
  fs::path t0, t1;
  std::optional<fs::path> truth;
  long vertices = 0, faces = 0;
  bool generated = false;
};

// The peer's result on one step at one thread count.
struct PeerRun {
  long candidates = 0;
  double ms = 0;
};

// Everything measured on one step.
struct SceneResult {
  Scene scene;
  DetectRun one, two;  // best whole-detection run on one and on two CPUs (two.candidates == 0: not run)
  double peak_rss_one = 0, peak_rss_two = 0;
  bool same_collisions = true;  // every run, one CPU or two, gave the same digest
  std::optional<TruthCheck> truth;
  std::optional<PeerRun> peer_one, peer_two;
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

// The frames as `clothcd detect` reads them, written for the peer (format in bench/peers/ipctk_candidates.py).
void write_peer_scene(const MeshFrames& frames, const fs::path& path) {
  std::ofstream out(path, std::ios::binary);
  const std::int64_t counts[2] = {frames.start.vertex_count(), frames.start.face_count()};
  out.write(reinterpret_cast<const char*>(counts), sizeof counts);
  const auto bytes = [](Eigen::Index values) { return static_cast<std::streamsize>(values * 8); };
  out.write(reinterpret_cast<const char*>(frames.start.vertices.data()), bytes(frames.start.vertices.size()));
  out.write(reinterpret_cast<const char*>(frames.end.data()), bytes(frames.end.size()));
  out.write(reinterpret_cast<const char*>(frames.start.faces.data()), frames.start.faces.size() * 4);
  if (!out) throw std::runtime_error(path.string() + ": write failed");
}

// The Python of the section's environment when it imports ipctk (creating the environment first in a full run), else
// nothing and why in `status`.
std::optional<fs::path> peer_python(const BenchContext& context, const fs::path& script, std::string& status) {
  const fs::path venv = context.repository / ".cache" / "bench-venv", python = venv / "bin" / "python";
  const auto works = [&] {
    if (access(python.c_str(), X_OK) != 0) return false;
    const ChildRun run = run_child({python.string(), script.string(), "--version"}, 1);
    status = run.output.substr(0, run.output.find('\n'));
    return run.exit_code == 0;
  };
  if (works()) return python;
  if (!context.quick) {
    context.progress("creating the peer's Python environment in " + venv.string() + " (pip install ipctk==1.6.1)");
    const ChildRun setup =
        run_child({"/usr/bin/env", "bash", (context.repository / "bench" / "peers" / "setup-ipctk.sh").string(),
                   venv.string()}, 1);
    if (setup.exit_code == 0 && works()) return python;
  }
  status = "peer not installed (no ipctk in " + venv.string() + (context.quick ? "; a full run creates it)" : ")");
  return std::nullopt;
}

PeerRun run_peer(const fs::path& python, const fs::path& script, const fs::path& scene, int threads) {
  const ChildRun run = run_child({python.string(), script.string(), scene.string(), "--threads",
                                  std::to_string(threads), "--repeats", "1"}, threads);
  std::map<std::string, double> values;
  std::istringstream words(run.output);
  for (std::string word; words >> word;) {
    const std::size_t eq = word.find('=');
    if (eq != std::string::npos) values[word.substr(0, eq)] = std::strtod(word.c_str() + eq + 1, nullptr);
  }
  if (run.exit_code != 0 || !values.count("candidates") || !values.count("best_ms"))
    throw std::runtime_error("the ipctk peer failed on " + scene.string() + ": " + run.output);
  return {static_cast<long>(values["candidates"]), values["best_ms"]};
}

// Keeps the faster of `best` and `run`, and the larger peak memory; notes the run's digest.
void keep_best(std::optional<DetectRun>& best, DetectRun run, double& peak_rss, std::vector<std::string>& digests) {
  peak_rss = std::max(peak_rss, run.peak_rss_mb);
  digests.push_back(run.digest);
  if (!best || run.whole_ms() < best->whole_ms()) best = std::move(run);
}

// Keeps the faster of `best` and `run`.
void keep_best(std::optional<PeerRun>& best, const PeerRun& run) {
  if (!best || run.ms < best->ms) best = run;
}

// The programs a step is measured with.
struct Programs {
  fs::path clothcd;                ///< clothcd, for `clothcd detect`.
  std::optional<fs::path> python;  ///< The peer's Python, when it imports ipctk.
  fs::path peer_script;            ///< bench/peers/ipctk_candidates.py.
};

// `repeats` rounds, each running clothcd detect on one CPU and on two and the peer on one and on two in turn (so a
// change of the shared machine's load affects all four alike); the best time of each over the rounds.
SceneResult measure_scene(const BenchContext& context, const Scene& scene, const fs::path& peer_file,
                          const Programs& programs, int repeats, bool two_cpus) {
  SceneResult result;
  result.scene = scene;
  std::optional<DetectRun> one, two;
  std::vector<std::string> digests;
  const fs::path collisions = peer_file.parent_path() / "collisions.json";
  for (int round = 1; round <= repeats; ++round) {
    context.progress(scene.name + " (" + std::to_string(scene.faces) + " faces): round " + std::to_string(round) +
                     " of " + std::to_string(repeats) + (programs.python ? ", clothcd detect and ipctk" : ""));
    keep_best(one, run_detect(programs.clothcd, scene.t0, scene.t1, collisions, 1), result.peak_rss_one, digests);
    if (two_cpus)
      keep_best(two, run_detect(programs.clothcd, scene.t0, scene.t1, collisions, 2), result.peak_rss_two, digests);
    if (!programs.python) continue;
    keep_best(result.peer_one, run_peer(*programs.python, programs.peer_script, peer_file, 1));
    if (two_cpus) keep_best(result.peer_two, run_peer(*programs.python, programs.peer_script, peer_file, 2));
  }
  result.one = *one;
  if (two) result.two = *two;
  result.same_collisions = std::all_of(digests.begin(), digests.end(), [&](auto& d) { return d == digests[0]; });
  if (scene.truth) result.truth = check_truth(*scene.truth, result.one.collisions);
  return result;
}

std::string verdict(bool met) { return met ? "met" : "**missed**"; }

std::string mb(double value) { return fixed(value, 1) + " MB"; }

std::string ms(double value) { return number(value, 4) + " ms"; }

SectionReport run_scale(const BenchContext& context) {
  const ScratchFolder scratch("scale");
  const fs::path clothcd = context.clothcd_program.empty()
                               ? fs::read_symlink("/proc/self/exe").parent_path() / "clothcd"
                               : fs::absolute(context.clothcd_program);
  if (access(clothcd.c_str(), X_OK) != 0) throw std::runtime_error("cannot run " + clothcd.string());
  if (context.repository.empty())
    throw std::runtime_error("scale: run clothcd bench inside the repository (its peer scripts are in bench/peers)");
  const fs::path script = context.repository / "bench" / "peers" / "ipctk_candidates.py";
  const int repeats = context.quick ? 1 : 3;
  const bool two_cpus = have_cpus(2);

  std::vector<Scene> scenes;
  if (context.scalable_ccd) {
    for (const char* name : {"cloth-funnel", "rod-twist"}) {
      const fs::path dir = *context.scalable_ccd / name;
      if (context.quick && std::string(name) == "rod-twist") continue;
      if (fs::exists(dir / "t0.ply"))
        scenes.push_back({name, dir / "t0.ply", dir / "t1.ply", dir / "truth.json"});
    }
  }
  for (const ThrownBodiesSpec& spec : generated_specs(context)) {
    context.progress("generating " + spec.name);
    const ThrownBodiesStep step = make_thrown_bodies(spec);
    Scene scene;
    scene.name = spec.name;
    scene.t0 = scratch.path() / (spec.name + "-t0.ply");
    scene.t1 = scratch.path() / (spec.name + "-t1.ply");
    scene.generated = true;
    save_mesh(step.start, scene.t0);
    save_mesh({step.end, step.start.faces}, scene.t1);
    scenes.push_back(scene);
  }

  std::string peer_status;
  const Programs programs{clothcd, peer_python(context, script, peer_status), script};
  const std::optional<fs::path>& python = programs.python;
  std::vector<SceneResult> results;
  for (Scene& scene : scenes) {
    const MeshFrames frames = load_mesh_frames(scene.t0, scene.t1);
    scene.vertices = static_cast<long>(frames.start.vertex_count());
    scene.faces = static_cast<long>(frames.start.face_count());
    const fs::path peer_file = scratch.path() / "peer-scene.bin";
    if (python) write_peer_scene(frames, peer_file);
    results.push_back(measure_scene(context, scene, peer_file, programs, repeats, two_cpus));
  }

  CsvFile csv(context.out_dir / "scale.csv",
              "scene,vertices,faces,candidates,refit_ms,traversal_ms,culling_ms,exact_ms,whole_1t_ms,"
              "ns_per_candidate_1t,whole_2t_ms,speedup_2t,peak_rss_1t_mb,peak_rss_2t_mb,collisions,digest,"
              "same_collisions_all_runs,truth_pairs,truth_missed,ipctk_candidates,ipctk_1t_ms,ipctk_2t_ms,"
              "ipctk_1t_over_ours_1t");
  std::vector<std::vector<std::string>> rows;
  BarChart chart;
  chart.text = {"Whole detection per candidate pair, per step", "step (scene)", "time per candidate pair (ns)", ""};
  chart.series = {"ours, one thread", "ours, two threads", "ipctk LBVH, one thread", "ipctk LBVH, two threads"};
  for (const SceneResult& r : results) {
    const double whole = r.one.whole_ms(), per = 1e6 * whole / static_cast<double>(std::max(1L, r.one.candidates));
    const bool has_two = r.two.candidates > 0;
    const double speedup = has_two ? whole / r.two.whole_ms() : 0;
    const double peer_ratio = r.peer_one ? r.peer_one->ms / whole : 0;
    const auto opt = [](bool has, double v, int digits) { return has ? number(v, digits) : std::string(); };
    csv.row({r.scene.name, std::to_string(r.scene.vertices), std::to_string(r.scene.faces),
             std::to_string(r.one.candidates), number(r.one.refit_ms, 6), number(r.one.traversal_ms, 6),
             number(r.one.culling_ms, 6), number(r.one.exact_ms, 6), number(whole, 6), number(per, 4),
             opt(has_two, r.two.whole_ms(), 6), opt(has_two, speedup, 4), number(r.peak_rss_one, 5),
             opt(has_two, r.peak_rss_two, 5), std::to_string(r.one.collisions.size()), r.one.digest,
             r.same_collisions ? "yes" : "no", r.truth ? std::to_string(r.truth->listed) : "",
             r.truth ? std::to_string(r.truth->missed) : "",
             r.peer_one ? std::to_string(r.peer_one->candidates) : "", opt(r.peer_one.has_value(),
             r.peer_one ? r.peer_one->ms : 0, 6), opt(r.peer_two.has_value(), r.peer_two ? r.peer_two->ms : 0, 6),
             opt(r.peer_one.has_value(), peer_ratio, 4)});
    rows.push_back({r.scene.name, std::to_string(r.scene.faces), std::to_string(r.one.candidates),
                    fixed(r.one.refit_ms, 1) + " / " + fixed(r.one.traversal_ms, 1) + " / " +
                        fixed(r.one.culling_ms, 1) + " / " + fixed(r.one.exact_ms, 1),
                    ms(whole), fixed(per, 1), has_two ? ms(r.two.whole_ms()) : "-",
                    has_two ? fixed(speedup, 2) + "x" : "-",
                    fixed(r.peak_rss_one, 1) + (has_two ? " / " + fixed(r.peak_rss_two, 1) : "") + " MB",
                    std::to_string(r.one.collisions.size()) + (r.same_collisions ? "" : " (**runs differ**)"),
                    "`" + r.one.digest + "`",
                    r.peer_one ? std::to_string(r.peer_one->candidates) : "-",
                    r.peer_one ? ms(r.peer_one->ms) : peer_status, r.peer_two ? ms(r.peer_two->ms) : "-",
                    r.peer_one ? fixed(peer_ratio, 2) : "-"});
    const auto ns_per = [](double t, long n) { return 1e6 * t / static_cast<double>(std::max(1L, n)); };
    const double none = std::nan("");  // draws no bar
    chart.categories.push_back(r.scene.name);
    chart.values.push_back({per, has_two ? ns_per(r.two.whole_ms(), r.one.candidates) : none,
                            r.peer_one ? ns_per(r.peer_one->ms, r.peer_one->candidates) : none,
                            r.peer_two ? ns_per(r.peer_two->ms, r.peer_one->candidates) : none});
  }
  write_bar_chart_svg((context.out_dir / "scale_ns_per_candidate.svg").string(), chart);

  // The targets, one row per step they apply to.
  std::vector<std::vector<std::string>> targets;
  bool huge_seen = false;
  for (const SceneResult& r : results) {
    if (r.one.candidates < kHugeCandidates) continue;
    huge_seen = true;
    const double peak = std::max(r.peak_rss_one, r.peak_rss_two);
    targets.push_back({"peak resident memory of `clothcd detect`, " + r.scene.name, mb(peak), "-", "-",
                       "<= 256 MB at >= 30M candidates", verdict(peak <= kMemoryTargetMb)});
  }
  if (!huge_seen)
    targets.push_back({"peak resident memory of `clothcd detect` at >= 30M candidates", "no such step in this run",
                       "-", "-", "<= 256 MB", context.part_of_all ? "not measured (`clothcd bench scale` runs it)"
                                                                  : "not measured"});
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
  for (const SceneResult& r : results) {
    if (r.one.candidates < kMillion) continue;
    const std::string measure = "two threads against one, " + r.scene.name;
    if (r.two.candidates == 0) {
      targets.push_back({measure, "-", "-", "-", ">= 1.8x", "not measured (one CPU)"});
      continue;
    }
    const double speedup = r.one.whole_ms() / r.two.whole_ms();
    targets.push_back({measure, ms(r.two.whole_ms()) + " vs " + ms(r.one.whole_ms()), "-", fixed(speedup, 2) + "x",
                       ">= 1.8x", verdict(speedup >= kSpeedupTarget)});
  }
  for (const SceneResult& r : results) {
    targets.push_back({"same collisions in every run (one and two threads), " + r.scene.name, "`" + r.one.digest + "`",
                       "-", "-", "one digest", verdict(r.same_collisions)});
    if (r.truth)
      targets.push_back({"ground-truth pairs missed, " + r.scene.name,
                         std::to_string(r.truth->missed) + " of " + std::to_string(r.truth->listed), "-", "-", "0",
                         verdict(r.truth->missed == 0)});
  }

  std::string md = "## Scaling to large steps: generated and real steps against the IPC Toolkit\n\n";
  md += "Each step is given to `clothcd detect T0 T1 --out FILE` (thickness 0, the default hierarchy and combined "
        "filters) as one multi-body mesh, in a child process pinned to one CPU and then to two (TBB sizes its pool "
        "to them), then to the peer on one CPU and on two, in turn, " + std::to_string(repeats) + " rounds; best "
        "round of each by whole-detection time (build/refit + candidate "
        "search + culling + exact test, the detector's own stage times; loading excluded). Peak memory: the child's "
        "peak resident set (wait4), loading and writing the JSON included. Digest: FNV-1a over the sorted collisions "
        "(pairs, conservative flags, tois), to compare two detector versions bit for bit. Peer: " +
        (python ? peer_status + ", `Candidates.build(mesh, V0, V1, 0.0, LBVH())` alone on the same positions, "
                                "`ipctk.set_num_threads` and the same CPU pinning, best round"
                : peer_status) +
        ". Generated steps: N bodies (UV spheres, cloth sheets, fish of about 1 unit) on a lattice of 1.5-unit "
        "cells, each thrown about a cell in a random direction with a turn (bench/suite/thrown_bodies.hpp; the same "
        "bits from the same seed), written as ASCII PLY.";
  if (context.scalable_ccd) md += " Real steps: rod-twist and cloth-funnel of " + context.scalable_ccd->filename().string() +
                                 " (real simulation steps with ground truth).";
  else md += " Real steps: not run (no ../shared/data/scalable-ccd-sample; see --scalable-ccd).";
  if (context.part_of_all && !context.quick)
    md += " Part of `clothcd bench all`: the two largest generated steps (20M and 34M candidates) run only in "
          "`clothcd bench scale`.";
  if (!context.clothcd_program.empty()) md += " Detector measured: " + clothcd.string() + " (`--clothcd`).";
  if (context.quick) md += " Quick run: small steps only, one run each, no peer set-up.";
  md += "\n\n";
  md += markdown_table({"step", "faces", "candidates", "ms build+refit / search / culling / exact (1 thread)",
                        "whole, 1 thread", "ns / candidate", "whole, 2 threads", "2T speed-up",
                        "peak RSS 1T / 2T", "collisions", "digest", "ipctk candidates", "ipctk, 1 thread",
                        "ipctk, 2 threads", "ipctk 1T / ours 1T"},
                       rows);
  std::string steps;
  for (const SceneResult& r : results) steps += (steps.empty() ? "" : ", ") + r.scene.name;
  md += "\n![ns per candidate pair, per step](scale_ns_per_candidate.svg)\n\n*Steps left to right: " + steps +
        "; ipctk per its own candidate count.*\n\n";
  md += "Targets of the scaling issue:\n\n";
  md += markdown_table({"measure", "ours", "peer", "ratio", "target", "verdict"}, targets);
  return {md, {"scale.csv", "scale_ns_per_candidate.svg"}};
}

const SectionRegistrar registrar{
    {57, "scale",
     "Large steps (real and generated, millions of candidate pairs): stage times, peak memory, one and two threads, "
     "against the IPC Toolkit's LBVH",
     run_scale}};

}  // namespace
}  // namespace clothcd::bench
