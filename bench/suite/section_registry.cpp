// The registry behind all_sections(): sections add themselves from their own .cpp files.
#include <algorithm>
#include <utility>

#include "bench_section.hpp"

namespace clothcd::bench {
namespace {

std::vector<Section>& registry() {
  static std::vector<Section> sections;  // constructed on first use, so registration order does not matter
  return sections;
}

}  // namespace

SectionRegistrar::SectionRegistrar(Section section) { registry().push_back(std::move(section)); }

std::vector<Section> all_sections() {
  std::vector<Section> sorted = registry();
  std::stable_sort(sorted.begin(), sorted.end(), [](const Section& a, const Section& b) { return a.order < b.order; });
  return sorted;
}

}  // namespace clothcd::bench
