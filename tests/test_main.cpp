// Catch2's main for the clothcd test suite.
#define CATCH_CONFIG_MAIN
#include <catch2/catch.hpp>
