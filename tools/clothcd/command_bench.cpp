// `clothcd bench all|NAME --out DIR [...]`: runs the benchmark program clothcd-bench (built with
// CLOTHCD_BUILD_BENCH=ON, which links the peer libraries) with the same arguments and returns its exit code.
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.hpp"

namespace clothcd::cli {
namespace {

namespace fs = std::filesystem;

// clothcd-bench beside this program, else in the install's bin folder; throws naming both places when neither has it.
fs::path find_bench_program() {
  std::error_code error;
  const fs::path self = fs::read_symlink("/proc/self/exe", error);
  std::vector<fs::path> candidates;
  if (!error) candidates.push_back(self.parent_path() / "clothcd-bench");
  candidates.push_back(fs::path(CLOTHCD_INSTALL_BINDIR) / "clothcd-bench");
  std::string looked;
  for (const fs::path& candidate : candidates) {
    if (access(candidate.c_str(), X_OK) == 0) return candidate;
    looked += (looked.empty() ? "" : " and ") + candidate.string();
  }
  throw std::runtime_error("the benchmark program clothcd-bench was not built (configure with "
                           "-DCLOTHCD_BUILD_BENCH=ON; looked for " + looked + ")");
}

// Runs `program` with `arguments` and returns its exit code (128 + signal when it was killed).
int run_program(const fs::path& program, const std::vector<std::string>& arguments) {
  std::vector<std::string> storage{program.string()};
  storage.insert(storage.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (std::string& a : storage) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t child = fork();
  if (child < 0) throw std::runtime_error("cannot start " + program.string());
  if (child == 0) {
    execv(program.c_str(), argv.data());
    _exit(127);
  }
  int status = 0;
  if (waitpid(child, &status, 0) < 0) throw std::runtime_error("lost " + program.string());
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  return 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

}  // namespace

void add_bench_command(CLI::App& app) {
  auto* command = app.add_subcommand(
      "bench", "Reproduce the paper's experiments with peer libraries: bench all|NAME --out DIR [--quick] "
               "(see `clothcd bench --help`)");
  command->prefix_command();  // everything after `bench` goes to clothcd-bench unparsed, --help included
  command->set_help_flag();
  command->callback([command] {
    const int status = run_program(find_bench_program(), command->remaining());
    if (status != 0) throw CLI::RuntimeError(status);
  });
}

}  // namespace clothcd::cli
