#include "experiments/cli/export_mjcf_command.h"

#include <iostream>

#include "experiments/cli/cli_output.h"
#include "experiments/cli/command.h"
#include "sim/mjcf_export.h"

namespace cmt {

nlohmann::json export_mjcf_command(const LoadedTask& task, const std::filesystem::path& output) {
  SceneInfo info;
  const MjcfOptions options;
  write_mjcf(task, output, options);
  mjcf_xml(task, options, &info);
  return {{"task", task.task.name},
          {"output", output.string()},
          {"meters_per_unit", info.meters_per_unit},
          {"reference_half_size", info.reference_half_size},
          {"convex_copies", info.convex_copies}};
}

void add_export_mjcf_command(CLI::App& app, CommandState& state) {
  struct Options {
    std::string task, output;
  };
  auto options = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("export-mjcf", "Write the task's MuJoCo 2.2 MJCF scene");
  cmd->add_option("TASK", options->task, "task YAML file")->required();
  cmd->add_option("-o,--output", options->output, "MJCF file to write")->required();
  cmd->add_flag("--json", state.json, "print one JSON object on stdout");
  cmd->callback([options, &state] {
    const auto task = load_task(options->task);
    const auto summary = export_mjcf_command(*task, options->output);
    if (state.json)
      print_json(summary);
    else
      std::cerr << "wrote " << options->output << std::endl;
    state.exit_status = kExitSuccess;
  });
}

}  // namespace cmt
