// UR5 kinematics per call: D-H FK (closed form and per-link chain), URDF chain FK, and the analytic
// IK returning every solution, each FK-checked. Reference on this machine kind (DESIGN.md section 5):
// ROS ur_kinematics ~1.95 us per IK call without FK checks, ~0.22 us per FK call.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "robot/ik_selection.h"
#include "robot/ur5_ik.h"
#include "robot/ur5_kinematics.h"
#include "robot/urdf_chain.h"

namespace {

using namespace sortcell::robot;

std::vector<Joints> RandomConfigurations(int n) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  std::vector<Joints> qs(n);
  for (Joints& q : qs) {
    for (int i = 0; i < 6; ++i) q[i] = angle(rng);
  }
  return qs;
}

std::vector<Eigen::Isometry3d> FlangePoses(const std::vector<Joints>& qs) {
  std::vector<Eigen::Isometry3d> poses;
  for (const Joints& q : qs) poses.push_back(FlangePose(q));
  return poses;
}

void BM_FlangePose(benchmark::State& state) {
  const auto qs = RandomConfigurations(1024);
  size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(FlangePose(qs[i++ & 1023]));
}
BENCHMARK(BM_FlangePose);

void BM_ForwardKinematicsAllLinks(benchmark::State& state) {
  const auto qs = RandomConfigurations(1024);
  size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(ForwardKinematicsAll(qs[i++ & 1023]));
}
BENCHMARK(BM_ForwardKinematicsAllLinks);

void BM_UrdfChainFk(benchmark::State& state) {
  const UrdfChain chain = UrdfChain::FromFile(SORTCELL_SOURCE_DIR "/models/ur5/ur5.urdf");
  const auto qs = RandomConfigurations(1024);
  size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(chain.TipPose(qs[i++ & 1023]));
}
BENCHMARK(BM_UrdfChainFk);

// All solutions (8 for almost every random pose), each checked by FK and de-duplicated.
void BM_SolveIkAllSolutionsChecked(benchmark::State& state) {
  const auto qs = RandomConfigurations(1024);
  const auto poses = FlangePoses(qs);
  size_t i = 0;
  long solutions = 0;
  for (auto _ : state) {
    const IkResult ik = SolveIk(poses[i++ & 1023], 0.0);
    solutions += ik.count;
    benchmark::DoNotOptimize(ik);
  }
  state.counters["solutions_per_call"] = benchmark::Counter(static_cast<double>(solutions) / state.iterations());
}
BENCHMARK(BM_SolveIkAllSolutionsChecked);

// IK plus the choice of the nearest valid solution (limits, links above the table).
void BM_SolveIkAndSelectNearest(benchmark::State& state) {
  const auto qs = RandomConfigurations(1024);
  const auto poses = FlangePoses(qs);
  size_t i = 0;
  for (auto _ : state) {
    const size_t k = i++ & 1023;
    benchmark::DoNotOptimize(SelectNearest(SolveIk(poses[k], qs[k][5]), qs[k]));
  }
}
BENCHMARK(BM_SolveIkAndSelectNearest);

}  // namespace

BENCHMARK_MAIN();
