// MJCF export (docs/mujoco-scene.md). Everything is emitted as text; no MuJoCo call is needed to write a
// scene.
#include "sim/mjcf_export.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "models/task_loader.h"
#include "sim/seam_filter.h"

namespace cmt {

namespace {

// Collision classes (MuJoCo collides two geoms when contype1 & conaffinity2 or contype2 & conaffinity1).
// Robot parts (bit 1) meet environment parts; the reference cube (bit 2) meets the bounds walls, which
// constrain the reference point only. Environment and walls have contype 0, so they never collide with each
// other.
constexpr int kPartBit = 1;
constexpr int kReferenceBit = 2;
// C-space form: convex part k (in task order) and its robot copy (below) share bit 4 << k, so each copy meets
// its own part only. Bits 2..30 of the positive int: 29 copies; further convex parts are eroded by the cube.
constexpr int kFirstCopyBit = 4;
constexpr int kMaxConvexCopies = 29;

// Shortest decimal text that reads back to the same double, so the scene carries the task's exact values.
std::string num(double v) {
  if (v == 0) v = 0;  // no "-0"
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), v);
  return std::string(buffer, result.ptr);
}

std::string vec(const Vec3& v) { return num(v.x()) + " " + num(v.y()) + " " + num(v.z()); }

// XML comments may not contain "--".
std::string comment_text(std::string text) {
  for (std::size_t i; (i = text.find("--")) != std::string::npos;) text.replace(i, 2, "- -");
  return text;
}

AxisBox bounding_box(const ConvexPart& part) {
  if (part.shape == ConvexPart::Shape::kBox) return part.box;
  AxisBox b{Vec3::Constant(std::numeric_limits<double>::infinity()),
            Vec3::Constant(-std::numeric_limits<double>::infinity())};
  for (const Vec3& v : part.vertices) {
    b.min = b.min.cwiseMin(v);
    b.max = b.max.cwiseMax(v);
  }
  return b;
}

// The erosion P ⊖ cube_h of a convex C-obstacle P = {x : n_i·x <= d_i}: the cube's support in direction n is
// h‖n‖₁, so P ⊖ cube_h = {x : n_i·x <= d_i − h‖n_i‖₁}. Its vertices are the feasible intersections of plane
// triples. Empty when the erosion has no interior (the part is thinner than 2h somewhere). A facet on the
// bounds (CSpace::covered_by_bounds: only the solid outside lies beyond it) is first moved out by 2h, as
// boxes are grown into the outside of the bounds (grow_into_neighbours): the eroded part then reaches the
// shrunk wall geom, and the cube cannot slip into the 2h slot between them (docs/mujoco-scene.md "Seams").
ErodedPart eroded_part(const ConvexObstacle& ob, const CSpace& cspace, double h) {
  ErodedPart out;
  out.normals = ob.normals;
  for (std::size_t i = 0; i < ob.normals.size(); ++i) {
    // A facet the outside of the bounds covers moves out by 2h first (grown into that solid, as boxes are).
    const double grow = cspace.covered_by_bounds(ob.normals[i], ob.offsets[i]) ? 2 * h : 0.0;
    out.offsets.push_back(ob.offsets[i] + grow - h * ob.normals[i].lpNorm<1>());
  }
  return out;
}

// The vertices of {x : n_i . x <= e_i} (unit normals): the feasible intersections of plane triples, each
// within `tolerance` of every half-space, without repeats closer than `tolerance`.
std::vector<Vec3> polytope_vertices(const std::vector<Vec3>& normals, const std::vector<double>& e,
                                    double tolerance) {
  const std::size_t n = normals.size();
  std::vector<Vec3> points;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      for (std::size_t k = j + 1; k < n; ++k) {
        Eigen::Matrix3d a;
        a.row(0) = normals[i];
        a.row(1) = normals[j];
        a.row(2) = normals[k];
        if (std::abs(a.determinant()) < 1e-9) continue;  // unit normals: near-parallel planes, no vertex
        const Vec3 x = a.partialPivLu().solve(Vec3(e[i], e[j], e[k]));
        bool feasible = true;
        for (std::size_t m = 0; m < n && feasible; ++m) feasible = normals[m].dot(x) <= e[m] + tolerance;
        if (!feasible) continue;
        if (std::none_of(points.begin(), points.end(),
                         [&](const Vec3& p) { return (p - x).norm() <= tolerance; }))
          points.push_back(x);
      }
  return points;
}

std::optional<std::vector<Vec3>> erode(const ConvexObstacle& ob, const CSpace& cspace, double h,
                                       double tolerance) {
  const std::size_t n = ob.normals.size();
  const std::vector<double> e = eroded_part(ob, cspace, h).offsets;
  std::vector<Vec3> points = polytope_vertices(ob.normals, e, tolerance);
  if (points.size() < 4) return std::nullopt;
  Vec3 centre = Vec3::Zero();
  for (const Vec3& p : points) centre += p;
  centre /= static_cast<double>(points.size());
  // A solid erosion has its vertex centroid strictly inside; a flat or degenerate one does not.
  for (std::size_t i = 0; i < n; ++i)
    if (e[i] - ob.normals[i].dot(centre) <= 1e3 * tolerance) return std::nullopt;
  return points;
}

// A convex C-space part P met by a robot copy instead of the cube (docs/mujoco-scene.md "Convex C-space
// parts"): with c a point inside P and 0 < eps < 1, the part emitted is A = (1 - eps) P + eps c and the
// robot's geom is R = eps (c - P) about the C-space point (P reflected through c, then scaled). The robot at
// x meets A where x lies in A + (-R) = (1 - eps) P + eps P, which for convex P is P exactly, sharp edges
// included. Facets on the bounds first move out by `grow` (into the solid outside, as boxes grow), so the
// copy of a part standing on the floor overlaps the emitted part by `grow` below the floor's level instead of
// meeting it edge to edge: a robot pushed along the floor into the part is pushed back out sideways. eps
// makes the copy's diameter 0.1 x scale (as the cube's edge), at most half the part's.
struct HomotheticCopy {
  std::vector<Vec3> scene_part, robot_copy;
};

HomotheticCopy homothetic_copy(const ConvexObstacle& ob, const CSpace& cspace, double grow, double scale) {
  std::vector<double> offsets = ob.offsets;
  for (std::size_t i = 0; i < ob.normals.size(); ++i)
    if (cspace.covered_by_bounds(ob.normals[i], ob.offsets[i])) offsets[i] += grow;
  const std::vector<Vec3> vertices = polytope_vertices(ob.normals, offsets, 1e-9 * scale);
  if (vertices.size() < 4)
    throw std::logic_error("mjcf_xml: a convex C-space part has fewer than 4 vertices");
  Vec3 centre = Vec3::Zero();
  for (const Vec3& v : vertices) centre += v;
  centre /= static_cast<double>(vertices.size());
  double diameter = 0;
  for (const Vec3& a : vertices)
    for (const Vec3& b : vertices) diameter = std::max(diameter, (a - b).norm());
  const double eps = std::min(0.5, 0.1 * scale / diameter);
  HomotheticCopy out;
  for (const Vec3& v : vertices) {
    out.scene_part.push_back((1 - eps) * v + eps * centre);
    out.robot_copy.push_back(eps * (centre - v));
  }
  return out;
}

struct Writer {
  std::ostringstream out;
  double s = 1;  // metres per task unit

  void box(const std::string& name, const std::string& note, const AxisBox& b, double shrink, double friction,
           int contype, int conaffinity, const char* rgba, const char* indent) {
    const Vec3 centre = 0.5 * (b.min + b.max) * s;
    const Vec3 half = (0.5 * (b.max - b.min) - Vec3::Constant(shrink)) * s;
    out << indent << "<geom name=\"" << name << "\" type=\"box\" pos=\"" << vec(centre) << "\" size=\""
        << vec(half) << "\" friction=\"" << num(friction) << " 0 0\" contype=\"" << contype
        << "\" conaffinity=\"" << conaffinity << "\" rgba=\"" << rgba << "\"/>";
    if (!note.empty()) out << "  <!-- " << comment_text(note) << " -->";
    out << "\n";
  }

  void mesh_geom(const std::string& name, const std::string& note, double friction, int contype,
                 int conaffinity, const char* rgba, const char* indent) {
    out << indent << "<geom name=\"" << name << "\" type=\"mesh\" mesh=\"" << name << "\" friction=\""
        << num(friction) << " 0 0\" contype=\"" << contype << "\" conaffinity=\"" << conaffinity
        << "\" rgba=\"" << rgba << "\"/>";
    if (!note.empty()) out << "  <!-- " << comment_text(note) << " -->";
    out << "\n";
  }

  void mesh_asset(const std::string& name, const std::vector<Vec3>& vertices) {
    out << "    <mesh name=\"" << name << "\" vertex=\"";
    for (std::size_t i = 0; i < vertices.size(); ++i) out << (i ? "  " : "") << vec(vertices[i] * s);
    out << "\"/>\n";
  }
};

// True when `region` lies inside the union U of the C-space boxes and (with bounds) the outside of the
// bounds: the solid part of configuration space. Exact for axis-aligned boxes: the region is cut into the
// cells of the grid of every box and bounds coordinate inside it, and each cell (its centre) is tested.
bool inside_solid(const AxisBox& region, const std::vector<AxisBox>& boxes,
                  const std::optional<AxisBox>& bounds) {
  std::vector<double> cuts[3];
  for (int k = 0; k < 3; ++k) {
    cuts[k] = {region.min[k], region.max[k]};
    auto add = [&](double c) {
      if (c > region.min[k] && c < region.max[k]) cuts[k].push_back(c);
    };
    for (const AxisBox& b : boxes) {
      add(b.min[k]);
      add(b.max[k]);
    }
    if (bounds) {
      add(bounds->min[k]);
      add(bounds->max[k]);
    }
    std::sort(cuts[k].begin(), cuts[k].end());
    cuts[k].erase(std::unique(cuts[k].begin(), cuts[k].end()), cuts[k].end());
  }
  for (std::size_t i = 0; i + 1 < cuts[0].size(); ++i)
    for (std::size_t j = 0; j + 1 < cuts[1].size(); ++j)
      for (std::size_t l = 0; l + 1 < cuts[2].size(); ++l) {
        const Vec3 c(0.5 * (cuts[0][i] + cuts[0][i + 1]), 0.5 * (cuts[1][j] + cuts[1][j + 1]),
                     0.5 * (cuts[2][l] + cuts[2][l + 1]));
        bool solid =
            bounds && ((c.array() < bounds->min.array()).any() || (c.array() > bounds->max.array()).any());
        for (std::size_t b = 0; b < boxes.size() && !solid; ++b)
          solid = (c.array() > boxes[b].min.array()).all() && (c.array() < boxes[b].max.array()).all();
        if (!solid) return false;
      }
  return true;
}

// Seam closing (docs/mujoco-scene.md "Seams"). Shrinking every C-space box by h keeps the union exact, but
// where two boxes share a face (or a box meets the bounds) the shrunk geoms leave a slot exactly 2h wide
// between them: the interiors of the pieces do not cover their common face, MuJoCo collides the cube with
// each geom separately, and the cube slides into the slot without resistance (measured: a cube pushed down
// at a seam of the hole task's top surface sank 0.4 in in 0.4 s). Each box is therefore grown by 2h into
// every neighbouring solid (direction by direction, -x +x -y +y -z +z, keeping the grown box inside the
// solid union), so that every contact face of the scene continues at least h past a seam or concave edge.
// The union of the geoms, and so the contact configurations, do not change.
std::vector<AxisBox> grow_into_neighbours(const Task& task, double grow) {
  std::vector<AxisBox> solids;
  for (const ConvexPart& p : task.cspace)
    if (p.shape == ConvexPart::Shape::kBox) solids.push_back(p.box);
  std::vector<AxisBox> out;
  for (const ConvexPart& p : task.cspace) {
    AxisBox b = bounding_box(p);
    if (p.shape == ConvexPart::Shape::kBox) {
      for (int k = 0; k < 3; ++k)
        for (int side = 0; side < 2; ++side) {
          AxisBox slab = b;
          if (side == 0) {
            slab.max[k] = b.min[k];
            slab.min[k] = b.min[k] - grow;
          } else {
            slab.min[k] = b.max[k];
            slab.max[k] = b.max[k] + grow;
          }
          if (inside_solid(slab, solids, task.bounds))
            (side == 0 ? b.min[k] : b.max[k]) = side == 0 ? slab.min[k] : slab.max[k];
        }
    }
    out.push_back(b);
  }
  return out;
}

constexpr char kEnvRgba[] = "0.55 0.57 0.62 1";
constexpr char kWallRgba[] = "0.8 0.8 0.85 0.15";
constexpr char kRobotRgba[] = "0.9 0.45 0.2 1";
constexpr char kReferenceRgba[] = "0.2 0.55 0.9 0.6";

// Reference cube half size h: small against the scene, and at most a quarter of the thinnest part, so that
// every C-space box shrunk by h keeps at least half its extent.
// In C-space form only the parts the cube meets count (`cube_parts`: boxes and convex parts without a copy).
double reference_half_size(const Task& task, double scale, bool cspace_form,
                           const std::vector<bool>& cube_parts) {
  double thinnest = std::numeric_limits<double>::infinity();
  auto consider = [&](const std::vector<ConvexPart>& parts) {
    for (std::size_t i = 0; i < parts.size(); ++i) {
      if (cspace_form && !cube_parts[i]) continue;
      const AxisBox b = bounding_box(parts[i]);
      thinnest = std::min(thinnest, (b.max - b.min).minCoeff());
    }
  };
  if (cspace_form) {
    consider(task.cspace);
  } else {
    consider(task.robot);
    consider(task.environment);
  }
  double h = 0.05 * scale;
  if (std::isfinite(thinnest)) h = std::min(h, 0.25 * thinnest);
  return h;
}

// The thinnest a convex C-space part gets: over its facets, the least distance from the facet's plane to a
// vertex off it (a box's least extent; a ramp's low end, which its bounding box does not show). A cube of
// half size h above a quarter of it would erode that end away (the rollouts' robot then sinks where the
// C-obstacle is, docs/mujoco-scene.md "Convex C-space parts"). Infinity without convex parts.
double convex_part_thickness(const Task& task, const CSpace& cspace, const std::vector<bool>& cube_parts) {
  const double off = 1e-9 * cspace.scale();  // a vertex this close to a facet's plane lies on the facet
  double thinnest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < task.cspace.size() && i < cspace.obstacles().size(); ++i) {
    if (task.cspace[i].shape != ConvexPart::Shape::kConvex || !cube_parts[i]) continue;
    const ConvexObstacle& ob = cspace.obstacles()[i];
    for (std::size_t k = 0; k < ob.normals.size(); ++k)
      for (const Vec3& v : ob.vertices) {
        const double d = ob.offsets[k] - ob.normals[k].dot(v);
        if (d > off) thinnest = std::min(thinnest, d);
      }
  }
  return thinnest;
}

// Convex C-space parts eroded by the cube of half size *h; a thin or sharp part may need a smaller cube (*h
// is halved until every part erodes).
std::vector<std::vector<Vec3>> eroded_cspace_parts(const Task& task, const CSpace& cspace, double tolerance,
                                                   const std::vector<bool>& cube_parts, double* h) {
  std::vector<std::vector<Vec3>> eroded(task.cspace.size());
  if (cspace.obstacles().size() != task.cspace.size())
    throw std::logic_error("mjcf_xml: C-obstacles do not match the task's cspace parts");
  for (int attempt = 0;; ++attempt) {
    bool ok = true;
    for (std::size_t i = 0; i < task.cspace.size() && ok; ++i) {
      if (task.cspace[i].shape != ConvexPart::Shape::kConvex || !cube_parts[i]) continue;
      auto points = erode(cspace.obstacles()[i], cspace, *h, tolerance);
      if (points)
        eroded[i] = std::move(*points);
      else
        ok = false;
    }
    if (ok) return eroded;
    if (attempt == 20)
      throw std::runtime_error(task.source_file + ": a convex cspace part is too thin to export to MuJoCo");
    *h *= 0.5;
  }
}

// What a scene is made of, decided before any text is written.
struct SceneLayout {
  bool cspace_form = false;
  double scale = 0, s = 0, h = 0, wall = 0;
  std::vector<std::vector<Vec3>> eroded;  // convex C-space parts as emitted (C-space form)
  std::vector<ErodedPart> eroded_parts;   // cube-eroded ones as half-spaces (empty for boxes and copies)
  std::vector<int> copy_bit;              // per C-space part: the bit it shares with its robot copy (0: none)
  std::vector<std::vector<Vec3>> copies;  // per C-space part: its robot copy's vertices (robot frame)
  std::vector<AxisBox> grown;             // C-space boxes before shrinking by h (C-space form)
};

// How many convex C-space parts the layout gives a robot copy.
int copy_count(const SceneLayout& l) {
  return static_cast<int>(std::count_if(l.copy_bit.begin(), l.copy_bit.end(), [](int b) { return b != 0; }));
}

// The file's opening comment: units, scale, form and h.
void write_header(std::ostream& out, const Task& task, const SceneLayout& l) {
  out << "<!-- cmt export-mjcf: task '" << comment_text(task.name) << "'";
  // The file name only: the scene text must not depend on where the task was loaded from.
  if (!task.source_file.empty())
    out << " (" << comment_text(std::filesystem::path(task.source_file).filename().string()) << ")";
  out << "\n     units: " << unit_name(task.units) << ", " << num(l.s)
      << " m per unit; every length below is in metres (task length x " << num(l.s) << ").\n"
      << "     scene scale (C-space diagonal): " << num(l.scale) << " " << unit_name(task.units) << " = "
      << num(l.scale * l.s) << " m.\n"
      << "     " << (l.cspace_form ? "C-space form" : "physical form")
      << ": joints x, y, z (slide) = configuration-space point in metres; reference cube half size h = "
      << num(l.h) << " " << unit_name(task.units)
      << (l.cspace_form ? "; C-space boxes and walls are shrunk by h." : "; walls shrunk by h.")
      << "\n     See docs/mujoco-scene.md. -->\n";
}

// <compiler>, <option>, <size>, <custom> and <default>.
void write_settings(std::ostream& out, const Task& task, const MjcfOptions& options, const SceneLayout& l) {
  out << "  <compiler angle=\"radian\" inertiafromgeom=\"false\"/>\n";
  const double solref = options.solref_timesteps * options.timestep;
  out << "  <option timestep=\"" << num(options.timestep) << "\" integrator=\"Euler\" gravity=\"0 0 0\""
      << " cone=\"elliptic\" impratio=\"" << num(options.impratio) << "\" solver=\"Newton\" iterations=\""
      << options.solver_iterations << "\" tolerance=\"" << num(options.solver_tolerance)
      << "\" noslip_iterations=\"" << options.noslip_iterations << "\" noslip_tolerance=\""
      << num(options.solver_tolerance) << "\"/>\n";

  // Contact buffer: a box-box pair yields at most 8 contacts (a mesh pair 1); 3 constraint rows per elliptic
  // contact with condim 3. Capped because MuJoCo 2.2 allocates njmax² numbers per mjData; d->warning reports
  // an overflow.
  const int robot_geoms = l.cspace_form ? 1 : static_cast<int>(task.robot.size());
  const int env_geoms =
      l.cspace_form ? static_cast<int>(task.cspace.size()) : static_cast<int>(task.environment.size());
  const int wall_geoms = task.bounds ? 6 : 0;
  const int pairs = robot_geoms * env_geoms + wall_geoms + copy_count(l);
  const int nconmax = std::clamp(8 * pairs, 64, 256);
  out << "  <size nconmax=\"" << nconmax << "\" njmax=\"" << 3 * nconmax << "\"/>\n";

  if (options.seam_filter_relative > 0)
    out << "  <custom>\n    <numeric name=\"" << kSeamFilterNumeric << "\" data=\""
        << num(options.seam_filter_relative * l.scale * l.s) << "\"/>\n  </custom>\n";

  out << "  <default>\n"
      << "    <geom condim=\"3\" solref=\"" << num(solref) << " 1\" solimp=\"" << num(options.solimp_dmin)
      << " " << num(options.solimp_dmax) << " " << num(options.solimp_width) << "\"/>\n"
      << "    <joint type=\"slide\" damping=\"" << num(options.damping)
      << "\" stiffness=\"0\" armature=\"0\"/>\n"
      << "  </default>\n";
}

// Mesh assets for convex parts (MuJoCo collides their convex hulls).
void write_assets(std::ostream& out, const Task& task, const SceneLayout& l) {
  Writer meshes;
  meshes.s = l.s;
  if (l.cspace_form) {
    for (std::size_t i = 0; i < task.cspace.size(); ++i)
      if (task.cspace[i].shape == ConvexPart::Shape::kConvex) {
        meshes.mesh_asset("cspace" + std::to_string(i), l.eroded[i]);
        if (l.copy_bit[i] != 0) meshes.mesh_asset("robot_copy" + std::to_string(i), l.copies[i]);
      }
  } else {
    for (std::size_t i = 0; i < task.environment.size(); ++i)
      if (task.environment[i].shape == ConvexPart::Shape::kConvex)
        meshes.mesh_asset("env" + std::to_string(i), task.environment[i].vertices);
    for (std::size_t i = 0; i < task.robot.size(); ++i)
      if (task.robot[i].shape == ConvexPart::Shape::kConvex)
        meshes.mesh_asset("robot" + std::to_string(i), task.robot[i].vertices);
  }
  if (!meshes.out.str().empty()) out << "  <asset>\n" << meshes.out.str() << "  </asset>\n";
}

// The environment's geoms: the C-space parts (boxes grown into their neighbours, then shrunk by h; convex
// parts eroded), or the physical environment parts.
void write_environment(Writer& w, const Task& task, const SceneLayout& l) {
  const char* in2 = "    ";
  if (!l.cspace_form) {
    for (std::size_t i = 0; i < task.environment.size(); ++i) {
      const ConvexPart& p = task.environment[i];
      const std::string name = "env" + std::to_string(i);
      if (p.shape == ConvexPart::Shape::kBox)
        w.box(name, p.key, p.box, 0, p.friction, 0, kPartBit, kEnvRgba, in2);
      else
        w.mesh_geom(name, p.key, p.friction, 0, kPartBit, kEnvRgba, in2);
    }
    return;
  }
  for (std::size_t i = 0; i < task.cspace.size(); ++i) {
    const ConvexPart& p = task.cspace[i];
    const std::string name = "cspace" + std::to_string(i);
    if (p.shape != ConvexPart::Shape::kBox) {
      if (l.copy_bit[i] != 0)
        w.mesh_geom(name, p.key + ", shrunk toward a centre; meets only robot_copy" + std::to_string(i),
                    p.friction, 0, l.copy_bit[i], kEnvRgba, in2);
      else
        w.mesh_geom(name, p.key + ", eroded by the cube", p.friction, 0, kPartBit, kEnvRgba, in2);
      continue;
    }
    std::string note = p.key;
    static const char* const kDir[3][2] = {{"-x", "+x"}, {"-y", "+y"}, {"-z", "+z"}};
    std::string grown_dirs;
    for (int k = 0; k < 3; ++k) {
      if (l.grown[i].min[k] < p.box.min[k])
        grown_dirs += std::string(grown_dirs.empty() ? "" : " ") + kDir[k][0];
      if (l.grown[i].max[k] > p.box.max[k])
        grown_dirs += std::string(grown_dirs.empty() ? "" : " ") + kDir[k][1];
    }
    if (!grown_dirs.empty()) note += ", grown by 2h into its neighbours (" + grown_dirs + ")";
    w.box(name, note + ", shrunk by h", l.grown[i], l.h, p.friction, 0, kPartBit, kEnvRgba, in2);
  }
}

// Six slabs of thickness `wall` just outside the bounds, overlapping at the corners so that every point
// outside the bounds (up to `wall` away) lies in one; shrunk by h because they act on the reference cube.
void write_walls(Writer& w, const Task& task, const SceneLayout& l) {
  if (!task.bounds) return;
  static const char* const kAxis[] = {"x", "y", "z"};
  const AxisBox& b = *task.bounds;
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      AxisBox slab{b.min - Vec3::Constant(l.wall), b.max + Vec3::Constant(l.wall)};
      if (side == 0)
        slab.max[axis] = b.min[axis];
      else
        slab.min[axis] = b.max[axis];
      // The y walls of a planar task only keep the robot in the extrusion slab; they are not C-space faces
      // (docs/cspace.md), so they get no friction.
      const bool phantom = task.dimension == 2 && axis == 1;
      const std::string name = std::string("wall_") + kAxis[axis] + (side == 0 ? "min" : "max");
      w.box(name, phantom ? "planar extrusion limit, frictionless" : "bounds", slab, l.h,
            phantom ? 0.0 : task.friction, 0, kReferenceBit, kWallRgba, "    ");
    }
}

// The robot body: three slide joints, its inertia and its geoms (the reference cube, or the robot's parts
// and, with bounds, the reference cube that meets the walls).
void write_robot(Writer& w, const Task& task, const MjcfOptions& options, const SceneLayout& l) {
  std::ostringstream& out = w.out;
  const char* in3 = "      ";
  out << "    <body name=\"robot\">\n"
      << "      <joint name=\"x\" axis=\"1 0 0\"/>\n"
      << "      <joint name=\"y\" axis=\"0 1 0\"/>\n"
      << "      <joint name=\"z\" axis=\"0 0 1\"/>\n";
  // Only translations exist, so the rotational inertia is never used; MuJoCo still wants it positive.
  const double inertia = options.robot_mass * (0.1 * l.scale * l.s) * (0.1 * l.scale * l.s);
  out << "      <inertial pos=\"0 0 0\" mass=\"" << num(options.robot_mass) << "\" diaginertia=\""
      << num(inertia) << " " << num(inertia) << " " << num(inertia) << "\"/>\n";
  const AxisBox cube{Vec3::Constant(-l.h), Vec3::Constant(l.h)};
  if (l.cspace_form) {
    w.box("robot_cube", "the C-space point, thickened to a cube of half size h", cube, 0, 0,
          kPartBit | kReferenceBit, 0, kRobotRgba, in3);
    for (std::size_t i = 0; i < l.copy_bit.size(); ++i)
      if (l.copy_bit[i] != 0)
        w.mesh_geom("robot_copy" + std::to_string(i),
                    "the C-space point, thickened to a small reflected copy of cspace[" + std::to_string(i) +
                        "]: with the part shrunk toward the same centre they sum to the part exactly",
                    0, l.copy_bit[i], 0, kRobotRgba, in3);
  } else {
    for (std::size_t i = 0; i < task.robot.size(); ++i) {
      const ConvexPart& p = task.robot[i];
      const std::string name = "robot" + std::to_string(i);
      if (p.shape == ConvexPart::Shape::kBox)
        w.box(name, p.key, p.box, 0, 0, kPartBit, 0, kRobotRgba, in3);
      else
        w.mesh_geom(name, p.key, 0, kPartBit, 0, kRobotRgba, in3);
    }
    if (task.bounds)
      w.box("reference",
            "reference point (frame origin), thickened to a cube of half size h; meets the walls only", cube,
            0, 0, kReferenceBit, 0, kReferenceRgba, in3);
  }
  out << "    </body>\n";
}

// The start region's centroid (on the contact surface) as a keyframe, so viewers open at a valid state.
void write_start_key(std::ostream& out, const Task& task, double s) {
  if (task.start.points.empty()) return;
  Vec3 c = Vec3::Zero();
  for (const Vec3& p : task.start.points) c += p;
  c /= static_cast<double>(task.start.points.size());
  out << "  <keyframe>\n    <key name=\"start\" qpos=\"" << vec(c * s) << "\"/>\n  </keyframe>\n";
}

SceneLayout scene_layout(const LoadedTask& loaded, const MjcfOptions& options) {
  const Task& task = loaded.task;
  SceneLayout l;
  l.cspace_form = !task.physical();
  l.scale = loaded.cspace.scale();
  // Which convex C-space parts get a robot copy; the cube meets the others and every box.
  std::vector<bool> cube_parts(task.cspace.size(), true);
  l.copy_bit.assign(task.cspace.size(), 0);
  if (l.cspace_form && options.convex_copies) {
    int k = 0;
    for (std::size_t i = 0; i < task.cspace.size() && k < kMaxConvexCopies; ++i)
      if (task.cspace[i].shape == ConvexPart::Shape::kConvex) {
        l.copy_bit[i] = kFirstCopyBit << k++;
        cube_parts[i] = false;
      }
  }
  l.h = reference_half_size(task, l.scale, l.cspace_form, cube_parts);
  if (l.cspace_form) l.h = std::min(l.h, 0.25 * convex_part_thickness(task, loaded.cspace, cube_parts));
  if (l.cspace_form) l.eroded = eroded_cspace_parts(task, loaded.cspace, 1e-9 * l.scale, cube_parts, &l.h);
  if (l.cspace_form) {
    l.copies.resize(task.cspace.size());
    for (std::size_t i = 0; i < task.cspace.size(); ++i) {
      const bool convex = task.cspace[i].shape == ConvexPart::Shape::kConvex;
      l.eroded_parts.push_back(convex && cube_parts[i]
                                   ? eroded_part(loaded.cspace.obstacles()[i], loaded.cspace, l.h)
                                   : ErodedPart{});
      if (!convex || cube_parts[i]) continue;
      HomotheticCopy c = homothetic_copy(loaded.cspace.obstacles()[i], loaded.cspace, 2 * l.h, l.scale);
      l.eroded[i] = std::move(c.scene_part);
      l.copies[i] = std::move(c.robot_copy);
    }
  }
  // Walls: thick enough that the shrunk wall keeps half its thickness (h <= 0.05 scale) and the robot cannot
  // tunnel through at simulated speeds.
  l.wall = 0.2 * l.scale;
  l.s = meters_per_unit(task.units);
  // The C-space boxes as emitted before shrinking by h: grown into their neighbours (seams), or as given.
  if (l.cspace_form && options.close_seams) {
    l.grown = grow_into_neighbours(task, 2 * l.h);
  } else if (l.cspace_form) {
    for (const ConvexPart& p : task.cspace) l.grown.push_back(bounding_box(p));
  }
  return l;
}

}  // namespace

std::string mjcf_xml(const LoadedTask& loaded, const MjcfOptions& options, SceneInfo* info) {
  const Task& task = loaded.task;
  const SceneLayout l = scene_layout(loaded, options);
  if (info) {
    *info = SceneInfo{l.s, l.h, task.bounds ? l.wall : 0.0, l.cspace_form, l.grown, l.eroded_parts};
    info->convex_copies = copy_count(l);
  }
  Writer w;
  w.s = l.s;
  std::ostringstream& out = w.out;
  write_header(out, task, l);
  out << "<mujoco model=\"" << task.name << "\">\n";
  write_settings(out, task, options, l);
  write_assets(out, task, l);
  out << "  <worldbody>\n";
  write_environment(w, task, l);
  write_walls(w, task, l);
  write_robot(w, task, options, l);
  out << "  </worldbody>\n";
  write_start_key(out, task, l.s);
  out << "</mujoco>\n";
  return out.str();
}

// Whether some cube of half size `reach` about x has its centre in the eroded part: {y : n . y <= e,
// |y − x|_inf <= reach} is not empty (bounded, so it has a vertex). With reach h − tol: x lies inside the
// scene's part by more than tol; with h + tol: within tol of it.
bool scene_part_reaches(const ErodedPart& part, const Vec3& x, double reach, double tolerance) {
  std::vector<Vec3> normals = part.normals;
  std::vector<double> offsets = part.offsets;
  for (int a = 0; a < 3; ++a) {
    normals.push_back(Vec3::Unit(a));
    offsets.push_back(x[a] + reach);
    normals.push_back(-Vec3::Unit(a));
    offsets.push_back(reach - x[a]);
  }
  return !polytope_vertices(normals, offsets, tolerance).empty();
}

namespace {

// in_convex_cut_back and in_convex_cut_back_interior; with only_interior the surface case is skipped.
bool cut_back(const SceneInfo& info, const CSpace& cspace, const Vec3& x, double tol, bool only_interior) {
  if (!info.cspace_form) return false;
  const double h = info.reference_half_size, rounding = 1e-9 * cspace.scale();
  for (std::size_t i = 0; i < info.eroded_parts.size() && i < cspace.obstacles().size(); ++i) {
    const ErodedPart& part = info.eroded_parts[i];
    if (part.normals.empty()) continue;
    const ConvexObstacle& p = cspace.obstacles()[i];
    double depth = std::numeric_limits<double>::infinity();  // inside the task's part (< 0: outside)
    for (std::size_t j = 0; j < p.normals.size(); ++j)
      depth = std::min(depth, p.offsets[j] - p.normals[j].dot(x));
    if (depth < -tol || (only_interior && depth <= tol)) continue;
    if (depth > tol ? !scene_part_reaches(part, x, std::max(0.0, h - tol), rounding)
                    : !scene_part_reaches(part, x, h + tol, rounding))
      return true;
  }
  return false;
}

}  // namespace

bool in_convex_cut_back(const SceneInfo& info, const CSpace& cspace, const Vec3& x, double tol) {
  return cut_back(info, cspace, x, tol, false);
}

bool in_convex_cut_back_interior(const SceneInfo& info, const CSpace& cspace, const Vec3& x, double tol) {
  return cut_back(info, cspace, x, tol, true);
}

void write_mjcf(const LoadedTask& task, const std::filesystem::path& file, const MjcfOptions& options) {
  const std::string xml = mjcf_xml(task, options);
  std::ofstream stream(file, std::ios::binary | std::ios::trunc);
  if (!stream) {
    const std::error_code ec(errno, std::generic_category());
    throw std::runtime_error("cannot write MJCF file '" + file.string() + "': " + ec.message());
  }
  stream << xml;
  stream.close();
  if (!stream) throw std::runtime_error("cannot write MJCF file '" + file.string() + "': write failed");
}

MjcfOptions soft_layer_scene() {
  MjcfOptions o;
  o.timestep = kSoftLayerTimestep;
  o.solimp_dmin = kSoftLayerSolimpDmin;
  o.solimp_dmax = kSoftLayerSolimpDmax;
  o.solimp_width = kSoftLayerSolimpWidth;
  return o;
}

}  // namespace cmt
