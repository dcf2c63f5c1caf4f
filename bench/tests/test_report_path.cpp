// The report names paths relative to the repository, never a folder of the machine the bench ran on.
#include <catch2/catch.hpp>

#include "bench_util.hpp"

using clothcd::bench::report_path;

TEST_CASE("report paths: inside the repository, beside it, and without one") {
  CHECK(report_path("/home/a/clothcd/models/default", "/home/a/clothcd") == "models/default");
  CHECK(report_path("/home/a/clothcd/./models/../models/default/", "/home/a/clothcd/") == "models/default");
  CHECK(report_path("/home/a/shared/data/ccd-sample-queries", "/home/a/clothcd") == "../shared/data/ccd-sample-queries");
  CHECK(report_path("/data/queries", "") == "/data/queries");
}
