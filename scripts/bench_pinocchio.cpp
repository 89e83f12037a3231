// Time Pinocchio's C++ RNEA, CRBA, ABA and frame Jacobian (the `pin` wheel's library) on a URDF
// exported by `osrl robot --urdf`, at the same states as crates/dynamics/benches/dynamics.rs.
// Built and run by scripts/bench_pinocchio_cpp.sh; prints one JSON object (ns per call).
#include <pinocchio/parsers/urdf.hpp>
#include <pinocchio/algorithm/aba.hpp>
#include <pinocchio/algorithm/crba.hpp>
#include <pinocchio/algorithm/frames.hpp>
#include <pinocchio/algorithm/jacobian.hpp>
#include <pinocchio/algorithm/rnea.hpp>
#include <pinocchio/algorithm/kinematics.hpp>
#include <chrono>
#include <cstdio>
#include <string>

template <class F> double ns_per_call(F f) {
  double best = 1e30;
  // Best of 300 short repetitions (2,000 calls, about a millisecond each: shorter than a
  // scheduler's time slice, so that on a loaded machine the best is a run without preemption).
  for (int rep = 0; rep < 300; ++rep) {
    const int n = 2000;
    auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < n; ++i) f();
    auto t1 = std::chrono::steady_clock::now();
    best = std::min(best, std::chrono::duration<double, std::nano>(t1 - t0).count() / n);
  }
  return best;
}

int main(int argc, char** argv) {
  std::printf("{");
  for (int r = 1; r < argc; r += 2) {
    const std::string name = argv[r], path = argv[r + 1];
    pinocchio::Model model;
    pinocchio::urdf::buildModel(path, model);
    pinocchio::Data data(model);
    const int n = model.nv;
    Eigen::VectorXd q(n), qd(n), qdd(n);
    for (int i = 0; i < n; ++i) { q[i] = 0.1 * i + 0.2; qd[i] = 0.3 - 0.05 * i; qdd[i] = 0.5 + 0.1 * i; }
    const auto fid = model.getFrameId("ee_link");
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(6, n);
    volatile double sink = 0;
    double fkj = ns_per_call([&] { J.setZero(); pinocchio::computeFrameJacobian(model, data, q, fid, pinocchio::LOCAL_WORLD_ALIGNED, J); sink = J(0, 0); });
    double rnea = ns_per_call([&] { sink = pinocchio::rnea(model, data, q, qd, qdd)[0]; });
    double crba = ns_per_call([&] { sink = pinocchio::crba(model, data, q)(0, 0); });
    double aba = ns_per_call([&] { sink = pinocchio::aba(model, data, q, qd, qdd)[0]; });
    std::printf("%s\"%s/fk_jacobian_ns\": %.1f, \"%s/rnea_ns\": %.1f, \"%s/crba_ns\": %.1f, \"%s/aba_ns\": %.1f",
                r > 1 ? ", " : "", name.c_str(), fkj, name.c_str(), rnea, name.c_str(), crba, name.c_str(), aba);
  }
  std::printf("}\n");
  return 0;
}
