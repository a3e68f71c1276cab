// Times Pinocchio's C++ rnea, crba, nonLinearEffects and aba on a URDF robot
// with a JointModelFreeFlyer root, by the method of dynagen-bench's
// examples/interleaved.rs and examples/floating.rs: 8 states, rounds of
// 2000 calls cycling through them, the functions in alternating order
// within a round (forward on even rounds, backward on odd), the minimum
// over rounds of the per-call time (interference only ever adds time); the
// median over rounds is printed too.
//
// Then the same functions called cold, as examples/floating.rs calls
// dynagen's: before each call a sweep writes one byte in every line of an
// 8 MiB buffer (evicting the code and data from the core's L1s and L2, not
// from the shared L3), each call timed on its own, the median and tenth
// percentile over the samples printed, with those of an empty function
// (the timer's cost, not subtracted).
//
// Usage: pinocchio_floating_bench ROBOT.urdf [ROUNDS] [COLD]   (COLD: cold
// samples a function, default 1000, 0 for none)
//
// DYNAGEN_BENCH_STACK=BYTES makes every call that many bytes deeper in the
// stack, as examples/floating.rs does for dynagen's (floating_bench.sh,
// STACKS).
//
// States: base position in [-1, 1]^3, a uniformly random unit quaternion,
// joints in [-pi, pi], velocities in [-2, 2], accelerations in [-5, 5],
// torques in [-20, 20].  aba and crba are timed with both of Pinocchio's
// conventions (LOCAL, their default, and WORLD).  The algorithm templates are compiled
// into this file, with the flags of floating_bench.sh.  Not run in CI; see
// README.md in this folder.

#include <alloca.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "pinocchio/algorithm/aba.hpp"
#include "pinocchio/algorithm/crba.hpp"
#include "pinocchio/algorithm/rnea.hpp"
#include "bench_common.hpp"

namespace {

constexpr int kStates = 8;
constexpr int kCalls = 2000;

using Clock = std::chrono::steady_clock;

// Keeps the optimiser from dropping a result.
volatile double g_sink = 0.0;

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s ROBOT.urdf [ROUNDS]\n", argv[0]);
    return 2;
  }
  const std::string path = argv[1];
  const int rounds = argc > 2 ? std::atoi(argv[2]) : 200;
  const int samples = argc > 3 ? std::atoi(argv[3]) : 1000;
  // The rest of main, and so every call, `stack` bytes deeper.
  const char* stack_env = std::getenv("DYNAGEN_BENCH_STACK");
  const unsigned long stack = stack_env ? std::strtoul(stack_env, nullptr, 10) : 0;
  volatile char* pad = static_cast<volatile char*>(alloca(stack + 1));
  pad[0] = 0;

  const pinocchio::Model model = bench_common::load_model(path, true);
  pinocchio::Data data(model);
  const int nq = model.nq, nv = model.nv;

  std::mt19937_64 rng(20261125);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<Eigen::VectorXd> q(kStates), v(kStates), a(kStates), tau(kStates);
  for (int s = 0; s < kStates; ++s) {
    q[s].resize(nq);
    for (int j = 0; j < 3; ++j) q[s][j] = unit(rng);
    Eigen::Vector4d quat(normal(rng), normal(rng), normal(rng), normal(rng));
    quat.normalize();
    q[s].segment<4>(3) = quat;  // x, y, z, w
    for (int j = 7; j < nq; ++j) q[s][j] = 3.141592653589793 * unit(rng);
    v[s] = 2.0 * Eigen::VectorXd::NullaryExpr(nv, [&] { return unit(rng); });
    a[s] = 5.0 * Eigen::VectorXd::NullaryExpr(nv, [&] { return unit(rng); });
    tau[s] = 20.0 * Eigen::VectorXd::NullaryExpr(nv, [&] { return unit(rng); });
  }

  using pinocchio::Convention;
  const char* names[] = {"rnea",        "crba (LOCAL)", "nonLinearEffects",
                         "aba (LOCAL)", "aba (WORLD)",  "crba (WORLD)"};
  std::vector<std::function<double(int)>> fs = {
      [&](int s) { return pinocchio::rnea(model, data, q[s], v[s], a[s])[0]; },
      [&](int s) { return pinocchio::crba(model, data, q[s])(0, 0); },
      [&](int s) { return pinocchio::nonLinearEffects(model, data, q[s], v[s])[0]; },
      [&](int s) { return pinocchio::aba(model, data, q[s], v[s], tau[s], Convention::LOCAL)[0]; },
      [&](int s) { return pinocchio::aba(model, data, q[s], v[s], tau[s], Convention::WORLD)[0]; },
      [&](int s) { return pinocchio::crba(model, data, q[s], Convention::WORLD)(0, 0); },
  };
  const int n = static_cast<int>(fs.size());
  // Warm-up.
  for (int k = 0; k < n; ++k)
    for (int i = 0; i < 20 * kCalls; ++i) g_sink = g_sink + fs[k](i & (kStates - 1));

  std::vector<std::vector<double>> per_call(n);
  for (int r = 0; r < rounds; ++r) {
    for (int j = 0; j < n; ++j) {
      const int k = r % 2 == 0 ? j : n - 1 - j;
      // Called directly (not through std::function) in the timed loop.
      double acc = 0.0;
      const auto t0 = Clock::now();
      switch (k) {
        case 0:
          for (int i = 0; i < kCalls; ++i) {
            const int s = i & (kStates - 1);
            acc += pinocchio::rnea(model, data, q[s], v[s], a[s])[0];
          }
          break;
        case 1:
          for (int i = 0; i < kCalls; ++i) acc += pinocchio::crba(model, data, q[i & (kStates - 1)])(0, 0);
          break;
        case 2:
          for (int i = 0; i < kCalls; ++i) {
            const int s = i & (kStates - 1);
            acc += pinocchio::nonLinearEffects(model, data, q[s], v[s])[0];
          }
          break;
        case 3:
          for (int i = 0; i < kCalls; ++i) {
            const int s = i & (kStates - 1);
            acc += pinocchio::aba(model, data, q[s], v[s], tau[s], Convention::LOCAL)[0];
          }
          break;
        case 4:
          for (int i = 0; i < kCalls; ++i) {
            const int s = i & (kStates - 1);
            acc += pinocchio::aba(model, data, q[s], v[s], tau[s], Convention::WORLD)[0];
          }
          break;
        default:
          for (int i = 0; i < kCalls; ++i) acc += pinocchio::crba(model, data, q[i & (kStates - 1)], Convention::WORLD)(0, 0);
          break;
      }
      const auto t1 = Clock::now();
      g_sink = g_sink + acc;
      per_call[k].push_back(std::chrono::duration<double, std::nano>(t1 - t0).count() / kCalls);
    }
  }

  std::printf("Pinocchio %s C++, %s with JointModelFreeFlyer (nq=%d, nv=%d), %d rounds of %d calls, stack offset %lu\n",
              PINOCCHIO_VERSION, path.substr(path.find_last_of('/') + 1).c_str(), nq, nv, rounds, kCalls, stack);
  for (int k = 0; k < n; ++k) {
    std::vector<double>& t = per_call[k];
    const double best = *std::min_element(t.begin(), t.end());
    std::nth_element(t.begin(), t.begin() + t.size() / 2, t.end());
    std::printf("pinocchio %-18s min %8.1f ns  median %8.1f ns\n", names[k], best, t[t.size() / 2]);
  }
  if (samples <= 0) return 0;

  // Cold calls: the functions above and an empty one, in alternating order.
  fs.push_back([&](int) { return 0.0; });
  const int m = static_cast<int>(fs.size());
  std::vector<unsigned char> buf(8u << 20);
  std::vector<std::vector<double>> cold(m);
  for (int r = 0; r < samples; ++r) {
    for (int j = 0; j < m; ++j) {
      const int k = r % 2 == 0 ? j : m - 1 - j;
      for (size_t i = 0; i < buf.size(); i += 64) buf[i] = static_cast<unsigned char>(buf[i] + 1);
      g_sink = g_sink + buf[static_cast<size_t>(r) * 64 % buf.size()];
      const auto t0 = Clock::now();
      const double x = fs[k](r & (kStates - 1));
      const auto t1 = Clock::now();
      g_sink = g_sink + x;
      cold[k].push_back(std::chrono::duration<double, std::nano>(t1 - t0).count());
    }
  }
  std::printf("Pinocchio %s, cold: %d calls each, each after an 8 MiB sweep\n", PINOCCHIO_VERSION, samples);
  for (int k = 0; k < m; ++k) {
    std::vector<double>& t = cold[k];
    std::sort(t.begin(), t.end());
    std::printf("pinocchio %-18s cold median %8.1f ns  p10 %8.1f ns\n", k < n ? names[k] : "(empty: the timer)",
                t[t.size() / 2], t[t.size() / 10]);
  }
  return 0;
}
