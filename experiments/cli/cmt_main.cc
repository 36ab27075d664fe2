// The cmt command-line program. Each subcommand prints exactly one JSON object on stdout with --json; exit
// status 0 success, 1 failure found, 2 bad input or usage (docs/contracts.md "Command line"). Subcommands
// register themselves (experiments/cli/command.h); this file only maps exceptions to exit statuses.
#include <CLI/CLI.hpp>
#include <iostream>

#include "experiments/cli/cli_output.h"
#include "experiments/cli/command.h"
#include "models/input_error.h"

int main(int argc, char** argv) {
  CLI::App app{"cmt - compliant motion testbed: Buckley's verifier checked by MuJoCo rollouts"};
  app.require_subcommand(1);
  cmt::CommandState state;
  cmt::add_info_command(app, state);
  cmt::add_export_mjcf_command(app, state);
  cmt::add_rollout_command(app, state);
  cmt::add_calibrate_friction_command(app, state);
  cmt::add_sticking_command(app, state);
  cmt::add_verify_command(app, state);
  cmt::add_check_sticking_command(app, state);
  cmt::add_report_command(app, state);
  cmt::add_view_command(app, state);
  cmt::add_validate_command(app, state);
  cmt::add_sweep_command(app, state);
  cmt::add_merge_command(app, state);
  cmt::add_export_csv_command(app, state);
  cmt::add_soundness_campaign_command(app, state);
  cmt::add_falsify_command(app, state);
  cmt::add_teach_command(app, state);
  cmt::add_plan_command(app, state);
  cmt::add_backproject_command(app, state);
  cmt::add_edr_command(app, state);
  cmt::add_plan_edr_command(app, state);

  bool wants_json = false;
  for (int i = 1; i < argc; ++i) wants_json = wants_json || std::string(argv[i]) == "--json";
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    return cmt::report_bad_input(std::string("usage: ") + e.what() + " (see cmt --help)", wants_json);
  } catch (const cmt::InputError& e) {
    return cmt::report_bad_input(e.what(), wants_json, e.file(), e.key(), e.reason(), e.where());
  } catch (const std::exception& e) {
    // Anything else is an I/O failure on the user's paths or a bug: still no crash, and the message says
    // which.
    return cmt::report_bad_input(e.what(), wants_json);
  }
  return state.exit_status;
}
