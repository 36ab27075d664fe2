// Seam contact filter (docs/mujoco-scene.md "Seams and ghost contacts"). Where two environment boxes abut,
// the face of one that the other covers is internal to the solid, but MuJoCo collides the robot with each box
// separately: a robot box sliding across the seam overlaps the first box's internal face by a little and,
// when that is less than its penetration below the real surface, gets a contact normal along the internal
// face (a "ghost" contact) that stops it. The filter drops a box-box contact when the point just outside the
// environment box's contact face lies inside another environment box, i.e. when the face is internal there.
#pragma once

namespace cmt {

// Name of the MJCF custom numeric that switches the filter on for a model; its value is the tolerance tau
// in metres (sim/mjcf_export.h MjcfOptions::filter_seam_contacts).
inline constexpr const char* kSeamFilterNumeric = "cmt_seam_filter";

// Replaces MuJoCo's box-box collision function (process-wide, once) with one that calls it and then, for
// models carrying kSeamFilterNumeric, drops the contacts on internal faces. Models without it are unaffected.
void install_seam_contact_filter();

}  // namespace cmt
