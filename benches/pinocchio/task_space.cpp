// Times the tool's task-space (operational-space) dynamics as a Pinocchio user writes them,
// for comparison with `cargo bench --bench generated -- task_space` (dhgen::task_space::tool):
// D⁻¹ (computeMinverse), the last joint's Jacobian in world axes (computeJointJacobians,
// getJointJacobian), the bias (nonLinearEffects), g (computeGeneralizedGravity), J̇ q̇
// (forwardKinematics at zero acceleration, getClassicalAcceleration), then with Eigen
// Λ = (J D⁻¹ Jᵀ)⁻¹ by Cholesky, J̄ᵀ = Λ J D⁻¹, p = J̄ᵀ g and μ = J̄ᵀ (b − g) − Λ J̇ q̇, on the
// models scripts/pinocchio_derivatives.py saves. DHGEN_PIN_CALLS=N times it N times in one
// round instead (for callgrind).
#include <pinocchio/multibody.hpp>

#include <pinocchio/algorithm/aba.hpp>
#include <pinocchio/algorithm/crba.hpp>
#include <pinocchio/algorithm/jacobian.hpp>
#include <pinocchio/algorithm/kinematics.hpp>
#include <pinocchio/algorithm/frames.hpp>
#include <pinocchio/algorithm/rnea.hpp>
#include <pinocchio/serialization.hpp>
#include "timing.hpp"
#include <Eigen/Cholesky>
#include <cstdio>
#include <cstdlib>
#include <random>

using namespace pinocchio;

int main(int argc, char** argv) {
  for (int k = 1; k < argc; ++k) {
    Model model;
    model.loadFromBinary(argv[k]);
    Data data(model);
    const JointIndex tip = model.njoints - 1;
    std::mt19937 gen(21);
    std::uniform_real_distribution<double> d(-1.5, 1.5);
    const int S = 64;
    std::vector<Eigen::VectorXd> q(S), v(S);
    for (int s = 0; s < S; ++s) {
      q[s] = Eigen::VectorXd(model.nq); v[s] = q[s];
      for (int j = 0; j < model.nq; ++j) { q[s][j] = d(gen); v[s][j] = d(gen); }
    }
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(model.nv);
    Data::Matrix6x J(6, model.nv);
    Eigen::Matrix<double, 6, Eigen::Dynamic> JDinv(6, model.nv), JbarT(6, model.nv);
    Eigen::Matrix<double, 6, 6> Lambda;
    Eigen::Matrix<double, 6, 1> mu, p;
    double sink = 0;
    // The state i's J, bias, g and J̇q̇, and from J D⁻¹ (which `j_dinv` forms from q and J)
    // Λ, J̄ᵀ, μ and p.
    auto task_space = [&](int i, auto j_dinv) {
      const Eigen::VectorXd& qi = q[i % S];
      const Eigen::VectorXd& vi = v[i % S];
      computeJointJacobians(model, data, qi);
      J.setZero();
      getJointJacobian(model, data, tip, LOCAL_WORLD_ALIGNED, J);
      j_dinv(qi);
      const Eigen::VectorXd bias = nonLinearEffects(model, data, qi, vi);
      const Eigen::VectorXd& g = computeGeneralizedGravity(model, data, qi);
      forwardKinematics(model, data, qi, vi, zero);
      const Eigen::Matrix<double, 6, 1> jdqd =
          getClassicalAcceleration(model, data, tip, LOCAL_WORLD_ALIGNED).toVector();
      const Eigen::Matrix<double, 6, 6> mobility = JDinv * J.transpose();
      Lambda = mobility.llt().solve(Eigen::Matrix<double, 6, 6>::Identity());
      JbarT.noalias() = Lambda * JDinv;
      p.noalias() = JbarT * g;
      mu.noalias() = JbarT * (bias - g) - Lambda * jdqd;
      sink += Lambda(1, 1) + mu(0) + p(2);
    };
    // J D⁻¹ from D⁻¹ itself (computeMinverse) ...
    auto from_minverse = [&](const Eigen::VectorXd& qi) {
      computeMinverse(model, data, qi);
      data.Minv.triangularView<Eigen::StrictlyLower>() = data.Minv.transpose();
      JDinv.noalias() = J * data.Minv;
    };
    // ... or from D (crba) and Eigen's Cholesky factorisation, solving instead of inverting.
    Eigen::Matrix<double, Eigen::Dynamic, 6> DinvJt(model.nv, 6);
    auto from_crba = [&](const Eigen::VectorXd& qi) {
      crba(model, data, qi);
      data.M.triangularView<Eigen::StrictlyLower>() = data.M.transpose();
      DinvJt = data.M.llt().solve(J.transpose());
      JDinv = DinvJt.transpose();
    };
    const char* calls = std::getenv("DHGEN_PIN_CALLS");
    const int batch = calls ? std::atoi(calls) : 20000, rounds = calls ? 1 : 31;
    double t = median_ns([&](int i) { task_space(i, from_minverse); }, batch, rounds);
    double t_crba = median_ns([&](int i) { task_space(i, from_crba); }, batch, rounds);
    std::printf("%s: task space (Λ, J̄ᵀ, μ, p) from computeMinverse %.1f ns, from crba and LLT %.1f ns (%g)\n",
                argv[k], t, t_crba, sink);
  }
  return 0;
}
