#pragma once
// The extension's parts, one per area.

#include <nanobind/nanobind.h>

namespace clothcd::python {

/// load_mesh, save_mesh, simplify, obb, generators, render_png.
void bind_mesh(nanobind::module_& m);
/// The collision detector and the CCD on query arrays.
void bind_detection(nanobind::module_& m);
/// Cloth simulation.
void bind_simulation(nanobind::module_& m);

}  // namespace clothcd::python
