// Times Pinocchio's C++ rnea, crba, nonLinearEffects and aba on a URDF robot
// (fixed base).
//
// Usage: pinocchio_bench [--mimic] ROBOT.urdf [ROBOT.urdf ...]
//
// With --mimic the robots after it are read with the URDF parser's mimic
// option; Pinocchio's aba (and its sparse Cholesky) refuse mimic joints, so
// their forward dynamics is timed as what a user then writes: crba,
// nonLinearEffects and Eigen's dense LDLT of M (the upper triangle crba
// fills, made whole) solving M qdd = tau - h.
//
// For each robot: 1000 random states (q uniform in [-pi, pi] for revolute
// joints and within the limits for prismatic ones, qd in [-2, 2], qdd in
// [-5, 5], tau in [-10, 10]); each algorithm is called in batches of 1000
// calls cycling through the states, after a warm-up; the per-call time of a
// batch is the batch time / 1000, and the median over 300 batches is
// printed, in ns per call, and on a second line the minimum.  The algorithm templates are compiled into this
// file (no PINOCCHIO_ENABLE_TEMPLATE_INSTANTIATION), with the flags of the
// build script.  Not run in CI; see README.md in this folder.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "bench_common.hpp"
#include "pinocchio/algorithm/aba.hpp"
#include "pinocchio/algorithm/crba.hpp"
#include "pinocchio/algorithm/rnea.hpp"
#include <Eigen/Cholesky>

namespace {

using namespace bench_common;

void bench(const std::string& path, bool mimic) {
  // (the header-only models of make_pinocchio_models.py: ROBOT.urdf:mimic is
  // the URDF parser's model with its mimic option)
  const std::string file = path.substr(path.find_last_of('/') + 1);
  const pinocchio::Model model = mimic ? pinocchio_models::build(file + ":mimic") : load_model(path, false);
  pinocchio::Data data(model);
  const int nv = model.nv;

  // (named references: a C++17 lambda cannot capture structured bindings)
  const States states = random_states(model);
  const auto &q = states.q, &v = states.v, &a = states.a, &tau = states.tau;

  const auto t_rnea = median_and_min_ns_per_call([&](int s) {
    g_sink += pinocchio::rnea(model, data, q[s], v[s], a[s])[0];
  });
  const auto t_crba = median_and_min_ns_per_call([&](int s) {
    g_sink += pinocchio::crba(model, data, q[s])(0, 0);
  });
  const auto t_nle = median_and_min_ns_per_call([&](int s) {
    g_sink += pinocchio::nonLinearEffects(model, data, q[s], v[s])[0];
  });
  const bool has_mimic = !model.mimicking_joints.empty();
  const auto t_aba = has_mimic ? median_and_min_ns_per_call([&](int s) {
    pinocchio::crba(model, data, q[s]);
    data.M.triangularView<Eigen::StrictlyLower>() = data.M.transpose().triangularView<Eigen::StrictlyLower>();
    const Eigen::VectorXd h = pinocchio::nonLinearEffects(model, data, q[s], v[s]);
    g_sink += data.M.ldlt().solve(tau[s] - h)[0];
  }) : median_and_min_ns_per_call([&](int s) {
    g_sink += pinocchio::aba(model, data, q[s], v[s], tau[s])[0];
  });
  const char* fd = has_mimic ? "crba+nle+ldlt" : "aba";
  std::printf("%-28s nv=%d  rnea %8.1f ns  crba %8.1f ns  nle %8.1f ns  %s %8.1f ns\n",
              file.c_str(), nv, t_rnea.first, t_crba.first, t_nle.first, fd, t_aba.first);
  std::printf("%-28s   min   rnea %8.1f ns  crba %8.1f ns  nle %8.1f ns  %s %8.1f ns\n",
              "", t_rnea.second, t_crba.second, t_nle.second, fd, t_aba.second);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s [--mimic] ROBOT.urdf [ROBOT.urdf ...]\n", argv[0]);
    return 2;
  }
  std::printf("Pinocchio %s, median (and minimum) ns per call over %d batches of %d calls\n",
              PINOCCHIO_VERSION, kBatches, kBatch);
  bool mimic = false;
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "--mimic") {
      mimic = true;
    } else {
      bench(argv[i], mimic);
    }
  }
  if (g_sink == 12345.678) std::printf("%f\n", g_sink);
  return 0;
}
