// Machine, date and commit lines of the benchmark report.
#include "machine_info.hpp"

#include <sys/utsname.h>

#include <array>
#include <cstdio>
#include <ctime>
#include <fstream>

namespace clothcd::bench {
namespace {

// The text after "key" and the following ':' or '=' on the first line starting with key, quotes removed.
std::string field(const std::string& file, const std::string& key, int* count = nullptr) {
  std::ifstream in(file);
  std::string line, value;
  while (std::getline(in, line)) {
    if (line.rfind(key, 0) != 0) continue;
    if (count) ++*count;
    if (!value.empty()) continue;
    const std::size_t at = line.find_first_of(":=", key.size());
    if (at == std::string::npos) continue;
    value = line.substr(at + 1);
    value.erase(0, value.find_first_not_of(" \t\""));
    while (!value.empty() && (value.back() == '"' || value.back() == ' ')) value.pop_back();
  }
  return value;
}

}  // namespace

std::string cpu_description() {
  int cores = 0;
  const std::string model = field("/proc/cpuinfo", "model name", &cores);
  if (model.empty()) return "unknown CPU";
  return model + " (" + std::to_string(cores) + " logical cores)";
}

std::string os_description() {
  std::string os = field("/etc/os-release", "PRETTY_NAME");
  utsname name{};
  if (uname(&name) == 0) os += (os.empty() ? "" : ", ") + std::string(name.sysname) + " " + name.release;
  return os.empty() ? "unknown OS" : os;
}

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  std::array<char, 32> text{};
  std::strftime(text.data(), text.size(), "%Y-%m-%d %H:%M UTC", &utc);
  return text.data();
}

std::string git_commit(const std::filesystem::path& source_dir) {
  const std::string command = "git -C '" + source_dir.string() + "' describe --always --dirty 2>/dev/null";
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return "unknown";
  std::array<char, 128> buffer{};
  std::string out;
  while (std::fgets(buffer.data(), static_cast<int>(buffer.size()), pipe)) out += buffer.data();
  const int status = pclose(pipe);
  while (!out.empty() && (out.back() == '\n' || out.back() == ' ')) out.pop_back();
  return status == 0 && !out.empty() ? out : "unknown";
}

std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string one;
  return in >> one ? one : "-";
}

}  // namespace clothcd::bench
