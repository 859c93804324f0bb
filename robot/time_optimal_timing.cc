#include "robot/time_optimal_timing.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>

namespace sortcell::robot {
namespace {

// The path may be run at most this many times faster than planned (x = sdot^2 at most its square):
// where the plan stands nearly still (its ends) the limits bound nothing, and the time saved beyond
// this is nil.
constexpr double kMaxSpeedUp = 100;
constexpr double kMaxX = kMaxSpeedUp * kMaxSpeedUp;
// |a| below this: the joint's limit does not involve u at this sample (the path does not move it).
constexpr double kNoU = 1e-12;

// The limits at one sample: lower <= a u + b x + c <= upper for every joint, and x <= x_max.
struct SampleLimits {
  Joints a, b, c, lower, upper;
  double x_max = kMaxX;
};

struct Interval {
  double lo = 0, hi = 0;
  bool empty() const { return !(lo <= hi); }
};

// A bound u >= p x + r (a lower line) or u <= p x + r (an upper line).
struct ULine {
  double p = 0, r = 0;
  double At(double x) const { return p * x + r; }
};

// The bounds on u at one sample, as lines in x, and the bounds that fall on x alone.
struct UBounds {
  std::array<ULine, 7> lower{}, upper{};
  int n_lower = 0, n_upper = 0;
  Interval x{0, kMaxX};
};

// The sample's limits as bounds on u; with `next`, also x + 2 delta u in next (the step to the
// next sample, delta apart, lands where the end can still be reached from).
UBounds Bounds(const SampleLimits& s, const Interval* next, double delta) {
  UBounds b;
  b.x.hi = std::min(s.x_max, kMaxX);
  for (int j = 0; j < 6; ++j) {
    const double lo = s.lower[j] - s.c[j], hi = s.upper[j] - s.c[j];
    if (std::abs(s.a[j]) > kNoU) {
      const ULine from_lo{-s.b[j] / s.a[j], lo / s.a[j]}, from_hi{-s.b[j] / s.a[j], hi / s.a[j]};
      b.lower[b.n_lower++] = s.a[j] > 0 ? from_lo : from_hi;
      b.upper[b.n_upper++] = s.a[j] > 0 ? from_hi : from_lo;
    } else if (s.b[j] > 0) {
      b.x.lo = std::max(b.x.lo, lo / s.b[j]);
      b.x.hi = std::min(b.x.hi, hi / s.b[j]);
    } else if (s.b[j] < 0) {
      b.x.lo = std::max(b.x.lo, hi / s.b[j]);
      b.x.hi = std::min(b.x.hi, lo / s.b[j]);
    } else if (lo > 0 || hi < 0) {
      b.x = {1, 0};  // Not even standing still keeps this joint's limit.
    }
  }
  if (next) {
    b.lower[b.n_lower++] = {-1 / (2 * delta), next->lo / (2 * delta)};
    b.upper[b.n_upper++] = {-1 / (2 * delta), next->hi / (2 * delta)};
  }
  return b;
}

// The x at which some u keeps every bound: where each lower line lies below each upper line.
Interval FeasibleX(const UBounds& b) {
  Interval x = b.x;
  for (int k = 0; k < b.n_lower; ++k) {
    for (int m = 0; m < b.n_upper; ++m) {
      const double coefficient = b.lower[k].p - b.upper[m].p, rhs = b.upper[m].r - b.lower[k].r;
      if (coefficient > 0)
        x.hi = std::min(x.hi, rhs / coefficient);
      else if (coefficient < 0)
        x.lo = std::max(x.lo, rhs / coefficient);
      else if (rhs < 0)
        return {1, 0};
    }
  }
  return x;
}

// The largest u that keeps every bound at x.
double LargestU(const UBounds& b, double x) {
  double u = std::numeric_limits<double>::infinity();
  for (int m = 0; m < b.n_upper; ++m) u = std::min(u, b.upper[m].At(x));
  double least = -std::numeric_limits<double>::infinity();
  for (int k = 0; k < b.n_lower; ++k) least = std::max(least, b.lower[k].At(x));
  return std::max(u, least);  // Round-off may cross the two by a hair.
}

using LimitsAt = std::function<SampleLimits(int k)>;

// The speed limits as a bound on x, and rest at both ends: a sample where the path moves (q' != 0)
// can only be passed at rest there.
double SpeedBound(const JointTrajectory& path, const Joints& speed, int k) {
  double x_max = kMaxX;
  const bool end = k == 0 || k == path.size() - 1;
  for (int j = 0; j < 6; ++j) {
    const double rate = std::abs(path.qd[k][j]);
    if (rate == 0) continue;
    x_max = end ? 0.0 : std::min(x_max, std::pow(speed[j] / rate, 2));
  }
  return x_max;
}

std::vector<int> Grid(int size, int stride) {
  std::vector<int> samples;
  for (int k = 0; k < size - 1; k += stride) samples.push_back(k);
  if (size > 0) samples.push_back(size - 1);
  return samples;
}

PathTiming Solve(const JointTrajectory& path, int stride, const LimitsAt& limits_at) {
  if (stride < 1)
    throw std::invalid_argument("TimeOptimalTiming: stride must be >= 1 (got " + std::to_string(stride) + ")");
  if (!(path.dt > 0)) throw std::invalid_argument("TimeOptimalTiming: the path's dt must be positive");
  PathTiming timing;
  timing.samples = Grid(path.size(), stride);
  const int n = static_cast<int>(timing.samples.size());
  if (n == 0) return timing;
  std::vector<SampleLimits> limits(n);
  for (int i = 0; i < n; ++i) limits[i] = limits_at(timing.samples[i]);
  const auto delta = [&](int i) { return path.dt * (timing.samples[i + 1] - timing.samples[i]); };
  // Backward: from which x at each sample the end is still reachable.
  std::vector<Interval> reachable(n);
  reachable[n - 1] = FeasibleX(Bounds(limits[n - 1], nullptr, 0));
  for (int i = n - 2; i >= 0 && !reachable[i + 1].empty(); --i) {
    reachable[i] = FeasibleX(Bounds(limits[i], &reachable[i + 1], delta(i)));
  }
  if (std::any_of(reachable.begin(), reachable.end(), [](const Interval& x) { return x.empty(); })) return timing;
  // Forward: as fast as those sets allow.
  timing.t.assign(n, 0.0);
  double x = reachable[0].hi;
  for (int i = 0; i + 1 < n; ++i) {
    const double u = LargestU(Bounds(limits[i], &reachable[i + 1], delta(i)), x);
    const double x_next = std::clamp(x + 2 * delta(i) * u, reachable[i + 1].lo, reachable[i + 1].hi);
    const double step = 2 * delta(i) / (std::sqrt(x) + std::sqrt(x_next));
    if (!std::isfinite(step)) {
      timing.t.clear();
      return timing;
    }
    timing.t[i + 1] = timing.t[i] + step;
    x = x_next;
  }
  timing.feasible = true;
  return timing;
}

void CheckPositive(const char* what, const Joints& v) {
  if (!(v.array() > 0).all() || !v.allFinite()) {
    throw std::invalid_argument(std::string("TimeOptimalTiming: ") + what + " must be positive on every joint");
  }
}

}  // namespace

double PathTiming::At(int k) const {
  if (t.empty()) return 0.0;
  const auto after = std::upper_bound(samples.begin(), samples.end(), k);
  if (after == samples.begin()) return t.front();
  if (after == samples.end()) return t.back();
  const size_t i = static_cast<size_t>(after - samples.begin()) - 1;
  const double w = static_cast<double>(k - samples[i]) / (samples[i + 1] - samples[i]);
  return t[i] + w * (t[i + 1] - t[i]);
}

PathTiming TimeOptimalTiming(const JointTrajectory& path, const JointMotionLimits& limits, int stride) {
  CheckPositive("speed limits", limits.speed);
  CheckPositive("acceleration limits", limits.acceleration);
  return Solve(path, stride, [&](int k) {
    SampleLimits s;
    s.a = path.qd[k];
    s.b = path.qdd[k];
    s.c.setZero();
    s.upper = limits.acceleration;
    s.lower = -limits.acceleration;
    s.x_max = SpeedBound(path, limits.speed, k);
    return s;
  });
}

PathTiming TimeOptimalTiming(const JointTrajectory& path, const Joints& speed, const TorqueBudget& budget, int stride) {
  CheckPositive("speed limits", speed);
  CheckPositive("torque limits", budget.limits);
  // The torque is M(q) qdd + C(q, qd) qd + g(q) + friction: with qd = q' sdot and qdd = q' u + q'' x,
  // a = M q', b = M q'' + C(q, q') q', c = g. Friction, which grows with sdot rather than x, is
  // allowed for at its largest (at the speed limit) by widening the budget.
  const Joints friction = Ur5Dynamics::Friction(speed, Joints::Zero());
  const Joints allowed = budget.fraction * budget.limits + friction;
  return Solve(path, stride, [&](int k) {
    SampleLimits s;
    s.a = budget.dynamics->Inertial(path.q[k], Joints::Zero(), path.qd[k]);
    s.b = budget.dynamics->Inertial(path.q[k], path.qd[k], path.qdd[k]);
    s.c = budget.dynamics->Gravity(path.q[k]);
    s.upper = allowed;
    s.lower = -allowed;
    s.x_max = SpeedBound(path, speed, k);
    return s;
  });
}

}  // namespace sortcell::robot
