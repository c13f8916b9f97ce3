#include "swemps/swe/balanced_bed_slope.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "swemps/neighbors/parallel.hpp"
#include "swemps/swe/bed_slope.hpp"
#include "support_nodes.hpp"

namespace swemps::swe {

namespace {

using support::drop_ground_beyond_rims;
using support::gather_nodes;
using support::NodeBuffer;

// Plain sqrt, not std::hypot: slopes and gradients are far from overflow, and hypot's guards
// cost more than the arithmetic (measured 3.6 % of the valley flood's run under this term).
double norm(double x, double y) { return std::sqrt(x * x + y * y); }

// Pairs closer than this have no direction and exert no force (as in the scheme's force).
constexpr double kCoincident = 1e-12;
// Each Newton step on (*) wets or dries at least one node; a particle's support holds a few
// hundred nodes at the widest radius, so this is never reached by a well-posed sum.
constexpr int kMaxLevelSteps = 1000;
// The level is exact once the wet set stops changing; round-off leaves an excess of about
// 1e-16 of the depth, which this stops on.
constexpr double kLevelTolerance = 1e-13;
// The eigenvalues of the Jacobian J that a Newton step on the plane's slope divides by, and
// that the exact solve on a wet set (plane_on_wet_set) needs. J scales with the share of the
// support that is wet: I for a full support, about 1/2 across a straight shore, 0.03-0.5 where
// the wet nodes cover a corner of a wide support on a hillside (measured on the valley flood).
// What holds no plane is a J small in one direction against the other (wet nodes almost on a
// line, where dividing would turn round-off into slope), so a partly wet support's eigenvalues
// are floored at a fraction of the largest, kWetSetConditioning, and at kSmallestWetJacobian
// when even the largest is that small (a node or two).
//
// Why relative: absolute floors of 0.5 (the steps) and 0.1 (the exact solve) held back every
// step of such a corner's plane, as if its J were I: on the valley flood's first 90 minutes
// 126,000 planes converged linearly (the residual falling about 10 % a step) into the cap of
// kMaxPlaneSteps, ending an order of magnitude short of the root, and took 30 % of this term's
// time. Floored at 1/50 of the largest they reach the root in 5 to 7 steps or settle on their
// wet set at once (docs/performance.md, "Third lever").
constexpr double kWetSetConditioning = 0.02;
constexpr double kSmallestWetJacobian = 1e-3;
// The plane of every node (an interior particle's, J about I) needs J's smallest eigenvalue at
// least this; a support that is not all wet goes on to its wet set.
constexpr double kSmallestFullJacobian = 0.5;
// A jump to the next node that a tilting plane wets goes this fraction past it, so that the
// node is wet at the next step.
constexpr double kBreakpointMargin = 1e-9;
// Newton's steps on the slope, for a particle whose support is partly dry (an interior one needs
// none: plane_on_wet_set): a few as nodes change from wet to dry, then the exact solve on the
// settled set. Measured on Thacker's bowl before the exact solves: at most 23 with the halving
// below.
constexpr int kMaxPlaneSteps = 30;
// Tries of wet_set_slope before Newton's steps take over.
constexpr int kWetSetTries = 4;
// A step halved this many times in a row without lowering the residual ends the search at the
// slope it was taken from, where the residual is least along it (a film held by three nodes, on
// the valley flood): more halvings only walked the step towards nothing, thirty times over.
constexpr int kMaxHalvings = 8;
// The slope is settled when a step moves it by less than this (a slope, dimensionless), or
// when the depth gradient is held to round-off (this times depth / h).
constexpr double kSlopeTolerance = 1e-10;
constexpr double kResidualTolerance = 1e-13;
// An interior particle's plane has the slope grad h_i + (the bed's slope through the kernel):
// never steeper than the two magnitudes together. A shore particle's plane, fitted where part of
// the support is dry, may be steeper. Steepest of all is the plane at a bore's toe, where a tiny
// depth sum with a large gradient is held only by a sliver of wet nodes (slope 0.39 where the
// surface's is 0.015, a film ahead of a 1 mm sheet); a plane is cut back to this many times the
// sum. Measured: the thin-film hard case's fastest particle 6 m/s uncut, 0.21-0.26 m/s cut (0.19
// with the point bed); Thacker's L1 2.05 % uncut, 2.0 % cut at 1.5 or 2 times, 2.4 % at 1 time
// (shore planes do need more than the sum), 2.2 % at 3 times.
constexpr double kSteepestFactor = 2.0;

// The magnitude of the bed's slope seen through the kernel, |sum_k grad w_k (z_k - z_mean)| over
// every node of the support (the lattice reaches past the domain, so the support is full).
double bed_gradient(const NodeBuffer& b) {
  double weight = 0.0, weighted_z = 0.0;
  for (std::size_t k = 0; k < b.z.size(); ++k) {
    weight += b.w[k];
    weighted_z += b.w[k] * b.z[k];
  }
  if (!(weight > 0.0)) return 0.0;
  const double mean = weighted_z / weight;
  double gx = 0.0, gy = 0.0;
  for (std::size_t k = 0; k < b.z.size(); ++k) {
    gx += b.wx[k] * (b.z[k] - mean);
    gy += b.wy[k] * (b.z[k] - mean);
  }
  return norm(gx, gy);
}

// The floor under a partly wet support's eigenvalues, given the largest.
double wet_set_floor(double largest_eigenvalue) {
  return std::max(kWetSetConditioning * largest_eigenvalue, kSmallestWetJacobian);
}

// J^-1 (gx, gy) for the symmetric J = [[jxx, jxy], [jxy, jyy]], with J's eigenvalues taken as
// no less than wet_set_floor.
std::array<double, 2> solve_floored(double jxx, double jxy, double jyy, double gx, double gy) {
  const double mean = 0.5 * (jxx + jyy);
  const double spread = std::sqrt(0.25 * (jxx - jyy) * (jxx - jyy) + jxy * jxy);
  const double large = mean + spread, small = mean - spread;
  const double floor = wet_set_floor(large);
  if (!(small >= floor)) {
    // Eigenvectors: (cos t, sin t) for the large eigenvalue, with tan 2t = 2 jxy / (jxx - jyy).
    const double t = 0.5 * std::atan2(2.0 * jxy, jxx - jyy);
    const double ex = std::cos(t), ey = std::sin(t);
    const double along = (ex * gx + ey * gy) / std::max(large, floor);
    const double across = (-ey * gx + ex * gy) / std::max(small, floor);
    return {along * ex - across * ey, along * ey + across * ex};
  }
  const double det = jxx * jyy - jxy * jxy;
  return {(jyy * gx - jxy * gy) / det, (jxx * gy - jxy * gx) / det};
}

// The plane whose water over a given set of wet nodes holds i's depth sum and its gradient:
// with the wet set fixed, (*) and the gradient equation are linear in (eta_i, s). With, over the
// wet nodes, W = sum w, Z = sum w z, M = sum w o, G = sum grad w, Z' = sum grad w z and
// J = sum grad w o^T, the first gives eta_i = (h_i + Z - M . s) / W, and the second
// (J - G M^T / W) s = grad h_i - G (h_i + Z) / W + Z'. The plane is the root sought when the set
// it wets is the set it was solved on (exact); it is not when it wets another (other_set). A
// system near singular (wet nodes few or almost on a line) holds no plane (undetermined).
//
// Why: Newton's steps with the floored Jacobian converge linearly where a shore halves the
// support (measured on the valley flood: 63 % of the planes were a shore particle's, taking 8
// steps on average and 30 for one in sixteen), and each step is two passes over the nodes; on a
// settled wet set this solve is exact in one pass, and an interior particle needs no step at all.
// `wet` == nullptr: every node. `wetted` != nullptr: the set the plane wets is written there
// (wet_set_slope's next guess).
enum class WetSetFit { exact, other_set, undetermined };
enum class Nodes { all, wet_set };  // the floor: kSmallestFullJacobian, or wet_set_floor

WetSetFit plane_on_wet_set(double depth, double grad_h_x, double grad_h_y, const NodeBuffer& b,
                           const std::vector<char>* wet, Nodes nodes, std::array<double, 2>& slope,
                           std::vector<char>* wetted = nullptr,
                           double* level_at_particle = nullptr) {
  const std::size_t count = b.z.size();
  double w = 0.0, wz = 0.0, mx = 0.0, my = 0.0, gx = 0.0, gy = 0.0, zx = 0.0, zy = 0.0;
  double jxx = 0.0, jxy = 0.0, jyx = 0.0, jyy = 0.0;
  // A dry node's weights times 0 rather than a branch (whether a node is wet follows no
  // pattern a branch predictor learns): adding the zeros leaves every sum as it was, bit for
  // bit, and the sums keep the nodes' order.
  const char* flag = wet ? wet->data() : nullptr;
  for (std::size_t k = 0; k < count; ++k) {
    const double on = flag ? static_cast<double>(flag[k]) : 1.0;
    const double wk = on * b.w[k], wxk = on * b.wx[k], wyk = on * b.wy[k];
    w += wk;
    wz += wk * b.z[k];
    mx += wk * b.ox[k];
    my += wk * b.oy[k];
    gx += wxk;
    gy += wyk;
    zx += wxk * b.z[k];
    zy += wyk * b.z[k];
    jxx += wxk * b.ox[k];
    jxy += wxk * b.oy[k];
    jyx += wyk * b.ox[k];
    jyy += wyk * b.oy[k];
  }
  if (!(w > 0.0)) return WetSetFit::undetermined;
  const double axx = jxx - gx * mx / w, axy = jxy - gx * my / w;
  const double ayx = jyx - gy * mx / w, ayy = jyy - gy * my / w;
  // The symmetric part's smallest eigenvalue: about 1 for a full support, 1/2 across a straight
  // shore.
  const double mean = 0.5 * (axx + ayy), off = 0.5 * (axy + ayx);
  const double spread = std::sqrt(0.25 * (axx - ayy) * (axx - ayy) + off * off);
  const double smallest =
      nodes == Nodes::all ? kSmallestFullJacobian : wet_set_floor(mean + spread);
  if (!(mean - spread >= smallest)) return WetSetFit::undetermined;
  const double held = (depth + wz) / w;
  const double rx = grad_h_x - gx * held + zx, ry = grad_h_y - gy * held + zy;
  const double det = axx * ayy - axy * ayx;
  const double sx = (ayy * rx - axy * ry) / det, sy = (axx * ry - ayx * rx) / det;
  const double level = held - (mx * sx + my * sy) / w;
  if (!std::isfinite(sx) || !std::isfinite(sy)) return WetSetFit::undetermined;
  slope = {sx, sy};
  if (level_at_particle) *level_at_particle = level;
  // The set the plane wets, against the set it was solved on, in one pass that vectorises
  // (no branch, no early exit).
  if (wetted) wetted->resize(count);
  char* out = wetted ? wetted->data() : nullptr;
  const double *z = b.z.data(), *ox = b.ox.data(), *oy = b.oy.data();
  int changed = 0;
#pragma omp simd reduction(| : changed)
  for (std::size_t k = 0; k < count; ++k) {
    const int wet_here = z[k] - sx * ox[k] - sy * oy[k] < level ? 1 : 0;
    if (out) out[k] = static_cast<char>(wet_here);
    changed |= wet_here ^ (flag ? static_cast<int>(flag[k]) : 1);
  }
  return changed == 0 ? WetSetFit::exact : WetSetFit::other_set;
}

// The plane of a partly dry support by its wet set alone: from a first guess of the wet set in
// b.wet, solve on the set (plane_on_wet_set), take the set that plane wets, and again, until a
// plane wets the set it was solved on: the exact root, in two passes over the nodes a try.
// Returns false when no try of kWetSetTries settles, or a set holds no plane.
//
// Why: on the valley flood 70 % of the planes belong to particles whose support is partly dry,
// and Newton's steps from a level surface took 3.5 steps for each of them on average, each
// step a level (2.7 passes) and a residual pass. With these tries first (from the two guesses
// in surface_slope), Newton's steps over the first hour fell from 11.4 to 1.05 million and the
// whole run from 144 s to 116 s on one thread (docs/method.md).
bool wet_set_slope(double depth, double grad_h_x, double grad_h_y, NodeBuffer& b,
                   std::array<double, 2>& slope, double& level) {
  for (int tries = 0; tries < kWetSetTries; ++tries) {
    const WetSetFit fit = plane_on_wet_set(depth, grad_h_x, grad_h_y, b, &b.wet, Nodes::wet_set,
                                           slope, &b.wetted, &level);
    if (fit == WetSetFit::exact) return true;
    if (fit == WetSetFit::undetermined) return false;
    std::swap(b.wet, b.wetted);
  }
  return false;
}

// The slope s of the plane surface eta(x) = eta_i + s . (x - x_i) whose water over the nodes,
// (eta(x_k) - z_k)+, gives through i's kernel both i's summed depth and its gradient:
//
//   sum_k w_k (eta_i + s . o_k - z_k)+ = h_i,   sum_k grad w_k (eta_i + s . o_k - z_k)+ = grad h_i.
//
// For each s, the first equation is (*) of the header over the tilted bed z_k - s . o_k
// (level_holding); Newton's method then finds s from the second, with the Jacobian
// J = sum_wet grad w_k (o_k - o_mean)^T (o_mean: the wet weights' centroid, through d eta_i/d s).
// A step that raises the residual (it crossed a change of the wet set) is halved.
// `level_at_particle`: the plane's level at the particle where an exact solve on a wet set gave
// the slope returned, uncut, else NaN; `interior_plane`: that wet set was every node.
std::array<double, 2> surface_slope(double depth, double h, double grad_h_x, double grad_h_y,
                                    const std::vector<char>& occupied, std::size_t own_node,
                                    NodeBuffer& b, double& level_at_particle,
                                    bool& interior_plane) {
  level_at_particle = std::numeric_limits<double>::quiet_NaN();
  interior_plane = false;
  double all_wet_level = level_at_particle, settled_level = level_at_particle;
  // Every node wet: the plane of grad h_i and the bed's slope through the kernel. When it wets
  // them all it is the root; when it does not, it is still the plane a support too thinly wet to
  // hold one falls back on (below).
  std::array<double, 2> all_wet{};
  WetSetFit interior = plane_on_wet_set(depth, grad_h_x, grad_h_y, b, nullptr, Nodes::all, all_wet,
                                        &b.wetted_by_all_wet_plane, &all_wet_level);
  // A partly dry support: lower ground beyond a rim left out (drop_ground_beyond_rims), then its
  // wet set, first guessed as the nodes under the level that holds the depth sum with no slope,
  // then (where that set holds no plane, as a film's few nodes on a hillside do not) as the
  // nodes the all-wet plane wets.
  std::array<double, 2> by_wet_set{};
  bool exact = interior == WetSetFit::exact;
  bool solved = exact;
  double level = std::numeric_limits<double>::quiet_NaN();
  if (!solved) {
    level = level_holding(b.z, b.w, depth);
    if (drop_ground_beyond_rims(occupied, own_node, depth, b, level)) {
      interior = plane_on_wet_set(depth, grad_h_x, grad_h_y, b, nullptr, Nodes::all, all_wet,
                                  &b.wetted_by_all_wet_plane, &all_wet_level);
      exact = interior == WetSetFit::exact;
      solved = exact;
    }
  }
  const std::size_t count = b.z.size();
  b.tilted.resize(count);
  if (!solved) {
    if (std::isfinite(level)) {
      b.wet.resize(count);
      for (std::size_t k = 0; k < count; ++k) b.wet[k] = b.z[k] < level ? 1 : 0;
      solved = wet_set_slope(depth, grad_h_x, grad_h_y, b, by_wet_set, settled_level);
    }
  }
  if (!solved && interior == WetSetFit::other_set) {
    b.wet = b.wetted_by_all_wet_plane;
    solved = wet_set_slope(depth, grad_h_x, grad_h_y, b, by_wet_set, settled_level);
  }
  // Neither settles (a few per cent of the partly dry supports on the valley flood): Newton's
  // steps from a level surface.
  double sx = exact ? all_wet[0] : (solved ? by_wet_set[0] : 0.0);  // the slope being tried
  double sy = exact ? all_wet[1] : (solved ? by_wet_set[1] : 0.0);
  if (!solved) {
    b.wet.assign(count, 0);
    b.previous_wet.assign(count, 2);  // no set yet
  }
  bool newton_settled = false;  // ended on an exact solve on a settled wet set
  double base_x = 0.0, base_y = 0.0, step_x = 0.0, step_y = 0.0;
  double previous_residual = std::numeric_limits<double>::infinity();
  int halvings = 0;  // in a row
  for (int steps = 0; !solved && steps < kMaxPlaneSteps; ++steps) {
    for (std::size_t k = 0; k < count; ++k) b.tilted[k] = b.z[k] - sx * b.ox[k] - sy * b.oy[k];
    const double level = level_holding(b.tilted, b.w, depth);
    if (!std::isfinite(level)) break;
    // Over the wet nodes: the weights and their first moments (for o_mean), the residual's sum
    // G, and the moments of grad w that make J = sum grad w o^T - (sum grad w) o_mean^T.
    double wet = 0.0, mx = 0.0, my = 0.0, gx = 0.0, gy = 0.0;
    double slope_x = 0.0, slope_y = 0.0, jxx = 0.0, jxy = 0.0, jyy = 0.0;
    for (std::size_t k = 0; k < count; ++k) {
      b.wet[k] = b.tilted[k] < level ? 1 : 0;
      if (!b.wet[k]) continue;
      const double d = level - b.tilted[k];
      wet += b.w[k];
      mx += b.w[k] * b.ox[k];
      my += b.w[k] * b.oy[k];
      gx += b.wx[k] * d;
      gy += b.wy[k] * d;
      slope_x += b.wx[k];
      slope_y += b.wy[k];
      jxx += b.wx[k] * b.ox[k];
      jxy += 0.5 * (b.wx[k] * b.oy[k] + b.wy[k] * b.ox[k]);
      jyy += b.wy[k] * b.oy[k];
    }
    if (!(wet > 0.0)) break;
    const double rx = grad_h_x - gx, ry = grad_h_y - gy, residual = norm(rx, ry);
    // Round-off: the gradient held to 1e-13 of the depth over the support.
    if (residual <= kResidualTolerance * depth / h) break;
    // The wet set has settled: the root on it, if it wets the same set, is exact. A set of one
    // or a few nodes in a line holds no plane: the residual cannot fall, and Newton's steps only
    // tilt the plane by the floored step, 30 times over (measured: 1.4 million planes of the
    // valley flood, a film of a millimetre on a hillside held by one node). Such a step jumps to
    // the next node the plane wets (below).
    bool undetermined = false;  // on b.wet, which becomes b.previous_wet below
    if (b.wet == b.previous_wet) {
      std::array<double, 2> settled{};
      const WetSetFit fit = plane_on_wet_set(depth, grad_h_x, grad_h_y, b, &b.wet, Nodes::wet_set,
                                             settled, nullptr, &settled_level);
      if (fit == WetSetFit::exact) {
        sx = settled[0];
        sy = settled[1];
        newton_settled = true;
        break;
      }
      undetermined = fit == WetSetFit::undetermined;
    }
    std::swap(b.wet, b.previous_wet);
    if (residual > previous_residual && norm(step_x, step_y) > kSlopeTolerance) {
      if (++halvings > kMaxHalvings) {
        sx = base_x;
        sy = base_y;
        break;
      }
      step_x *= 0.5;
      step_y *= 0.5;
      sx = base_x + step_x;
      sy = base_y + step_y;
      continue;
    }
    previous_residual = residual;
    halvings = 0;
    mx /= wet;
    my /= wet;
    // J symmetrised: the step is a Newton step on the symmetric part.
    jxx -= slope_x * mx;
    jxy -= 0.5 * (slope_x * my + slope_y * mx);
    jyy -= slope_y * my;
    auto [ux, uy] = solve_floored(jxx, jxy, jyy, rx, ry);
    if (undetermined) {
      // Along the step the residual stays what it is until a dry node (of this step's set, now in
      // previous_wet) comes under the plane: node k's height above it, tilted_k - level, falls as
      // t u . (o_k - o_mean). Jump to the first such node. None: the water is a film on the bed, as
      // a lone particle's is, and takes the all-wet plane.
      double first = std::numeric_limits<double>::infinity();
      for (std::size_t k = 0; k < count; ++k) {
        const double approach = ux * (b.ox[k] - mx) + uy * (b.oy[k] - my);
        if (!b.previous_wet[k] && approach > 0.0)
          first = std::min(first, (b.tilted[k] - level) / approach);
      }
      if (!std::isfinite(first)) {
        if (interior != WetSetFit::undetermined) {
          sx = all_wet[0];
          sy = all_wet[1];
        }
        break;
      }
      const double jump = std::max(1.0, first * (1.0 + kBreakpointMargin));
      ux *= jump;
      uy *= jump;
    }
    base_x = sx;
    base_y = sy;
    step_x = ux;
    step_y = uy;
    sx += ux;
    sy += uy;
    // A small step is still taken: near rest the whole slope is that small.
    if (norm(ux, uy) <= kSlopeTolerance) break;
  }
  // The cut (kSteepestFactor); the bed's slope is needed only for a plane steeper than the depth
  // sum's slope alone allows, which few are.
  const double magnitude = norm(sx, sy), depth_slope = norm(grad_h_x, grad_h_y);
  bool cut = false;
  if (magnitude > kSteepestFactor * depth_slope) {
    const double steepest = kSteepestFactor * (depth_slope + bed_gradient(b));
    if (magnitude > steepest) {
      sx *= steepest / magnitude;
      sy *= steepest / magnitude;
      cut = true;
    }
  }
  if (!cut && exact) {
    level_at_particle = all_wet_level;
    interior_plane = true;
  } else if (!cut && (solved || newton_settled)) {
    level_at_particle = settled_level;
  }
  return {sx, sy};
}

// One row's pairs, gathered so that the sums below are a tight loop over contiguous values.
struct PairBuffer {
  std::vector<double> dx, dy, volume, inverse_h, inverse_omega;
};

struct RowGradients {
  double depth_x, depth_y;        // grad h_i at i's own radius
  double pressure_x, pressure_y;  // the scheme's pressure sum, per unit g
};

// grad h: the gradient of i's depth sum at i's radius (eq 7 differentiated in x_i, ghosts
// included as they are in the sum); P: the scheme's own pressure sum, which the total replaces.
//
// Why gathered: computed pair by pair in place, with a division for each kernel, this loop was
// 40 % of the term's own time on the valley flood (measured by sampling); gathered, the
// kernels vectorise as in the scheme's force pass.
template <class K>
RowGradients depth_and_pressure_gradients(const particles::SweParticles& p,
                                          const neighbors::NeighborList& nl, std::size_t i,
                                          PairBuffer& b) {
  const auto row = nl.row(i);
  const std::size_t count = row.size();
  for (auto* v : {&b.dx, &b.dy, &b.volume, &b.inverse_h, &b.inverse_omega}) v->resize(count);
  for (std::size_t k = 0; k < count; ++k) {
    const std::uint32_t j = row[k];
    b.dx[k] = p.x[i] - p.x[j];
    b.dy[k] = p.y[i] - p.y[j];
    b.volume[k] = p.volume[j];
    b.inverse_h[k] = 1.0 / p.smoothing_length[j];
    b.inverse_omega[k] = 1.0 / p.omega[j];
  }
  const double inverse_hi = 1.0 / p.smoothing_length[i];
  const double scale_i = K::sigma() * inverse_hi * inverse_hi * inverse_hi;
  const double inverse_omega_i = 1.0 / p.omega[i];
  double gx = 0.0, gy = 0.0, px = 0.0, py = 0.0;
#pragma omp simd reduction(+ : gx, gy, px, py)
  for (std::size_t k = 0; k < count; ++k) {
    const double r = std::sqrt(b.dx[k] * b.dx[k] + b.dy[k] * b.dy[k]);
    const double inverse_r = r > kCoincident ? 1.0 / r : 0.0;  // coincident: no direction
    const double hj = b.inverse_h[k];
    const double wi = scale_i * K::shape_slope(r * inverse_hi);  // dW/dr <= 0
    const double wj = K::sigma() * hj * hj * hj * K::shape_slope(r * hj);
    const double own = b.volume[k] * wi * inverse_r;
    gx += own * b.dx[k];
    gy += own * b.dy[k];
    const double pressure =
        b.volume[k] * 0.5 * (wi * inverse_omega_i + wj * b.inverse_omega[k]) * inverse_r;
    px += pressure * b.dx[k];
    py += pressure * b.dy[k];
  }
  return {gx, gy, px, py};
}

// The plane of every fluid particle into `planes`, and the scheme's pressure force taken back
// from the accelerations (the plane's force follows once the planes agree: apply()).
template <class K>
void find_planes(const BedSource& bed, const BedLattice& lattice, std::vector<char>& occupied,
                 std::vector<std::size_t>& marked, ParticlePlanes& planes, StepContext& c) {
  auto& p = c.particles;
  const std::size_t n = p.fluid_count();
  sample_bed_at_particles(bed, p);
  const double g = c.settings.gravity_m_s2;
  // The nodes that hold water: those within half a particle's spacing, 0.5 sqrt(A_i), of it and
  // the one nearest it, ghosts included (their water is the mirror image of their particle's, on
  // the nodes mirrored beyond the domain). A particle seeded on a node marks only that node; one
  // spread over several cells (a thin sheet, a finger of a lake) marks the nodes its water covers.
  // Only the nodes the last step marked are cleared: the lattice spans the whole domain, which
  // a flood fills only in part (the valley flood: 169,000 nodes, at most some 10,000 marked by
  // its 3,000 particles), and a clear of all of them every step was work for nothing.
  if (occupied.size() != lattice.node_count()) {
    occupied.assign(lattice.node_count(), 0);
    marked.clear();
  }
  for (const std::size_t node : marked) occupied[node] = 0;
  marked.clear();
  const auto mark = [&](std::size_t node) {
    if (node >= occupied.size() || occupied[node]) return;
    occupied[node] = 1;
    marked.push_back(node);
  };
  for (std::size_t i = 0; i < p.size(); ++i) {
    mark(lattice.nearest_node(p.x[i], p.y[i]));
    lattice.for_each_node_offset_within(
        p.x[i], p.y[i], std::sqrt(0.5 * p.area[i]),
        [&](double, double, double, double, LatticeNode node) { mark(node.index); });
  }
#pragma omp parallel if (n > static_cast <std::size_t>(parallel_threshold))
  {
    NodeBuffer nodes;
    PairBuffer pairs;
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      const double hi = p.smoothing_length[i];
      const auto [grad_h_x, grad_h_y, px, py] =
          depth_and_pressure_gradients<K>(p, c.neighbors, i, pairs);
      gather_nodes<K>(lattice, p.x[i], p.y[i], hi, nodes);
      double level = 0.0;
      bool interior = false;
      const auto [sx, sy] =
          surface_slope(p.depth[i], hi, grad_h_x, grad_h_y, occupied,
                        lattice.nearest_node(p.x[i], p.y[i]), nodes, level, interior);
      planes.slope_x[i] = sx;
      planes.slope_y[i] = sy;
      // The plane's level at x_i, and whether it wets the whole support (the nodes beyond a
      // rim, dropped by surface_slope, are not part of it): given by the exact solve that found
      // the plane for most, found over the tilted nodes for the rest.
      if (!std::isfinite(level)) {
        nodes.tilted.resize(nodes.z.size());
        for (std::size_t k = 0; k < nodes.z.size(); ++k)
          nodes.tilted[k] = nodes.z[k] - sx * nodes.ox[k] - sy * nodes.oy[k];
        level = level_holding(nodes.tilted, nodes.w, p.depth[i]);
        interior = std::isfinite(level);
        for (std::size_t k = 0; k < nodes.z.size() && interior; ++k)
          interior = nodes.tilted[k] < level;
      }
      planes.level[i] = level;
      planes.interior[i] = interior ? 1 : 0;
      c.accel_x[i] += g * px;
      c.accel_y[i] += g * py;
    }
  }
}

}  // namespace

double level_holding(std::span<const double> z, std::span<const double> w, double depth) {
  double weight = 0.0, weighted_z = 0.0;
  for (std::size_t k = 0; k < z.size(); ++k) {
    weight += w[k];
    weighted_z += w[k] * z[k];
  }
  if (!(weight > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  // Every node wet: sum w (eta - z) = depth. The function below is >= its all-wet line, so
  // this eta is at or above the root, and Newton's steps from there descend onto it.
  double level = (depth + weighted_z) / weight;
  for (int step = 0; step < kMaxLevelSteps; ++step) {
    // A dry node's weight times 0, not a branch (as in plane_on_wet_set): the same sums.
    double held = 0.0, wet_weight = 0.0;
    for (std::size_t k = 0; k < z.size(); ++k) {
      const double wet_w = static_cast<double>(z[k] < level) * w[k];
      held += wet_w * (level - z[k]);
      wet_weight += wet_w;
    }
    const double excess = held - depth;
    if (!(excess > kLevelTolerance * depth) || !(wet_weight > 0.0)) break;
    const double next = level - excess / wet_weight;
    if (!(next < level)) break;  // round-off: the root is reached
    level = next;
  }
  return level;
}

void BalancedBedSlope::apply(StepContext& context) {
  auto& p = context.particles;
  planes_.resize(p.fluid_count());
  with_kernel_shape(context.kernel.shape(), [&](const auto& kernel) {
    using K = std::decay_t<decltype(kernel)>;
    find_planes<K>(*bed_, *lattice_, occupied_, marked_, planes_, context);
  });
  arrangement_error_.remove(p, context.neighbors, context.kernel.shape(), planes_);
  const double g = context.settings.gravity_m_s2;
  parallel_for(p.fluid_count(), [&](std::size_t i) {
    context.accel_x[i] -= g * planes_.slope_x[i];
    context.accel_y[i] -= g * planes_.slope_y[i];
  });
}

}  // namespace swemps::swe
