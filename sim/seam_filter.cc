#include "sim/seam_filter.h"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <mutex>

namespace cmt {

namespace {

mjfCollision original_box_box = nullptr;

// Rounding allowance (m) on top of the gap allowance when deciding that two boxes abut: far below every
// contact depth (~1e-6 m), far above the rounding of coordinates that are equal in the task (~1e-17 m).
constexpr double kAbutEpsilon = 1e-9;

struct FilterParameters {
  double tau = -1;  // m; negative: the model does not ask for the filter
  double gap = 0;   // m; geoms of abutting boxes are at most this far apart
};

FilterParameters filter_parameters(const mjModel* m) {
  for (int i = 0; i < m->nnumeric; ++i)
    if (std::strcmp(m->names + m->name_numericadr[i], kSeamFilterNumeric) == 0 && m->numeric_size[i] >= 1) {
      const mjtNum* data = m->numeric_data + m->numeric_adr[i];
      return {data[0], m->numeric_size[i] >= 2 ? data[1] : 0.0};
    }
  return {};
}

bool axis_aligned(const mjData* d, int g) {
  const mjtNum* r = d->geom_xmat + 9 * g;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (std::abs(r[3 * i + j] - (i == j ? 1.0 : 0.0)) > 1e-12) return false;
  return true;
}

double lo(const mjModel* m, const mjData* d, int g, int k) {
  return d->geom_xpos[3 * g + k] - m->geom_size[3 * g + k];
}
double hi(const mjModel* m, const mjData* d, int g, int k) {
  return d->geom_xpos[3 * g + k] + m->geom_size[3 * g + k];
}

// An environment box that the robot collides with (a world geom that is a part, not a bounds wall).
bool environment_box(const mjModel* m, int g) {
  return m->geom_bodyid[g] == 0 && m->geom_type[g] == mjGEOM_BOX && (m->geom_conaffinity[g] & 1);
}

// True if environment box n reaches the face of e with outward normal sign * axis `a` (the boxes abut or
// overlap there in the task): a box across a real gap, however narrow, leaves e's face exposed, and the
// robot can enter the gap (in C-space, a slot of any positive width is free space).
bool reaches_face(const mjModel* m, const mjData* d, int e, int n, int a, int sign, double gap) {
  if (sign > 0) return lo(m, d, n, a) <= hi(m, d, e, a) + gap + kAbutEpsilon;
  return hi(m, d, n, a) >= lo(m, d, e, a) - gap - kAbutEpsilon;
}

// True if the face of environment box e with outward normal sign * axis `a` is internal to the solid where
// robot box r touches it: another environment box n reaches that face (reaches_face), and r moved 2 tau
// outward along that normal (out of e) still overlaps n by more than tau along every axis, or, along an axis
// where n's overlap is bounded by a face coplanar with e's face on the same side (the real surface
// continuing over the seam), by more than -tau (r sits a penetration depth below that surface). Then n
// blocks the motion along the normal as much as e does, n's own contact carries the load, and e's contact
// along `a` is a ghost.
bool on_internal_face(const mjModel* m, const mjData* d, int e, int r, int a, int sign,
                      const FilterParameters& p) {
  const double tau = p.tau;
  double rlo[3], rhi[3];
  for (int k = 0; k < 3; ++k) {
    rlo[k] = lo(m, d, r, k);
    rhi[k] = hi(m, d, r, k);
  }
  rlo[a] += sign * 2 * tau;
  rhi[a] += sign * 2 * tau;
  for (int n = 0; n < m->ngeom; ++n) {
    if (n == e || !environment_box(m, n) || !axis_aligned(d, n)) continue;
    if (!reaches_face(m, d, e, n, a, sign, p.gap)) continue;
    bool blocks = true;
    for (int k = 0; k < 3 && blocks; ++k) {
      const double top = std::min(rhi[k], hi(m, d, n, k)), bottom = std::max(rlo[k], lo(m, d, n, k));
      const double overlap = top - bottom;
      if (overlap > tau) continue;
      if (k == a || overlap <= -tau) {
        blocks = false;
        continue;
      }
      // Small overlap: allowed only where it is bounded by n's face coplanar with e's on the same side.
      const bool by_high = hi(m, d, n, k) <= rhi[k] && std::abs(hi(m, d, n, k) - hi(m, d, e, k)) <= tau;
      const bool by_low = lo(m, d, n, k) >= rlo[k] && std::abs(lo(m, d, n, k) - lo(m, d, e, k)) <= tau;
      blocks = by_high || by_low;
    }
    if (blocks) return true;
  }
  return false;
}

int filtered_box_box(const mjModel* m, const mjData* d, mjContact* con, int g1, int g2, mjtNum margin) {
  const int count = original_box_box(m, d, con, g1, g2, margin);
  if (count == 0 || m->nnumeric == 0) return count;
  const FilterParameters p = filter_parameters(m);
  if (p.tau < 0) return count;
  const bool e_is_1 = environment_box(m, g1) && m->geom_bodyid[g2] != 0;
  const bool e_is_2 = environment_box(m, g2) && m->geom_bodyid[g1] != 0;
  if (e_is_1 == e_is_2) return count;  // not a robot-environment pair
  const int e = e_is_1 ? g1 : g2, r = e_is_1 ? g2 : g1;
  if (!axis_aligned(d, g1) || !axis_aligned(d, g2)) return count;
  int kept = 0;
  for (int i = 0; i < count; ++i) {
    // frame[0..2] is the normal from geom1 to geom2; out of e toward the robot:
    mjtNum out[3];
    for (int k = 0; k < 3; ++k) out[k] = e_is_1 ? con[i].frame[k] : -con[i].frame[k];
    int a = -1;
    for (int k = 0; k < 3; ++k)
      if (std::abs(out[k]) > 1 - 1e-9) a = k;
    const bool drop = a >= 0 && on_internal_face(m, d, e, r, a, out[a] > 0 ? 1 : -1, p);
    if (!drop) {
      if (kept != i) con[kept] = con[i];
      ++kept;
    }
  }
  return kept;
}

}  // namespace

void install_seam_contact_filter() {
  static std::once_flag once;
  std::call_once(once, [] {
    original_box_box = mjCOLLISIONFUNC[mjGEOM_BOX][mjGEOM_BOX];
    mjCOLLISIONFUNC[mjGEOM_BOX][mjGEOM_BOX] = filtered_box_box;
  });
}

}  // namespace cmt
