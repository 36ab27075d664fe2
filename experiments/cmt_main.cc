// The cmt command-line program. Each subcommand prints exactly one JSON object on stdout with --json; exit
// status 0 success, 1 failure found, 2 bad input or usage (contracts.md "Command line").
#include <CLI/CLI.hpp>
#include <chrono>
#include <iostream>

#include "experiments/cli_output.h"
#include "experiments/export_mjcf_command.h"
#include "experiments/info_command.h"
#include "models/loaded_task.h"
#include "models/task_error.h"

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "cmt - compliant motion testbed: verifier and MuJoCo rollouts for Buckley's compliant motions"};
  app.require_subcommand(1);
  bool json = false;

  std::string info_task;
  bool info_atoms = false;
  auto* info = app.add_subcommand("info", "Configuration-space atoms of a task (faces, edges, vertices)");
  info->add_option("TASK", info_task, "task YAML file")->required();
  info->add_flag("--atoms", info_atoms, "also list every atom's geometry");
  info->add_flag("--json", json, "print one JSON object on stdout");

  std::string export_task, export_output;
  auto* export_mjcf = app.add_subcommand("export-mjcf", "Write the task's MuJoCo 2.2 MJCF scene");
  export_mjcf->add_option("TASK", export_task, "task YAML file")->required();
  export_mjcf->add_option("-o,--output", export_output, "MJCF file to write")->required();
  export_mjcf->add_flag("--json", json, "print one JSON object on stdout");

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    bool wants_json = false;
    for (int i = 1; i < argc; ++i) wants_json = wants_json || std::string(argv[i]) == "--json";
    return cmt::report_bad_input(std::string("usage: ") + e.what() + " (see cmt --help)", wants_json);
  }

  try {
    if (*info) {
      const auto start = Clock::now();
      const auto task = cmt::load_task(info_task);
      const double seconds = seconds_since(start);
      if (json)
        cmt::print_json(cmt::info_json(*task, info_atoms, seconds));
      else
        std::cout << cmt::info_text(*task);
      return cmt::kExitSuccess;
    }
    if (*export_mjcf) {
      const auto task = cmt::load_task(export_task);
      const auto summary = cmt::export_mjcf_command(*task, export_output);
      if (json)
        cmt::print_json(summary);
      else
        std::cerr << "wrote " << export_output << std::endl;
      return cmt::kExitSuccess;
    }
  } catch (const cmt::TaskError& e) {
    return cmt::report_bad_input(e.what(), json, e.file(), e.key(), e.reason());
  } catch (const std::exception& e) {
    // Anything else is a bug or an I/O failure on the user's paths: still no crash, and the message says
    // which.
    return cmt::report_bad_input(e.what(), json);
  }
  return cmt::kExitBadInput;
}
