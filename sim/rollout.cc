// Rollout engine (docs/rollouts.md). Per control step (one MuJoCo step, 1 kHz):
//   1. sense: true position and velocity from qpos / qvel, plus the motion's sensing offset; the contact
//   force
//      of the previous step (qfrc_constraint: with slide joints x, y, z it is the Cartesian force on the
//      robot), turned by the force-direction error;
//   2. the controller maps the sensed state to a velocity command; the velocity error turns its drive part;
//   3. mj_step1, then qfrc_applied = b_s v_cmd + qfrc_bias (the servo; qfrc_bias is gravity, which this adds
//      back: the robot is gravity-compensated as Buckley's gravity-free first-order model assumes, §3.1,
//      whatever the scene's gravity), then mj_step2;
//   4. record the contact force, penetration and stability checks; the termination monitor decides.
#include "sim/rollout.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <stdexcept>
#include <thread>

#include "models/polygon_distance.h"
#include "sim/mujoco_guard.h"
#include "sim/parallel_runs.h"
#include "sim/seam_filter.h"

namespace cmt {

namespace {

const char* const kWarningNames[mjNWARNING] = {"inertia",
                                               "contact buffer full",
                                               "constraint buffer full",
                                               "vgeom full",
                                               "bad qpos",
                                               "bad qvel",
                                               "bad qacc",
                                               "bad ctrl"};

}  // namespace

double distance_to_region(const Vec3& p, const Region& region) {
  switch (region.kind) {
    case Region::Kind::kPoint:
      return (p - region.points.at(0)).norm();
    case Region::Kind::kSegment:
      return distance_to_segment(p, region.points.at(0), region.points.at(1));
    case Region::Kind::kPolygon:
      return distance_to_convex_polygon(p, region.points, polygon_normal(region.points));
  }
  return 0;
}

Vec3 sample_region(const Region& region, SampleMode mode, Rng& rng) {
  const std::vector<Vec3>& v = region.points;
  if (region.kind == Region::Kind::kPoint) return v.at(0);
  if (mode == SampleMode::kExtreme && uniform01(rng) < kExtremeBoundaryFraction) {
    if (uniform01(rng) < 0.5) return v[uniform_index(rng, static_cast<int>(v.size()))];
    // Uniform on the boundary by length (a segment's boundary for this purpose is the segment itself).
    const std::size_t edges = region.kind == Region::Kind::kSegment ? 1 : v.size();
    std::vector<double> cumulative;
    double total = 0;
    for (std::size_t i = 0; i < edges; ++i)
      cumulative.push_back(total += (v[(i + 1) % v.size()] - v[i]).norm());
    const double t = uniform01(rng) * total;
    std::size_t i = std::upper_bound(cumulative.begin(), cumulative.end(), t) - cumulative.begin();
    i = std::min(i, edges - 1);
    const double before = i == 0 ? 0 : cumulative[i - 1];
    const double length = cumulative[i] - before;
    const double u = length > 0 ? (t - before) / length : 0;
    return v[i] + u * (v[(i + 1) % v.size()] - v[i]);
  }
  if (region.kind == Region::Kind::kSegment) return v[0] + uniform01(rng) * (v[1] - v[0]);
  // Convex polygon: a triangle of the fan from v[0], chosen by area, then uniform in it.
  std::vector<double> cumulative;
  double total = 0;
  for (std::size_t i = 1; i + 1 < v.size(); ++i)
    cumulative.push_back(total += 0.5 * (v[i] - v[0]).cross(v[i + 1] - v[0]).norm());
  const double t = uniform01(rng) * total;
  std::size_t i = std::upper_bound(cumulative.begin(), cumulative.end(), t) - cumulative.begin();
  i = std::min(i, cumulative.size() - 1);
  double a = uniform01(rng), b = uniform01(rng);
  if (a + b > 1) {
    a = 1 - a;
    b = 1 - b;
  }
  return v[0] + a * (v[i + 1] - v[0]) + b * (v[i + 2] - v[0]);
}

// ---------------------------------------------------------------------------------------------------------
// RolloutScene

std::shared_ptr<const RolloutScene> RolloutScene::build(std::shared_ptr<const LoadedTask> task,
                                                        const SimOptions& options) {
  SceneInfo info;
  const std::string xml = mjcf_xml(*task, options.scene, &info);
  auto scene = std::shared_ptr<RolloutScene>(new RolloutScene());
  scene->task_ = std::move(task);
  scene->model_ = MujocoModel::load_xml_string(xml);
  scene->info_ = info;
  scene->options_ = options;
  scene->init();
  return scene;
}

std::shared_ptr<const RolloutScene> RolloutScene::build(std::shared_ptr<const LoadedTask> task,
                                                        std::shared_ptr<const MujocoModel> model,
                                                        const SimOptions& options) {
  SceneInfo info;
  mjcf_xml(*task, options.scene, &info);
  auto scene = std::shared_ptr<RolloutScene>(new RolloutScene());
  scene->task_ = std::move(task);
  scene->model_ = std::move(model);
  scene->info_ = info;
  scene->options_ = options;
  scene->init();
  return scene;
}

void RolloutScene::init() {
  install_seam_contact_filter();  // acts only on models whose scene asks for it (seam_filter_relative)
  const mjModel* m = model_->get();
  static const char* const kJoints[3] = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k) {
    const int j = mj_name2id(m, mjOBJ_JOINT, kJoints[k]);
    if (j < 0) throw std::runtime_error(std::string("the scene has no joint '") + kJoints[k] + "'");
    qpos_[k] = m->jnt_qposadr[j];
    dof_[k] = m->jnt_dofadr[j];
  }
  geom_is_box_.resize(m->ngeom);
  for (int g = 0; g < m->ngeom; ++g) geom_is_box_[g] = m->geom_type[g] == mjGEOM_BOX;
  servo_damping_si_ = m->dof_damping[dof_[0]];
  const double s = info_.meters_per_unit;
  const double mass = m->body_mass[mj_name2id(m, mjOBJ_BODY, "robot")];
  // Controllers work in task units with forces in newtons: b_s in N per (task unit / s) = b [N s / m] x s.
  params_.servo_damping = servo_damping_si_ * s;
  params_.servo_time_constant = mass / servo_damping_si_;
  params_.damper_speed = options_.damper_speed_per_scale * task_->cspace.scale();
  params_.spring_rate = options_.spring_rate;
  params_.max_speed = options_.max_speed_per_scale * task_->cspace.scale();
  params_.step =
      task_->task.uncertainty.step > 0 ? task_->task.uncertainty.step : task_->task.uncertainty.eps_p;
  if (params_.step <= 0) params_.step = 0.01 * task_->cspace.scale();
  params_.position_gain = options_.position_gain;
  params_.via_time = options_.via_time_constants / options_.position_gain;
  // The task's own termination sets (Buckley §3.1.2 types 2 and 3), unless the caller gave the motion's.
  for (const Motion& m : task_->task.motions)
    if (m.terminate.any() && !options_.terminations.count(m.name))
      options_.terminations[m.name] = termination_spec(m.terminate);
}

double RolloutScene::timestep() const { return model_->get()->opt.timestep; }

double RolloutScene::timeout(const Motion& motion, const Vec3& from) const {
  if (motion.kind == Motion::Kind::kDamper)
    return options_.damper_timeout_scales * task_->cspace.scale() /
           (kStopRelativeSpeed * params_.damper_speed);
  const double distance = (motion.target - from).norm();
  const double reach = distance + task_->cspace.scale();
  if (options_.form == ControllerForm::kPosition) {
    const double vias = distance / params_.step + 1;
    return 3 * vias * params_.via_time + options_.spring_timeout_time_constants *
                                             std::max(1 / params_.position_gain, reach / params_.max_speed);
  }
  return distance / params_.max_speed + options_.spring_timeout_time_constants *
                                            std::max(1 / params_.spring_rate, reach / params_.max_speed);
}

double RolloutScene::goal_distance(const Vec3& p) const {
  double best = std::numeric_limits<double>::infinity();
  for (const Region& r : task_->task.goal) best = std::min(best, distance_to_region(p, r));
  return best;
}

// ---------------------------------------------------------------------------------------------------------
// RolloutRunner

struct RolloutRunner::Impl {
  std::shared_ptr<const RolloutScene> scene;
  MujocoData data;
  Vec3 force = Vec3::Zero();  // contact force of the last step, N
  double penetration = 0;     // of the last step, task units
  std::string failure;        // why the last step was unstable ("" = fine)
  std::vector<Vec3>* applied_sink = nullptr;

  explicit Impl(std::shared_ptr<const RolloutScene> s) : scene(std::move(s)), data(scene->model()) {}
  MotionOutcome run_motion(const Motion& motion, int node_id, int motion_index, double time_before,
                           ErrorSource& errors, RolloutOutcome* out);

  Vec3 position() const {
    const mjData* d = data.get();
    const double s = scene->meters_per_unit();
    return Vec3(d->qpos[scene->qpos_[0]], d->qpos[scene->qpos_[1]], d->qpos[scene->qpos_[2]]) / s;
  }
  Vec3 velocity() const {
    const mjData* d = data.get();
    const double s = scene->meters_per_unit();
    return Vec3(d->qvel[scene->dof_[0]], d->qvel[scene->dof_[1]], d->qvel[scene->dof_[2]]) / s;
  }

  void reset(const Vec3& p) {
    const mjModel* m = scene->model()->get();
    mjData* d = data.get();
    mj_resetData(m, d);  // also clears qacc_warmstart and the warning counters: replays are exact
    for (int k = 0; k < 3; ++k) d->qpos[scene->qpos_[k]] = p[k] * scene->meters_per_unit();
    force.setZero();
    penetration = 0;
    failure.clear();
  }

  // One control step with velocity command v_cmd (task units / s). Returns false if the step was unstable.
  bool step(const Vec3& v_cmd) {
    const mjModel* m = scene->model()->get();
    mjData* d = data.get();
    const double gain = scene->servo_damping_si_ * scene->meters_per_unit();  // N per (unit / s)
    const double f0 = gain * v_cmd[0], f1 = gain * v_cmd[1], f2 = gain * v_cmd[2];
    const int* dof = scene->dof_;
    try {
      mujoco_call([&] {
        mj_step1(m, d);
        d->qfrc_applied[dof[0]] = f0 + d->qfrc_bias[dof[0]];
        d->qfrc_applied[dof[1]] = f1 + d->qfrc_bias[dof[1]];
        d->qfrc_applied[dof[2]] = f2 + d->qfrc_bias[dof[2]];
        mj_step2(m, d);
      });
    } catch (const MujocoError& e) {
      failure = e.what();
      return false;
    }
    if (applied_sink)
      applied_sink->emplace_back(d->qfrc_applied[dof[0]], d->qfrc_applied[dof[1]], d->qfrc_applied[dof[2]]);
    force = Vec3(d->qfrc_constraint[dof[0]], d->qfrc_constraint[dof[1]], d->qfrc_constraint[dof[2]]);
    double deepest = 0;
    for (int i = 0; i < d->ncon; ++i) {
      const mjContact& c = d->contact[i];
      // Box-box contacts report minus half the overlap (docs/mujoco-scene.md), others the overlap.
      const bool boxes = scene->geom_is_box_[c.geom1] && scene->geom_is_box_[c.geom2];
      deepest = std::max(deepest, -(boxes ? 2 : 1) * c.dist);
    }
    penetration = deepest / scene->meters_per_unit();
    for (int w = 0; w < mjNWARNING; ++w)
      if (d->warning[w].number > 0) {
        failure = std::string("MuJoCo warning: ") + kWarningNames[w];
        return false;
      }
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(d->qpos[scene->qpos_[k]]) || !std::isfinite(d->qvel[scene->dof_[k]])) {
        failure = "non-finite state";
        return false;
      }
    if (penetration > scene->unstable_penetration()) {
      failure = "penetration " + std::to_string(penetration) + " beyond tolerance " +
                std::to_string(scene->unstable_penetration());
      return false;
    }
    if (scene->task().task.bounds) {
      const AxisBox& b = *scene->task().task.bounds;
      const Vec3 p = position();
      const double t = scene->unstable_penetration();
      if ((p.array() < b.min.array() - t).any() || (p.array() > b.max.array() + t).any()) {
        failure = "left the bounds";
        return false;
      }
    }
    return true;
  }
};

RolloutRunner::RolloutRunner(std::shared_ptr<const RolloutScene> scene)
    : impl_(std::make_unique<Impl>(std::move(scene))) {}

RolloutRunner::~RolloutRunner() = default;

void RolloutRunner::record_applied_forces(std::vector<Vec3>* sink) { impl_->applied_sink = sink; }

void RolloutRunner::drive(const Vec3& position, const Motion& motion, double duration,
                          const std::function<void(const StepState&)>& observer) {
  Impl& s = *impl_;
  s.reset(position);
  const RolloutScene& scene = *s.scene;
  auto controller = make_controller(motion, scene.options().form, scene.controller_params(), position);
  const double dt = scene.timestep();
  const long steps = std::lround(duration / dt);
  for (long i = 0; i < steps; ++i) {
    Sensed sensed;
    sensed.time = static_cast<double>(i) * dt;
    sensed.position = s.position();
    sensed.velocity = s.velocity();
    sensed.force = s.force;
    const ServoCommand c = controller->update(sensed);
    const bool ok = s.step(c.drive + c.feedback);
    ++total_steps_;
    StepState st;
    st.time = static_cast<double>(i + 1) * dt;
    st.position = s.position();
    st.velocity = s.velocity();
    st.force = s.force;
    st.contacts = s.data.get()->ncon;
    st.penetration = s.penetration;
    if (observer) observer(st);
    if (!ok) throw std::runtime_error("unstable simulation: " + s.failure);
  }
}

RolloutOutcome RolloutRunner::run(const Strategy& strategy, std::uint64_t seed, int index) {
  const RolloutScene& scene = *impl_->scene;
  const LoadedTask& task = scene.task();
  Rng rng = rollout_stream(seed, static_cast<std::uint64_t>(index));
  const ErrorSampler sampler(task.task.uncertainty, scene.options().mode, task.task.dimension == 2);
  SampledErrors errors(sampler, rng, scene.options().switch_interval);
  return run(strategy, errors, index);
}

// One motion of a rollout from the robot's current state: the servo loop until the termination monitor
// stops it, the controller stops on force, the simulation turns unstable or the time limit passes. Records
// trajectory samples (the rollout's time so far is `time_before`) into out->trajectory.
MotionOutcome RolloutRunner::Impl::run_motion(const Motion& motion, int node_id, int motion_index,
                                              double time_before, ErrorSource& errors, RolloutOutcome* out) {
  Impl& s = *this;
  const RolloutScene& scene = *s.scene;
  const SimOptions& options = scene.options();
  const double dt = scene.timestep();
  MotionOutcome mo;
  mo.motion = motion.name;
  mo.node = node_id;
  errors.begin_motion(node_id);
  const Vec3 start = s.position();
  // A start in a convex part's cut-back is in the air in the scene (docs/mujoco-scene.md).
  const bool start_cut_back =
      in_convex_cut_back(scene.info(), scene.task().cspace, start, scene.atom_tolerance());
  auto controller =
      make_controller(motion, options.form, scene.controller_params(), start + errors.sensing_offset(),
                      [&] { return errors.positioning_error(); });
  auto spec_it = options.terminations.find(motion.name);
  TerminationMonitor monitor(spec_it == options.terminations.end() ? TerminationSpec{} : spec_it->second,
                             controller->reference_speed(), controller->guard_force(), dt);
  const long limit = std::lround(scene.timeout(motion, start) / dt);
  std::optional<Termination> end;
  long step = 0;
  for (; step < limit && !end; ++step) {
    const double t = static_cast<double>(step) * dt;
    errors.advance(t);
    Sensed sensed;
    sensed.time = t;
    sensed.position = s.position() + errors.sensing_offset();
    sensed.velocity = s.velocity();
    sensed.force = errors.force().apply(s.force);
    end = monitor.update(sensed, controller->plan_complete());
    if (end) break;
    const ServoCommand c = controller->update(sensed);
    if (controller->stopped_by_force()) {
      end = Termination::kSticking;
      break;
    }
    const bool stable = s.step(errors.velocity().apply(c.drive) + c.feedback);
    mo.max_penetration = std::max(mo.max_penetration, s.penetration);
    if (!stable) {
      end = Termination::kUnstable;
      ++step;
      break;
    }
    if (in_convex_cut_back_interior(scene.info(), scene.task().cspace, s.position(),
                                    scene.atom_tolerance())) {
      end = Termination::kUnstable;
      s.failure =
          "passed inside a convex C-space part where the scene cuts it back (near its edges and "
          "corners that are not box-shaped: the scene does not represent the task there)";
      ++step;
      break;
    }
    if (options.record_trajectory && step % options.trajectory_stride == 0)
      out->trajectory.push_back(
          {time_before + t + dt, motion_index, s.position(), sensed.position, s.data.get()->ncon > 0});
  }
  mo.steps = step;
  mo.sim_time = static_cast<double>(step) * dt;
  mo.termination = end.value_or(Termination::kNone);
  mo.end = s.position();
  // An end deeper than the unstable penetration inside the solid is no outcome of the task's physics: the
  // scene does not represent the task there (its convex parts are inner approximations, cut back near edges
  // and corners: docs/mujoco-scene.md "Convex C-space parts"), so the rollout is unstable.
  if (mo.termination != Termination::kUnstable) {
    const double depth = scene.task().cspace.solid_depth(mo.end);
    if (depth > scene.unstable_penetration()) {
      mo.termination = Termination::kUnstable;
      s.failure = "ended " + std::to_string(depth) + " inside a C-obstacle, beyond tolerance " +
                  std::to_string(scene.unstable_penetration()) +
                  " (the scene does not represent the task there)";
    } else if (start_cut_back ||
               in_convex_cut_back(scene.info(), scene.task().cspace, mo.end, scene.atom_tolerance())) {
      mo.termination = Termination::kUnstable;
      s.failure = std::string(start_cut_back ? "started" : "ended") +
                  " where the scene cuts a convex C-space part back (near its edges and corners that are not "
                  "box-shaped: the scene does not represent the task there)";
    }
  }
  mo.atom = scene.task().cspace.nearest_atom(mo.end, scene.atom_tolerance());
  mo.contact_force = s.force;
  mo.velocity_switches = errors.switches();
  mo.replans = controller->replans();
  return mo;
}

namespace {

// The node after a terminated motion: its successor, or (Buckley §4.2) the branch one reading of the sensors
// at rest decides (mo->branch; -1 when no branch passes, and out->no_branch), or -1 at the end.
int next_node(const StrategyNode& node, int node_id, const Vec3& position, const Vec3& force,
              ErrorSource& errors, MotionOutcome* mo, RolloutOutcome* out) {
  if (node.next >= 0) return node.next;
  if (node.branches.empty()) return -1;
  const ReadingErrors reading = errors.reading(node_id);
  mo->branch = choose_branch(node, position + reading.sensing_offset, reading.force.apply(force));
  if (mo->branch < 0) {
    out->no_branch = true;
    return -1;
  }
  return node.branches[static_cast<std::size_t>(mo->branch)].first;
}

}  // namespace

RolloutOutcome RolloutRunner::run(const Strategy& strategy, ErrorSource& errors, int index) {
  Impl& s = *impl_;
  const RolloutScene& scene = *s.scene;
  const LoadedTask& task = scene.task();

  RolloutOutcome out;
  out.index = index;
  out.start = errors.start(task.task.start);
  s.reset(out.start);
  double rollout_time = 0;
  bool all_terminated = true;

  int motion_index = 0;
  for (int node_id = strategy.nodes.empty() ? -1 : 0; node_id >= 0; ++motion_index) {
    const StrategyNode& node = strategy.nodes[static_cast<std::size_t>(node_id)];
    const Motion* motion = task.task.find_motion(node.motion);
    if (motion == nullptr)
      throw std::invalid_argument("strategy '" + strategy.name + "' names unknown motion '" + node.motion +
                                  "'");
    MotionOutcome mo = s.run_motion(*motion, node_id, motion_index, rollout_time, errors, &out);
    total_steps_ += mo.steps;
    rollout_time += mo.sim_time;
    if (mo.termination == Termination::kUnstable) {
      out.unstable = true;
      out.unstable_reason = "motion '" + motion->name + "': " + s.failure;
    }
    if (mo.termination == Termination::kNone || mo.termination == Termination::kUnstable) {
      out.motions.push_back(mo);
      all_terminated = false;
      break;  // a motion that did not terminate ends the strategy (a real robot would stop with an error)
    }
    node_id = next_node(node, node_id, s.position(), s.force, errors, &mo, &out);
    out.motions.push_back(mo);
  }
  out.end = s.position();
  out.atom = out.motions.empty() ? task.cspace.nearest_atom(out.end, scene.atom_tolerance())
                                 : out.motions.back().atom;
  out.termination = out.motions.empty() ? Termination::kSticking : out.motions.back().termination;
  out.success = all_terminated && !out.unstable && !out.no_branch &&
                scene.goal_distance(out.end) <= scene.atom_tolerance();
  return out;
}

int choose_branch(const StrategyNode& node, const Vec3& sensed_position, const Vec3& sensed_force) {
  for (std::size_t i = 0; i < node.branches.size(); ++i) {
    const StrategyBranch& b = node.branches[i];
    if (b.otherwise) return static_cast<int>(i);
    const TerminationSpec test = termination_spec(b.when);
    if (test.sensed_position && !test.sensed_position->contains(sensed_position)) continue;
    if (test.sensed_force && !test.sensed_force->contains(sensed_force)) continue;
    return static_cast<int>(i);
  }
  return -1;
}

std::vector<RolloutOutcome> run_rollouts(std::shared_ptr<const RolloutScene> scene, const Strategy& strategy,
                                         int n, std::uint64_t seed, int threads,
                                         const std::function<void(int)>& progress) {
  if (n < 0) throw std::invalid_argument("run_rollouts: n must be >= 0");
  std::vector<RolloutOutcome> results(static_cast<std::size_t>(n));
  std::atomic<int> done{0};
  const auto run_all = [&] {
    parallel_runs(
        n, threads, [&] { return std::make_unique<RolloutRunner>(scene); },
        [&](RolloutRunner& runner, int i) {
          results[static_cast<std::size_t>(i)] = runner.run(strategy, seed, i);
          done.fetch_add(1);
        });
  };
  if (!progress) {
    run_all();
    return results;
  }
  // The rollouts on a thread of their own; the calling thread only reports progress.
  std::exception_ptr error;
  std::atomic<bool> finished{false};
  std::thread worker([&] {
    try {
      run_all();
    } catch (...) {
      error = std::current_exception();
    }
    finished.store(true);
  });
  while (!finished.load()) {
    progress(done.load());
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  worker.join();
  if (error) std::rethrow_exception(error);
  progress(done.load());
  return results;
}

}  // namespace cmt
