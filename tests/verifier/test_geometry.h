// Lookups shared by the verifier tests.
#pragma once

#include "models/cspace.h"

namespace cmt::test {

// The face whose outward normal is `normal` and whose closure contains p, or -1.
inline int face_at(const CSpace& c, const Vec3& normal, const Vec3& p) {
  for (const Face& f : c.faces())
    if (f.normal.dot(normal) > 1 - 1e-12 && c.distance_to_atom(p, f.id) < 1e-9) return f.id;
  return -1;
}

}  // namespace cmt::test
