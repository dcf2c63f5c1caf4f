#pragma once
/// @file
/// Linearised implicit (backward) Euler for the mass-spring cloth, solved matrix-free with Jacobi-preconditioned CG.
/// Why implicit: the paper's cloths with realistic stiffness have spring periods far below a 5 ms step
/// (h * sqrt(k / m) is about 8 for cloth C), where explicit or symplectic Euler would need tens of substeps; one
/// linearised backward-Euler solve is unconditionally stable for springs and costs a few dozen sparse products.

#include <vector>

#include "clothcd/simulation/cloth_model.hpp"

namespace clothcd::simulation {

/// Settings of the linear solve.
struct IntegratorSettings {
  int max_cg_iterations = 20;     ///< Upper bound on conjugate-gradient iterations per step.
  double cg_tolerance = 1e-3;     ///< Stop when the residual norm falls below this fraction of the right-hand side's.
};

/// What one solve did.
struct IntegratorResult {
  int cg_iterations = 0;          ///< Iterations used.
  double relative_residual = 0;   ///< Final residual norm / right-hand side norm.
};

/// Advances velocities by one backward-Euler step (Baraff and Witkin 1998):
/// (M - h dF/dv - h^2 dF/dx) dv = h (F(x0, v0) + h dF/dx v0), v1 = v0 + dv; pinned vertices keep v = 0.
/// Holds scratch buffers so that repeated steps do not allocate.
/// Threads: a step reuses the object's buffers, so one integrator belongs to one thread at a time.
class ImplicitIntegrator {
 public:
  /// Creates an integrator with the given solve settings. Throws std::invalid_argument unless max_cg_iterations >= 1
  /// and 0 < cg_tolerance < 1.
  explicit ImplicitIntegrator(const IntegratorSettings& settings = {});

  /// Writes the end-of-step velocities (#V x 3) for positions and velocities `state` and step `dt` seconds (> 0) into
  /// `velocities`. Positions are not changed: the caller moves x1 = x0 + dt v1 and applies collision response.
  /// Throws std::runtime_error when the system overflows (a time step far too large for the stiffness or speeds), and
  /// std::invalid_argument for dt not finite and > 0 or a state whose sizes differ from the model's.
  IntegratorResult predict_velocities(const ClothModel& model, const ClothState& state, double dt,
                                      Vertices& velocities);

 private:
  /// Per-spring linearisation S q = alpha n (n . q) + beta q for a relative vector q = p_a - p_b, one array per field
  /// (the product takes four springs at a time from clothcd::SimdLevel::Avx2 up).
  struct SpringBlocks {
    std::vector<double> n0, n1, n2;  ///< Unit direction n of each spring.
    std::vector<double> alpha, beta;
    std::vector<int> a3;  ///< 3 a: offset of the spring's first vertex in a stacked 3n vector.
    std::vector<int> b3;  ///< 3 b: the same for its second vertex.
    std::vector<double> rest, stiffness;  ///< Each spring's rest length and stiffness k (inputs of the linearisation).
  };
  void multiply(const ClothModel& model, const Eigen::VectorXd& p, Eigen::VectorXd& out) const;

  IntegratorSettings settings_;
  SpringBlocks blocks_;
  Eigen::VectorXd diagonal_, mass_diagonal_, rhs_, dv_, r_, z_, p_, ap_;
};

}  // namespace clothcd::simulation
