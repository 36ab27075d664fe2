// Model error (Donald 1987 §1.2, l.920-1027): named model parameters alpha with intervals, and geometry that
// is affine in them. The generalized configuration space C x J is represented by slices, one task per sampled
// alpha (Donald's LIMITED, l.1754-1769): the physics axioms make alpha fixed during a motion, so each slice
// is an ordinary task. Obstacles that move linearly with alpha give polyhedral generalized obstacles
// (l.1320).
#pragma once
#include <string>
#include <vector>

namespace cmt {

struct Task;

// A model parameter and its interval, or its finite set of values (docs/task-format.md "model_error"; a
// discrete J such as Donald's twin universe, J = {1, 2}, l.1617). `nominal` is the value every command that
// does not slice reads the task at (the interval's midpoint, or the first value, unless the file gives one).
struct ModelParameter {
  std::string name;
  double min = 0, max = 0, nominal = 0;
  std::vector<double> values;  // a discrete parameter's values, increasing (min and max are its ends); empty:
                               // every value of [min, max]
  bool discrete() const { return !values.empty(); }
  // v is a value of the parameter: in [min, max], and one of `values` when discrete.
  bool admits(double v) const;
};

// c + sum_i coefficients[i] alpha_i, one coefficient per model parameter (in the task's order).
struct AffineValue {
  double constant = 0;
  std::vector<double> coefficients;
  double at(const std::vector<double>& values) const;
  bool is_constant() const;
};

// Parses an affine expression such as "alpha + 3", "-0.5*width - 1", "2 * depth": terms joined by + and -,
// each a number, a parameter name, or a number times a name ("2*w", "w*2"). Throws std::invalid_argument
// with the reason (unknown name, malformed term).
AffineValue parse_affine(const std::string& text, const std::vector<ModelParameter>& parameters);

// A coordinate of a part, the bounds, the start or a goal region as read (axis 0-2), kept to find the
// critical slices. C-space coordinates (cspace parts, bounds, regions) compare as they are; a physical task's
// C-obstacle coordinates are an environment coordinate less a robot one (O ⊕ −R).
struct ModelCoordinate {
  enum class Role { kNone, kConfiguration, kEnvironment, kRobot };
  int axis = 0;
  AffineValue value;
  Role role = Role::kConfiguration;
};

// At most this many model parameters and slices (docs/task-format.md "Accepted ranges and sizes").
inline constexpr std::size_t kMaxModelParameters = 4;
inline constexpr std::size_t kMaxModelSlices = 10000;

// The values of parameter `p` in (min, max) where two C-space coordinates on one axis become equal along p
// with the other parameters at their nominal values: where faces meet, a part degenerates, a face passes the
// start or a goal region leaves a face, so the C-space topology may change there (Donald §6.4's critical
// slices, for obstacles that move linearly with alpha); none for a discrete parameter. C-space coordinates:
// those of cspace parts, bounds and regions, and for physical tasks every environment coordinate less every
// robot coordinate on the same axis (a superset of the C-obstacles' box coordinates). Exact for one parameter
// and box C-obstacles; for convex hulls and several parameters a sample of the critical set. Sorted.
std::vector<double> critical_values(const Task& task, std::size_t p);

// The values of parameter p that slices take. A discrete parameter: its values, whatever the resolution (each
// is a world of its own, and there is nothing between them). Otherwise `resolution` evenly spaced values from
// min to max (both included; 1: the nominal value alone), the critical values, and the midpoint of each
// interval between consecutive values of {min, critical values, max}, so that every piece of the interval
// between critical values has a slice. Sorted, without duplicates.
std::vector<double> slice_values(const Task& task, std::size_t p, int resolution);

// The Cartesian product of slice_values over the parameters (one slice, the empty vector, without model
// error). Throws std::invalid_argument past kMaxModelSlices.
std::vector<std::vector<double>> model_slices(const Task& task, int resolution);

}  // namespace cmt
