#pragma once
/// @file
/// The exception thrown for unreadable, malformed or invalid meshes.

#include <stdexcept>
#include <string>

namespace clothcd {

/// Thrown when a mesh cannot be loaded, saved or validated; what() names the file (or context) and the problem.
class MeshError : public std::runtime_error {
 public:
  /// Builds the message "<context>: <problem>".
  MeshError(const std::string& context, const std::string& problem) : std::runtime_error(context + ": " + problem) {}
};

}  // namespace clothcd
