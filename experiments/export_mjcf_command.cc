#include "experiments/export_mjcf_command.h"

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
          {"reference_half_size", info.reference_half_size}};
}

}  // namespace cmt
