// The extension module clothcd._clothcd. C++ exceptions arrive in Python with their message: invalid arguments as
// ValueError, an exceeded collision budget as CollisionBudgetExceeded (a RuntimeError), files that cannot be read or
// written (clothcd::MeshError and the other std::runtime_errors the library raises for files) as OSError.
#include <stdexcept>

#include "bindings.hpp"
#include "clothcd/detection/detection_errors.hpp"
#include "clothcd/mesh/mesh_error.hpp"
#include "clothcd/version.hpp"

NB_MODULE(_clothcd, m) {
  namespace nb = nanobind;
  static PyObject* const budget_exceeded = PyErr_NewExceptionWithDoc(
      "clothcd.CollisionBudgetExceeded",
      "A detect() call found more collisions than the detector's max_collisions: a degenerate step (see the README).",
      PyExc_RuntimeError, nullptr);
  m.attr("CollisionBudgetExceeded") = nb::handle(budget_exceeded);
  nb::register_exception_translator([](const std::exception_ptr& error, void*) {
    try {
      std::rethrow_exception(error);
    } catch (const clothcd::CollisionBudgetExceeded& e) {
      PyErr_SetString(budget_exceeded, e.what());
    } catch (const std::invalid_argument& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const std::domain_error& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const std::runtime_error& e) {
      PyErr_SetString(PyExc_OSError, e.what());
    }
  });
  m.attr("__version__") = clothcd::version();
  clothcd::python::bind_mesh(m);
  clothcd::python::bind_detection(m);
  clothcd::python::bind_simulation(m);
}
