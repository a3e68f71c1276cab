// Shared by pinocchio_bench.cpp and pinocchio_derivatives_bench.cpp: the
// timing (median over batches of the per-call time, after a warm-up) and
// the random states of a fixed-base robot (q uniform in [-pi, pi] for
// revolute joints and within the limits for prismatic ones, qd in [-2, 2],
// qdd in [-5, 5], tau in [-10, 10]).

#pragma once

#include <algorithm>
#include <chrono>
#include <random>
#include <string>
#include <utility>
#include <vector>

// pinocchio_models.hpp is written by make_pinocchio_models.py (see
// pinocchio_build.sh): the models, built without the URDF parser's
// prebuilt library, so that everything compiles with -march=native.
#include "pinocchio_models.hpp"

namespace bench_common {

constexpr int kStates = 1000;
constexpr int kBatch = 1000;
constexpr int kBatches = 300;
constexpr int kWarmupBatches = 20;

using Clock = std::chrono::steady_clock;

// The model of the URDF file at `path` (by its file name), with a
// JointModelFreeFlyer root if `floating`.
inline pinocchio::Model load_model(const std::string& path, bool floating) {
  const std::string file = path.substr(path.find_last_of('/') + 1);
  return pinocchio_models::build(floating ? file + ":floating" : file);
}

// Keeps the optimiser from dropping a result.
inline double g_sink = 0.0;

// The median and the minimum over the batches of the per-call time (the
// minimum is what a batch no other process interrupted takes).
template <class F>
std::pair<double, double> median_and_min_ns_per_call(F&& call) {
  for (int b = 0; b < kWarmupBatches; ++b)
    for (int i = 0; i < kBatch; ++i) call(i % kStates);
  std::vector<double> per_call(kBatches);
  for (int b = 0; b < kBatches; ++b) {
    const auto t0 = Clock::now();
    for (int i = 0; i < kBatch; ++i) call(i % kStates);
    const auto t1 = Clock::now();
    per_call[b] =
        std::chrono::duration<double, std::nano>(t1 - t0).count() / kBatch;
  }
  const double min = *std::min_element(per_call.begin(), per_call.end());
  std::nth_element(per_call.begin(), per_call.begin() + kBatches / 2,
                   per_call.end());
  return {per_call[kBatches / 2], min};
}

template <class F>
double median_ns_per_call(F&& call) {
  return median_and_min_ns_per_call(call).first;
}

struct States {
  std::vector<Eigen::VectorXd> q, v, a, tau;
};

inline States random_states(const pinocchio::Model& model) {
  const int nv = model.nv;
  std::mt19937_64 rng(20240611);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  States s{std::vector<Eigen::VectorXd>(kStates), std::vector<Eigen::VectorXd>(kStates),
           std::vector<Eigen::VectorXd>(kStates), std::vector<Eigen::VectorXd>(kStates)};
  for (int k = 0; k < kStates; ++k) {
    s.q[k].resize(model.nq);
    for (int j = 0; j < model.nq; ++j) {
      const double lo = model.lowerPositionLimit[j];
      const double hi = model.upperPositionLimit[j];
      const bool prismatic = hi - lo < 1.0;  // the finger joints (0..0.04 m)
      s.q[k][j] = prismatic ? lo + (hi - lo) * 0.5 * (unit(rng) + 1.0)
                            : 3.141592653589793 * unit(rng);
    }
    s.v[k] = 2.0 * Eigen::VectorXd::NullaryExpr(nv, [&] { return unit(rng); });
    s.a[k] = 5.0 * Eigen::VectorXd::NullaryExpr(nv, [&] { return unit(rng); });
    s.tau[k] = 10.0 * Eigen::VectorXd::NullaryExpr(nv, [&] { return unit(rng); });
  }
  return s;
}

}  // namespace bench_common
