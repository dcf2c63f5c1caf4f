// clothcd-bench: runs the benchmark sections (the paper's tables and figures, with peer libraries in the same run) and
// writes their CSV and PNG files plus one Markdown report into the output folder.
// Usage: clothcd-bench all|NAME --out DIR [--quick] [--quiet] [--cache DIR] [--network DIR] [--ccd-queries DIR]
//        [--scalable-ccd DIR] [--clothcd PROGRAM]
// Data paths are found at run time: the model cache as every clothcd command finds it, the network and the shared
// data from the repository the current folder is in.
#include <CLI/CLI.hpp>

#include <cctype>
#include <chrono>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "bench_section.hpp"
#include "bench_util.hpp"
#include "clothcd/culling/network_culler.hpp"
#include "clothcd/mesh/model_catalog.hpp"
#include "machine_info.hpp"

namespace fs = std::filesystem;
using namespace clothcd::bench;

namespace {

// The clothcd repository the run is made from, found at run time: the current folder or the nearest folder above it
// that holds bench/README.md and models/default; empty outside a checkout.
fs::path find_repository() {
  std::error_code error;
  fs::path dir = fs::current_path(error);
  if (error) return {};
  for (; !dir.empty(); dir = dir.parent_path()) {
    std::error_code missing;  // set when a path does not exist: not an error here
    if (fs::is_regular_file(dir / "bench" / "README.md", missing) &&
        fs::is_directory(dir / "models" / "default", missing))
      return dir;
    if (dir == dir.root_path()) break;
  }
  return {};
}

// The repository's models/default, else the library's default pair network; empty when neither exists.
fs::path default_network(const fs::path& repository) {
  std::error_code error;
  if (!repository.empty() && fs::is_directory(repository / "models" / "default", error))
    return repository / "models" / "default";
  try {
    return clothcd::learning::default_network_model_dir();
  } catch (const std::exception&) {
    return {};
  }
}

// A folder of the shared data beside the checkout (../shared/data/NAME: the public CCD benchmark's sample queries, the
// real simulation steps), when present.
std::optional<fs::path> default_shared_data(const fs::path& repository, const std::string& name) {
  if (repository.empty()) return std::nullopt;
  const fs::path dir = repository.parent_path() / "shared" / "data" / name;
  std::error_code error;
  if (fs::is_directory(dir, error)) return dir;
  return std::nullopt;
}

std::string section_names(const std::vector<Section>& sections) {
  std::string names = "all";
  for (const Section& s : sections) names += ", " + s.name;
  return names;
}

// A GitHub-style anchor of a heading: lower case, spaces to '-', other punctuation dropped.
std::string anchor(const std::string& heading) {
  std::string out;
  for (const char c : heading) {
    if (std::isalnum(static_cast<unsigned char>(c))) out += static_cast<char>(std::tolower(c));
    else if (c == ' ' || c == '-' || c == '_') out += c == ' ' ? '-' : c;
  }
  return out;
}

// The text of the first "## " heading of a section's Markdown.
std::string first_heading(const std::string& markdown) {
  const std::size_t start = markdown.find("## ");
  if (start == std::string::npos) return "";
  return markdown.substr(start + 3, markdown.find('\n', start) - start - 3);
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<Section> sections = all_sections();
  CLI::App app{"clothcd-bench: the paper's experiments beside the paper's figures and peer libraries", "clothcd-bench"};
  std::string which;
  BenchContext context;
  context.repository = find_repository();
  context.obstacle_model_dir = clothcd::default_model_dir();
  context.network_model_dir = default_network(context.repository);
  context.ccd_queries = default_shared_data(context.repository, "ccd-sample-queries");
  context.scalable_ccd = default_shared_data(context.repository, "scalable-ccd-sample");
  std::string ccd_queries, scalable_ccd;
  bool quiet = false;
  app.add_option("SECTION", which, "all, or one section: " + section_names(sections).substr(5))->required();
  app.add_option("--out", context.out_dir, "Folder for report.md and the CSV and PNG files (created)")->required();
  app.add_flag("--quiet,-q", quiet, "No progress lines on stderr");
  app.add_flag("--quick", context.quick, "CI-sized run: fewer models, steps and repetitions (under 2 minutes)");
  app.add_option("--cache", context.obstacle_model_dir, "Obstacle model cache (`clothcd meshes`; default "
                 "$CLOTHCD_CACHE, else $XDG_CACHE_HOME/clothcd or ~/.cache/clothcd)")
      ->capture_default_str();
  app.add_option("--models", context.obstacle_model_dir, "old spelling of --cache")->group("");
  app.add_option("--network", context.network_model_dir, "Pair network model folder (default: models/default of "
                 "the repository the current folder is in)")->capture_default_str();
  app.add_option("--ccd-queries", ccd_queries, "The public CCD benchmark's query folder (default: "
                 "../shared/data/ccd-sample-queries beside the repository the current folder is in, when present)");
  app.add_option("--scalable-ccd", scalable_ccd, "The shared real simulation steps for the scale section (default: "
                 "../shared/data/scalable-ccd-sample beside the repository the current folder is in, when present)");
  app.add_option("--clothcd", context.clothcd_program, "The clothcd program whose `detect` the scale section measures "
                 "(default: the one beside clothcd-bench)")->check(CLI::ExistingFile);
  std::string footer = "Sections:\n";
  for (const Section& s : sections) footer += "  " + s.name + ": " + s.summary + "\n";
  app.footer(footer);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);  // --help
    std::cerr << "clothcd-bench: error: " << e.what() << " (see clothcd-bench --help)\n";
    return 1;
  }

  std::vector<Section> chosen;
  for (const Section& s : sections)
    if (which == "all" || which == s.name) chosen.push_back(s);
  if (chosen.empty()) {
    std::cerr << "clothcd-bench: error: unknown section '" << which << "' (known: " << section_names(sections)
              << ")\n";
    return 1;
  }
  if (!ccd_queries.empty()) {
    if (!fs::is_directory(ccd_queries)) {
      std::cerr << "clothcd-bench: error: --ccd-queries " << ccd_queries << ": no such folder\n";
      return 1;
    }
    context.ccd_queries = fs::path(ccd_queries);
  }
  if (!scalable_ccd.empty()) {
    if (!fs::is_directory(scalable_ccd)) {
      std::cerr << "clothcd-bench: error: --scalable-ccd " << scalable_ccd << ": no such folder\n";
      return 1;
    }
    context.scalable_ccd = fs::path(scalable_ccd);
  }
  context.part_of_all = which == "all";
  try {
    fs::create_directories(context.out_dir);
  } catch (const std::exception& e) {
    std::cerr << "clothcd-bench: error: cannot create " << context.out_dir << ": " << e.what() << '\n';
    return 1;
  }

  const auto start = std::chrono::steady_clock::now();
  const auto elapsed_s = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  const std::string commit = context.repository.empty() ? "unknown (not run inside a checkout)"
                                                        : git_commit(context.repository);  // before the sections write their results into the tree
  std::vector<std::string> parts;
  bool failed = false;
  for (std::size_t i = 0; i < chosen.size(); ++i) {
    const Section& section = chosen[i];
    context.progress = [&](const std::string& step) {
      if (!quiet) std::cerr << "[" << section.name << "] " << step << "  (" << fixed(elapsed_s(), 1) << " s)\n";
    };
    context.progress("section " + std::to_string(i + 1) + "/" + std::to_string(chosen.size()) + ": " +
                     section.summary);
    const double section_start = elapsed_s();
    try {
      SectionReport report = section.run(context);
      report.markdown += "\n*Section time: " + fixed(elapsed_s() - section_start, 1) + " s.";
      if (!report.files.empty()) {
        report.markdown += " Files:";
        for (const std::string& f : report.files) report.markdown += " [" + f + "](" + f + ")";
      }
      parts.push_back(report.markdown + "*\n");
    } catch (const std::exception& e) {
      failed = true;
      std::cerr << "clothcd-bench: error in section " << section.name << ": " << e.what() << '\n';
      parts.push_back("## " + section.name + "\n\n**FAILED**: " + std::string(e.what()) + "\n");
    }
  }

  std::string report = "# clothcd benchmark report\n\n";
  report += "Every figure below was measured in this run; the paper's figures (Jin et al.) are quoted beside ours.\n\n";
  report += "- Machine: " + cpu_description() + ", " + os_description() + "\n";
  report += "- Load average (1 min) at the end of the run: " + load_average() +
            " (a shared machine: compare ratios measured in the same run, not absolute times)\n";
  report += "- Date: " + utc_now() + "\n";
  report += "- Commit: " + commit + " (at the start of the run)\n";
  report += std::string("- Mode: ") + (context.quick ? "quick (`--quick`, CI-sized)" : "full") + "\n";
  report += "- Command: `clothcd bench " + which + " --out " + context.out_dir.string() +
            (context.quick ? " --quick" : "") + "`\n\n## Contents\n\n";
  for (const std::string& part : parts)
    report += "- [" + first_heading(part) + "](#" + anchor(first_heading(part)) + ")\n";
  for (const std::string& part : parts) report += "\n" + part;
  report += "\nTotal time: " + fixed(elapsed_s(), 1) + " s.\n";
  const fs::path report_path = context.out_dir / "report.md";
  std::ofstream out(report_path);
  out << report;
  if (!out) {
    std::cerr << "clothcd-bench: error: cannot write " << report_path << '\n';
    return 1;
  }
  std::cerr << "clothcd-bench: wrote " << report_path.string() << " in " << fixed(elapsed_s(), 1) << " s\n";
  return failed ? 1 : 0;
}
