// MuJoCo 2.2 MJCF scene of a task (docs/contracts.md `cmt export-mjcf`): the robot is one body with slide
// joints x, y, z whose joint positions are the configuration-space point in metres; environment parts and
// bounds walls are world geoms. What is emitted, and why each contact and solver option has its value, is in
// docs/mujoco-scene.md.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "models/loaded_task.h"

namespace cmt {

// The soft-surface-layer scene (soft_layer_scene(), docs/mujoco-scene.md "Concave edges and the soft surface
// layer"): with the seam filter it is the rollouts' scene (sim/rollout.h calibrated_scene()), the one in
// which `cmt calibrate-friction` passes every criterion, at concave edges too (docs/rollouts.md
// "Calibration"). The exporter's own defaults (MjcfOptions{}) stay the stiff contact at 1 ms.

// Integration step, s. With the soft surface layer below, 0.5 ms left the admittance loop erratic in concave
// edges (sliding 18 % off Coulomb there, 2.3 % on a face); at 0.25 ms every calibration criterion holds
// (docs/rollouts.md "Calibration"). Contacts have a time constant of 2 steps, so they
// are also 2x stiffer than at 0.5 ms. Cost: 2x the steps of 0.5 ms.
inline constexpr double kSoftLayerTimestep = 0.00025;
// Impedance at the surface: a contact 0-1 um deep is soft (d = 0.01: 99 % of its force is the soft
// constraint's spring), so when MuJoCo's convex friction model pushes a sliding contact outward at ~mu x the
// slip speed, the contact gives way inside the layer instead of separating, and stays active. At a concave
// edge that matters: with d = 0.99 everywhere each face's contact lifted off while sliding and the other
// face's friction wedged the robot into the edge (sliding up to 73 % slower than Coulomb).
inline constexpr double kSoftLayerSolimpDmin = 0.01;
// Impedance below the layer: stiff (the constant d = 0.99 of stiff_scene), so a loaded contact stops within
// ~1 um of the surface (penetration at 1 in/s <= 3.5e-6 m, calibration) instead of sinking through a soft
// contact.
inline constexpr double kSoftLayerSolimpDmax = 0.99;
// Layer depth, m (MuJoCo's r = contact.dist; box-box contacts report half the overlap, so ~2 um of overlap).
// Absolute, not scaled with the task: it acts on the contact's micrometre-scale hop and penetration, which
// depend on speed and stiffness, not on the scene's size. For the built-in tasks (scene scales 0.088-0.46 m)
// it is <= 1/9 of the atom tolerance (1e-4 x scale >= 8.8e-6 m) and 1/600 of the smallest clearance
// (peg_in_hole_real, 6.35e-4 m). Thinner (3e-7 m) lets the hop through again (edge sliding 33 % off
// Coulomb); thicker (1e-5 m, measured at 0.5 ms) made sticking robots creep (1.1e-5 of their speed) and 12
// calibration cases stick/slide against Coulomb.
inline constexpr double kSoftLayerSolimpWidth = 1e-6;

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
  // Constraint impedance d(r) (MJCF solimp "dmin dmax width"; midpoint 0.5 and power 2, MuJoCo's defaults):
  // the fraction of the constraint force that is rigid, rising from dmin at the surface to dmax at depth
  // `width` (MuJoCo's r = the contact's `dist`, in metres, absolute: not scaled with the task). A soft
  // surface layer below a stiff body keeps a sliding contact active instead of letting it hop off
  // (docs/mujoco-scene.md "Concave edges and the soft surface layer").
  // Default: stiff at every depth (d = 0.99; the width then does not matter).
  double solimp_dmin = 0.99;
  double solimp_dmax = 0.99;
  double solimp_width = 0.001;  // m
  // C-space form: grow every C-space box by 2h into neighbouring solids (other boxes, the outside of the
  // bounds) before shrinking it by h, so that the robot cube cannot slip into the 2h slots that shrinking
  // leaves between boxes that share a face (docs/mujoco-scene.md "Seams"). Off only for tests that show the
  // slots.
  bool close_seams = true;
  // Seam contact filter (sim/seam_filter.h), as a fraction of the scene scale: > 0 writes the MJCF custom
  // numeric that switches it on, with tolerance tau = this x scale (m). Off by default (the exporter's tests
  // check raw box-box contacts); the rollouts set it (SimOptions::scene).
  double seam_filter_relative = 0;
  // C-space form: each convex C-space part (up to 29) meets its own robot geom, a small copy of the part, and
  // is emitted shrunk toward the copy's centre, so that the scene's part is the task's exactly
  // (docs/mujoco-scene.md "Convex C-space parts"). Off: the part is eroded by the cube and the scene cuts it
  // back near its sharp edges and corners (in_convex_cut_back); kept for the tests that show the cut-back.
  bool convex_copies = true;
};

// The soft-surface-layer scene: kSoftLayer* on top of the defaults.
MjcfOptions soft_layer_scene();

// Facts about an exported scene that a simulator needs to interpret it.
// A convex C-space part as the scene emits it, before the robot cube is added back: n . x <= e per facet
// (task units), the part eroded by the cube (its facets on the bounds first moved out by 2h).
struct ErodedPart {
  std::vector<Vec3> normals;
  std::vector<double> offsets;
};

struct SceneInfo {
  double meters_per_unit = 1;  // scene length = task length x this
  double reference_half_size =
      0;                      // half size h of the reference cube (task units): the robot in C-space form
  double wall_thickness = 0;  // thickness of the bounds walls before shrinking (task units); 0 without bounds
  bool cspace_form = false;   // true: robot = cube of half size h, C-space parts shrunk by h
  // C-space form: per task.cspace part, the box emitted before shrinking by h (task units): the part's box
  // grown into its neighbours (MjcfOptions::close_seams), or the bounding box of a convex part.
  std::vector<AxisBox> cspace_boxes;
  // C-space form: per task.cspace part, its eroded half-spaces (empty for a box and for a convex part met by
  // a robot copy, MjcfOptions::convex_copies: both are represented exactly).
  std::vector<ErodedPart> eroded_parts;
  // C-space form: how many convex parts meet a robot copy.
  int convex_copies = 0;
};

// True when x is in the cut-back of a convex C-space part P (docs/mujoco-scene.md "Convex C-space parts"):
// the scene represents P by (P eroded by the cube) + cube, cut back near its edges and corners that are not
// box-shaped. That is, x lies inside P by more than tol but not inside the scene's part by more than tol (a
// robot resting on the scene's surface below P's), or x lies on P's surface (within tol) but farther than tol
// from the scene's part (a robot starting there is in the air). False for boxes and the physical form.
bool in_convex_cut_back(const SceneInfo& info, const CSpace& cspace, const Vec3& x, double tol);
// The first case of in_convex_cut_back alone: x inside P by more than tol, not inside the scene's part by
// more than tol. A robot there moves through empty scene where the task has solid (campaign task 224 of the
// slanted seed 9: a spring slides off a ramp's slope onto the cube's shelf 9.5 mm below the slope's convex
// edge, along it and out through the end face), so a rollout passing there is no outcome of the task.
bool in_convex_cut_back_interior(const SceneInfo& info, const CSpace& cspace, const Vec3& x, double tol);

// The MJCF text. Throws std::runtime_error if a convex C-space part is too thin to be represented.
std::string mjcf_xml(const LoadedTask& task, const MjcfOptions& options = {}, SceneInfo* info = nullptr);

// Writes mjcf_xml(task, options) to `file`. Throws std::runtime_error naming the file on I/O errors.
void write_mjcf(const LoadedTask& task, const std::filesystem::path& file, const MjcfOptions& options = {});

}  // namespace cmt
