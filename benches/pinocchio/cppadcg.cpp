// Pinocchio's own code generation, for issue 16 §0: traces rnea, forwardKinematics (the last
// joint's pose as a 3×3 rotation and a translation) and the last joint's Jacobian (in the
// world-aligned frame at that joint) of a model saved by scripts/pinocchio_derivatives.py
// with CppADCodeGen, with the model's quarter turns made exact first (its 6e-17 cosines
// become 0, as in dhgen's models), and writes their forward-zero code as C functions
// `rnea(x, y)` (x = q, q̇, q̈), `fk(x, y)` and `jacobian(x, y)` (x = q) to argv[2].
// scripts/cppadcg_counts.sh compiles them with gcc -O3 and counts instructions per call.
#include <pinocchio/codegen/cppadcg.hpp>
#include <pinocchio/multibody.hpp>
#include <pinocchio/algorithm/rnea.hpp>
#include <pinocchio/algorithm/kinematics.hpp>
#include <pinocchio/algorithm/jacobian.hpp>
#include <pinocchio/serialization.hpp>
#include <cmath>
#include <fstream>
#include <iostream>

using Scalar = double;
using CGS = CppAD::cg::CG<Scalar>;
using ADS = CppAD::AD<CGS>;
using Model = pinocchio::ModelTpl<Scalar>;
using ADModel = pinocchio::ModelTpl<ADS>;
using ADData = pinocchio::DataTpl<ADS>;
using ADVec = Eigen::Matrix<ADS, Eigen::Dynamic, 1>;

static double snap(double x) {
  for (double k : {0.0, 1.0, -1.0})
    if (std::abs(x - k) < 1e-12) return k;
  return x;
}

static void emit(std::ostream &os, const char *name, CppAD::ADFun<CGS> &fun, size_t nin) {
  CppAD::cg::CodeHandler<Scalar> handler;
  CppAD::vector<CGS> ind(nin);
  handler.makeVariables(ind);
  CppAD::vector<CGS> dep = fun.Forward(0, ind);
  CppAD::cg::LanguageC<Scalar> lang("double");
  CppAD::cg::LangCDefaultVariableNameGenerator<Scalar> names;
  std::ostringstream code;
  handler.generateCode(code, lang, dep, names);
  os << "void " << name << "(const double *x, double *y) {\n  double v["
     << handler.getTemporaryVariableCount() + 1 << "];\n" << code.str() << "}\n";
}

int main(int argc, char **argv) {
  Model model;
  model.loadFromBinary(argv[1]);
  // Exact quarter turns: the model's 6e-17 cosines become 0 (what dhgen's models carry).
  for (auto &m : model.jointPlacements) {
    Eigen::Matrix3d r = m.rotation();
    Eigen::Vector3d p = m.translation();
    for (int i = 0; i < 9; ++i) r.data()[i] = snap(r.data()[i]);
    for (int i = 0; i < 3; ++i) p[i] = snap(p[i]);
    m.rotation(r);
    m.translation(p);
  }
  for (auto &in : model.inertias) {
    Eigen::Vector3d c = in.lever();
    for (int i = 0; i < 3; ++i) if (std::abs(c[i]) < 1e-14) c[i] = 0;
    auto I = in.inertia().matrix();
    for (int i = 0; i < 9; ++i) if (std::abs(I.data()[i]) < 1e-14) I.data()[i] = 0;
    in = pinocchio::Inertia(in.mass(), c, I);
  }
  const int n = model.nq;
  ADModel ad_model = model.cast<ADS>();
  ADData ad_data(ad_model);
  std::ofstream os(argv[2]);
  os << "#include <math.h>\n";
  {
    ADVec x(3 * n);
    x.setZero();
    CppAD::Independent(x);
    rnea(ad_model, ad_data, x.head(n), x.segment(n, n), x.tail(n));
    ADVec y = ad_data.tau;
    CppAD::ADFun<CGS> fun(x, y);
    emit(os, "rnea", fun, 3 * n);
  }
  {
    ADVec x(n);
    x.setZero();
    CppAD::Independent(x);
    forwardKinematics(ad_model, ad_data, x);
    const auto &m = ad_data.oMi[n];
    ADVec y(12);
    for (int i = 0; i < 9; ++i) y[i] = m.rotation().data()[i];
    for (int i = 0; i < 3; ++i) y[9 + i] = m.translation()[i];
    CppAD::ADFun<CGS> fun(x, y);
    emit(os, "fk", fun, n);
  }
  {
    ADVec x(n);
    x.setZero();
    CppAD::Independent(x);
    Eigen::Matrix<ADS, 6, Eigen::Dynamic> J(6, n);
    J.setZero();
    computeJointJacobian(ad_model, ad_data, x, n, J);  // LOCAL frame of joint n
    // In the world-aligned frame at joint n's origin, as dhgen's J (rotate by oMi[n]).
    const auto &R = ad_data.oMi[n].rotation();
    ADVec y(6 * n);
    for (int j = 0; j < n; ++j) {
      Eigen::Matrix<ADS, 3, 1> v = R * J.col(j).head(3), w = R * J.col(j).tail(3);
      for (int i = 0; i < 3; ++i) { y[6 * j + i] = v[i]; y[6 * j + 3 + i] = w[i]; }
    }
    CppAD::ADFun<CGS> fun(x, y);
    emit(os, "jacobian", fun, n);
  }
  return 0;
}
