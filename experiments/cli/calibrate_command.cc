// cmt calibrate-friction: the simulated robot against Coulomb's law (sim/calibration.h, docs/rollouts.md).
#include <iostream>
#include <memory>
#include <string>

#include "experiments/cli/cli_output.h"
#include "experiments/cli/command.h"
#include "sim/calibration.h"
#include "sim/rollout.h"

namespace cmt {

nlohmann::json calibration_json(const CalibrationResult& r) {
  nlohmann::json cases = nlohmann::json::array();
  for (const CalibrationCase& c : r.cases)
    cases.push_back({{"geometry", c.geometry},
                     {"motion", c.motion},
                     {"controller", controller_form_name(c.form)},
                     {"mu", c.mu},
                     {"ratio", c.ratio},
                     {"reference", c.reference},
                     {"alpha", c.alpha},
                     {"expected", c.expected},
                     {"observed", c.observed},
                     {"command_speed", c.command_speed},
                     {"creep", c.creep},
                     {"loading_creep", c.loading_creep},
                     {"speed", c.speed},
                     {"analytic_speed", c.analytic_speed},
                     {"speed_error", c.speed_error},
                     {"max_penetration", c.max_penetration},
                     {"agree", c.agree},
                     {"passed", c.passed}});
  return {{"cases", cases},
          {"agree", r.agree},
          {"passed", r.passed},
          {"max_creep", r.max_creep},
          {"max_loading_creep", r.max_loading_creep},
          {"max_speed_error", r.max_speed_error},
          {"max_penetration", r.max_penetration},
          {"face", {{"max_creep", r.max_face_creep}, {"max_speed_error", r.max_face_speed_error}}},
          {"edge", {{"max_creep", r.max_edge_creep}, {"max_speed_error", r.max_edge_speed_error}}},
          {"ambiguous", r.ambiguous},
          {"criteria",
           {{"max_creep", kMaxCreep},
            {"max_speed_error", kMaxSpeedError},
            {"max_penetration", kMaxPenetration},
            {"command_speed_in_per_s", kCalibrationSpeed}}},
          {"seconds", r.seconds}};
}

void add_calibrate_friction_command(CLI::App& app, CommandState& state) {
  auto* cmd = app.add_subcommand(
      "calibrate-friction",
      "Check the simulated robot against Coulomb friction on a face and in a concave edge");
  cmd->add_flag("--json", state.json, "print one JSON object on stdout");
  auto scene = std::make_shared<std::string>("rollout");
  auto* scene_option =
      cmd->add_option(
             "--scene", *scene,
             "MuJoCo scene: rollout (default: the rollouts' scene, sim/rollout.h calibrated_scene), "
             "soft-layer (the same scene) or stiff (sim/rollout.h stiff_scene: stiff contact, off Coulomb "
             "in concave edges)")
          ->check(CLI::IsMember({"rollout", "soft-layer", "stiff"}));
  auto soft_layer = std::make_shared<bool>(false);
  cmd->add_flag("--soft-layer", *soft_layer,
                "the soft-surface-layer scene (= --scene soft-layer, the rollouts' scene)")
      ->excludes(scene_option);
  cmd->callback([&state, scene, soft_layer] {
    if (*soft_layer) *scene = "soft-layer";
    const MjcfOptions options = *scene == "stiff" ? stiff_scene() : calibrated_scene();
    const CalibrationResult r = calibrate_friction(
        {ControllerForm::kImpedance, ControllerForm::kAdmittance, ControllerForm::kPosition}, options);
    nlohmann::json j = calibration_json(r);
    j["scene"] = *scene;
    j["timestep"] = options.timestep;
    if (state.json) {
      print_json(j);
    } else {
      int failed = 0;
      for (const CalibrationCase& c : r.cases) failed += !c.passed && c.expected != "ambiguous";
      std::cout << r.cases.size() << " cases (" << r.ambiguous << " ambiguous), " << failed
                << " failed; agree " << (r.agree ? "yes" : "no") << ", max creep " << r.max_creep << " (face "
                << r.max_face_creep << "; position form while loading " << r.max_loading_creep
                << ", not scored), max speed error " << r.max_speed_error << " (face "
                << r.max_face_speed_error << "), max penetration " << r.max_penetration << " m\n";
    }
    state.exit_status = r.passed ? kExitSuccess : kExitFailureFound;
  });
}

}  // namespace cmt
