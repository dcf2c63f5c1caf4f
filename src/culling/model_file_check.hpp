#pragma once
// A cheap look at a model file before an XML parser reads it: a recursive parser (OpenNN's tinyxml2) exhausts the
// stack on a file nested deeply enough, and every parser holds the whole file in memory.

#include <string>

namespace clothcd::learning {

/// Elements deeper than this are refused; an OpenNN model nests five levels.
inline constexpr int kMaxModelNesting = 64;
/// Files larger than this are refused; the largest network clothcd can load is far below it.
inline constexpr long long kMaxModelFileBytes = 64LL << 20;

/// Throws std::runtime_error naming `path` when the file is larger than kMaxModelFileBytes or nests elements deeper
/// than kMaxModelNesting. A missing or unreadable file passes (the parser reports it); so do other faults of form.
void check_model_file_shape(const std::string& path);

}  // namespace clothcd::learning
