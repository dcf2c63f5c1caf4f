// The clothcd program: one subcommand per task; any error ends with a one-line message on stderr and exit code 1.
#include <exception>
#include <iostream>
#include <new>
#include <string>

#include "clothcd/version.hpp"
#include "commands.hpp"

namespace {

// A command-line mistake as one line: CLI11's message, an unknown command named as such, and where to look for help.
std::string usage_error_message(CLI::App& app, int argc, char** argv, const CLI::ParseError& error) {
  const std::string first = argc > 1 ? argv[1] : "";
  if (!first.empty() && first[0] != '-') {
    bool known = false;
    std::string names;
    for (const CLI::App* command : app.get_subcommands({})) {
      known = known || command->get_name() == first;
      names += (names.empty() ? "" : ", ") + command->get_name();
    }
    if (!known) return "unknown command '" + first + "' (commands: " + names + ")";
    std::string what = error.what();
    if (what.rfind(": ", 0) == 0) what.erase(0, 2);  // a hidden option's message has no option name before ": "
    return first + ": " + what + " (see clothcd " + first + " --help)";
  }
  return std::string(error.what()) + " (see clothcd --help)";
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"clothcd: cloth collision detection (Jin et al.'s method, done safely)", "clothcd"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("clothcd ") + clothcd::version(), "Print the version and exit");
  clothcd::cli::add_info_command(app);
  clothcd::cli::add_convert_command(app);
  clothcd::cli::add_meshes_command(app);
  clothcd::cli::add_detect_command(app);
  clothcd::cli::add_proximity_command(app);
  clothcd::cli::add_intersections_command(app);
  clothcd::cli::add_ccd_command(app);
  clothcd::cli::add_simplify_command(app);
  clothcd::cli::add_obb_command(app);
  clothcd::cli::add_simulate_command(app);
  clothcd::cli::add_train_command(app);
  clothcd::cli::add_evaluate_command(app);
  clothcd::cli::add_gen_dataset_command(app);
  clothcd::cli::add_bench_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::RuntimeError& e) {
    return e.get_exit_code();  // `bench`: clothcd-bench has reported its error already
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);  // --help
    std::cerr << "clothcd: error: " << usage_error_message(app, argc, argv, e) << '\n';
    return 1;
  } catch (const std::bad_alloc&) {
    std::cerr << "clothcd: error: out of memory: the input needs more than this machine can give (for detect, two "
                 "frames far apart make billions of candidate pairs; for simulate, a fine cloth at a large thickness)\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "clothcd: error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
