// MuJoCo 2.2 MJCF scene of a task (contracts.md `cmt export-mjcf`): the robot is one body with slide joints
// x, y, z whose joint positions are the configuration-space point in metres; environment parts and bounds
// walls are world geoms. What is emitted, and why each contact and solver option has its value, is in
// docs/mujoco-scene.md.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "models/loaded_task.h"

namespace cmt {

struct MjcfOptions {
  // Integration step, s. Contact time constants are tied to it (solref_timesteps).
  double timestep = 0.001;
  // Robot mass, kg; with `damping` it sets the velocity time constant m/b of the generalized damper.
  double robot_mass = 1.0;
  // Joint damping b of the generalized damper (Buckley §3.2), N·s/m. m/b = 10 ms = 10 timesteps: the
  // commanded velocity is reached within ~50 ms, so the body behaves first-order on motion time scales, and
  // MuJoCo's Euler integrator treats joint damping implicitly, so any b is stable.
  double damping = 100.0;
  // Ratio of frictional to normal constraint impedance (elliptic cones); > 1 makes sticking stiffer.
  double impratio = 10.0;
  // Post-processing iterations of MuJoCo's noslip solver: removes the creep of the soft friction constraint.
  int noslip_iterations = 10;
  // Main (Newton) solver iterations and tolerance.
  int solver_iterations = 100;
  double solver_tolerance = 1e-10;
  // Contact time constant solref[0] in timesteps; MuJoCo's stiffest safe value is 2 (it clamps below that).
  double solref_timesteps = 2.0;
  // Constraint impedance d (solimp dmin = dmax): fraction of the constraint force that is rigid.
  double solimp = 0.99;
  // C-space form: grow every C-space box by 2h into neighbouring solids (other boxes, the outside of the
  // bounds) before shrinking it by h, so that the robot cube cannot slip into the 2h slots that shrinking
  // leaves between boxes that share a face (docs/mujoco-scene.md "Seams"). Off only for tests that show the
  // slots.
  bool close_seams = true;
};

// Facts about an exported scene that a simulator needs to interpret it.
struct SceneInfo {
  double meters_per_unit = 1;  // scene length = task length x this
  double reference_half_size =
      0;                      // half size h of the reference cube (task units): the robot in C-space form
  double wall_thickness = 0;  // thickness of the bounds walls before shrinking (task units); 0 without bounds
  bool cspace_form = false;   // true: robot = cube of half size h, C-space parts shrunk by h
  // C-space form: per task.cspace part, the box emitted before shrinking by h (task units): the part's box
  // grown into its neighbours (MjcfOptions::close_seams), or the bounding box of a convex part.
  std::vector<AxisBox> cspace_boxes;
};

// The MJCF text. Throws std::runtime_error if a convex C-space part is too thin to be represented.
std::string mjcf_xml(const LoadedTask& task, const MjcfOptions& options = {}, SceneInfo* info = nullptr);

// Writes mjcf_xml(task, options) to `file`. Throws std::runtime_error naming the file on I/O errors.
void write_mjcf(const LoadedTask& task, const std::filesystem::path& file, const MjcfOptions& options = {});

}  // namespace cmt
