#include "sim/seam_filter.h"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <mutex>

namespace cmt {

namespace {

mjfCollision original_box_box = nullptr;

// Rounding allowance (m) when deciding that two boxes abut: far below every contact depth (~1e-6 m), far
// above the rounding of coordinates that are equal in the task (~1e-17 m).
constexpr double kAbutEpsilon = 1e-9;

// The filter's tolerance tau (m) if the model asks for the filter, else a negative number.
double filter_tolerance(const mjModel* m) {
  for (int i = 0; i < m->nnumeric; ++i)
    if (std::strcmp(m->names + m->name_numericadr[i], kSeamFilterNumeric) == 0 && m->numeric_size[i] >= 1)
      return m->numeric_data[m->numeric_adr[i]];
  return -1;
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

// True if environment box n reaches robot box r where r touches the face of e with outward normal sign *
// axis `a`: r, flush with that face, would overlap n along `a` (n's near face lies within r's width of e's
// face). Then the configuration is inside n's C-obstacle too and e's C-face is covered there. In the C-space
// form r is the cube of half size h and the boxes are shrunk by h, so this says the C-space boxes abut or
// overlap: a box across a real gap, however narrow, leaves e's face exposed (in C-space a slot of any
// positive width is free space). In the physical form it says the gap is narrower than the robot part.
bool reaches_face(const mjModel* m, const mjData* d, int e, int n, int r, int a, int sign) {
  const double width = 2 * m->geom_size[3 * r + a];
  if (sign > 0) return lo(m, d, n, a) <= hi(m, d, e, a) + width + kAbutEpsilon;
  return hi(m, d, n, a) >= lo(m, d, e, a) - width - kAbutEpsilon;
}

// True if the face of environment box e with outward normal sign * axis `a` is internal to the solid where
// robot box r touches it: another environment box n reaches r there (reaches_face), and r moved 2 tau
// outward along that normal (out of e) still overlaps n by more than tau along every axis, or, along an axis
// where n's overlap is bounded by a face coplanar with e's face on the same side (the real surface
// continuing over the seam), by more than -tau (r sits a penetration depth below that surface). Then n
// blocks the motion along the normal as much as e does, n's own contact carries the load, and e's contact
// along `a` is a ghost.
bool on_internal_face(const mjModel* m, const mjData* d, int e, int r, int a, int sign, double tau) {
  double rlo[3], rhi[3];
  for (int k = 0; k < 3; ++k) {
    rlo[k] = lo(m, d, r, k);
    rhi[k] = hi(m, d, r, k);
  }
  rlo[a] += sign * 2 * tau;
  rhi[a] += sign * 2 * tau;
  for (int n = 0; n < m->ngeom; ++n) {
    if (n == e || !environment_box(m, n) || !axis_aligned(d, n)) continue;
    if (!reaches_face(m, d, e, n, r, a, sign)) continue;
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
  const double tau = filter_tolerance(m);
  if (tau < 0) return count;
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
    const bool drop = a >= 0 && on_internal_face(m, d, e, r, a, out[a] > 0 ? 1 : -1, tau);
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
