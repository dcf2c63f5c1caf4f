// The clothcd program: one subcommand per task; any error ends with a one-line message on stderr and exit code 1.
#include <exception>
#include <iostream>

#include "commands.hpp"

int main(int argc, char** argv) {
  CLI::App app{"clothcd: cloth collision detection (Jin et al.'s method, done safely)", "clothcd"};
  app.require_subcommand(1);
  clothcd::cli::add_info_command(app);
  clothcd::cli::add_convert_command(app);
  clothcd::cli::add_meshes_command(app);
  clothcd::cli::add_detect_command(app);
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
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    std::cerr << "clothcd: error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
