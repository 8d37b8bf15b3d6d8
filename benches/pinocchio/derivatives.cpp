// Times Pinocchio's analytic derivatives (computeRNEADerivatives, computeABADerivatives) and
// rnea on the models scripts/pinocchio_derivatives.py builds, saved with Model.saveToBinary.
// DHGEN_PIN_CALLS=N times each function N times in one round instead (for callgrind: then
// every function's inclusive instruction count over N is its count per call).
#include <pinocchio/multibody.hpp>

#include <pinocchio/algorithm/rnea.hpp>
#include <pinocchio/algorithm/rnea-derivatives.hpp>
#include <pinocchio/algorithm/aba-derivatives.hpp>
#include <pinocchio/serialization.hpp>
#include "timing.hpp"
#include <cstdio>
#include <cstdlib>
#include <random>

using namespace pinocchio;

int main(int argc, char** argv) {
  for (int k = 1; k < argc; ++k) {
    Model model;
    model.loadFromBinary(argv[k]);
    Data data(model);
    std::mt19937 gen(21);
    std::uniform_real_distribution<double> d(-1.5, 1.5);
    const int S = 64;
    std::vector<Eigen::VectorXd> q(S), v(S), a(S), tau(S);
    for (int s = 0; s < S; ++s) {
      q[s] = Eigen::VectorXd(model.nq); v[s] = q[s]; a[s] = q[s];
      for (int j = 0; j < model.nq; ++j) { q[s][j] = d(gen); v[s][j] = d(gen); a[s][j] = d(gen); }
      tau[s] = rnea(model, data, q[s], v[s], a[s]);
    }
    Eigen::MatrixXd dq(model.nv, model.nv), dv(model.nv, model.nv), da(model.nv, model.nv);
    const char* calls = std::getenv("DHGEN_PIN_CALLS");
    const int batch = calls ? std::atoi(calls) : 20000, rounds = calls ? 1 : 31;
    double t_rnea = median_ns([&](int i) { rnea(model, data, q[i % S], v[i % S], a[i % S]); }, batch, rounds);
    double t_drnea = median_ns([&](int i) { computeRNEADerivatives(model, data, q[i % S], v[i % S], a[i % S], dq, dv, da); }, batch, rounds);
    double t_daba = median_ns([&](int i) { computeABADerivatives(model, data, q[i % S], v[i % S], tau[i % S]); }, batch, rounds);
    std::printf("%s: rnea %.1f ns, computeRNEADerivatives %.1f ns, computeABADerivatives %.1f ns\n", argv[k], t_rnea, t_drnea, t_daba);
  }
  return 0;
}
