// Seam contact filter (docs/mujoco-scene.md "Seam contact filter"). Where two environment boxes abut, the
// face of one that the other covers is internal to the solid, but MuJoCo collides the robot with each box
// separately: a robot box sliding across the seam, or flush with a wall while resting on a coplanar
// neighbour, overlaps that face by less than it has sunk below the real surface and gets a contact normal
// along it (a "ghost" contact) that stops it. The filter drops a box-box contact on a face of environment box
// E when the robot box, moved a little further out of E along the contact normal, still overlaps another
// environment box that R, flush with E's face, would overlap (which then blocks that motion as E does: E's
// face is internal there). A box across a gap R fits into does not count, however narrow the gap.
#pragma once

namespace cmt {

// Name of the MJCF custom numeric that switches the filter on for a model; its value is the tolerance tau
// in metres (sim/mjcf_export.h MjcfOptions::filter_seam_contacts).
inline constexpr const char* kSeamFilterNumeric = "cmt_seam_filter";

// Replaces MuJoCo's box-box collision function (process-wide, once) with one that calls it and then, for
// models carrying kSeamFilterNumeric, drops the contacts on internal faces. Models without it are unaffected.
void install_seam_contact_filter();

}  // namespace cmt
