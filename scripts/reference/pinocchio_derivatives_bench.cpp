// Times Pinocchio's C++ analytical derivatives (Carpentier & Mansard 2018)
// on a URDF robot (fixed or free-flyer base): computeRNEADerivatives (dtau/dq, dtau/dqd),
// computeABADerivatives (dqdd/dq, dqdd/dqd, Minv), computeMinverse, and rnea
// for scale.
//
// Usage: pinocchio_derivatives_bench ROBOT.urdf[:floating] [...]
//
// States and statistic as pinocchio_bench.cpp: 1000 random states (q in
// [-pi, pi], prismatic joints within their limits, qd in [-2, 2], qdd in
// [-5, 5], tau in [-10, 10]); batches of 1000 calls cycling through them
// after a warm-up; the median and the minimum over 300 batches of the batch
// time / 1000, in ns per call.  A ROBOT.urdf:floating argument has a
// JointModelFreeFlyer root (its quaternion normalised).  The algorithm
// templates are compiled into this file.  Not run in CI; see README.md in
// this folder and derivatives_bench.sh.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "bench_common.hpp"
#include "pinocchio/algorithm/aba.hpp"
#include "pinocchio/algorithm/aba-derivatives.hpp"
#include "pinocchio/algorithm/rnea.hpp"
#include "pinocchio/algorithm/rnea-derivatives.hpp"

namespace {

using namespace bench_common;

void bench(const std::string& arg) {
  // ROBOT.urdf, or ROBOT.urdf:floating for a JointModelFreeFlyer root.
  const std::string suffix = ":floating";
  const bool floating = arg.size() > suffix.size() &&
                        arg.compare(arg.size() - suffix.size(), suffix.size(), suffix) == 0;
  const std::string path = floating ? arg.substr(0, arg.size() - suffix.size()) : arg;
  const pinocchio::Model model = load_model(path, floating);
  pinocchio::Data data(model);
  const int nv = model.nv;

  // (named references: a C++17 lambda cannot capture structured bindings)
  States states = random_states(model);
  // A free flyer's quaternion (q[3..7], drawn as the other coordinates)
  // made a unit one.
  if (floating)
    for (auto& q : states.q) q.segment<4>(3).normalize();
  const auto &q = states.q, &v = states.v, &a = states.a, &tau = states.tau;
  Eigen::MatrixXd dq = Eigen::MatrixXd::Zero(nv, nv),
                  dv = Eigen::MatrixXd::Zero(nv, nv),
                  da = Eigen::MatrixXd::Zero(nv, nv);

  const auto t_rnea = median_and_min_ns_per_call([&](int s) {
    g_sink += pinocchio::rnea(model, data, q[s], v[s], a[s])[0];
  });
  const auto t_drnea = median_and_min_ns_per_call([&](int s) {
    pinocchio::computeRNEADerivatives(model, data, q[s], v[s], a[s], dq, dv,
                                      da);
    g_sink += dq(nv - 1, 0) + dv(nv - 1, 0);
  });
  const auto t_daba = median_and_min_ns_per_call([&](int s) {
    pinocchio::computeABADerivatives(model, data, q[s], v[s], tau[s], dq, dv,
                                     da);
    g_sink += dq(nv - 1, 0) + dv(nv - 1, 0) + da(0, nv - 1);
  });
  const auto t_minv = median_and_min_ns_per_call([&](int s) {
    g_sink += pinocchio::computeMinverse(model, data, q[s])(0, nv - 1);
  });
  std::printf(
      "%-16s nv=%d  rnea %8.1f ns (min %8.1f)  computeRNEADerivatives %8.1f "
      "ns (min %8.1f)  computeABADerivatives %8.1f ns (min %8.1f)  "
      "computeMinverse %8.1f ns (min %8.1f)\n",
      arg.substr(arg.find_last_of('/') + 1).c_str(), nv, t_rnea.first,
      t_rnea.second, t_drnea.first, t_drnea.second, t_daba.first,
      t_daba.second, t_minv.first, t_minv.second);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s ROBOT.urdf[:floating] ...\n", argv[0]);
    return 2;
  }
  std::printf("Pinocchio %s, median (and minimum) ns per call (batches of %d calls)\n",
              PINOCCHIO_VERSION, kBatch);
  for (int i = 1; i < argc; ++i) bench(argv[i]);
  if (g_sink == 12345.678) std::printf("%f\n", g_sink);
  return 0;
}
