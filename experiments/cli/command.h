// Each cmt subcommand lives in its own file and registers itself on the CLI11 app with an add_*_command
// function; its callback runs the command and stores the exit status here. Errors are thrown (InputError for
// bad input) and turned into exit status 2 by cmt_main.cc.
#pragma once

#include <CLI/CLI.hpp>

namespace cmt {

struct CommandState {
  bool json = false;    // --json: print exactly one JSON object on stdout
  int exit_status = 2;  // set by the command that ran
};

void add_info_command(CLI::App& app, CommandState& state);
void add_export_mjcf_command(CLI::App& app, CommandState& state);
void add_rollout_command(CLI::App& app, CommandState& state);
void add_calibrate_friction_command(CLI::App& app, CommandState& state);
void add_sticking_command(CLI::App& app, CommandState& state);
void add_verify_command(CLI::App& app, CommandState& state);
void add_check_sticking_command(CLI::App& app, CommandState& state);
void add_report_command(CLI::App& app, CommandState& state);
void add_view_command(CLI::App& app, CommandState& state);
void add_validate_command(CLI::App& app, CommandState& state);
void add_sweep_command(CLI::App& app, CommandState& state);
void add_merge_command(CLI::App& app, CommandState& state);
void add_export_csv_command(CLI::App& app, CommandState& state);
void add_soundness_campaign_command(CLI::App& app, CommandState& state);
void add_falsify_command(CLI::App& app, CommandState& state);
void add_teach_command(CLI::App& app, CommandState& state);
void add_plan_command(CLI::App& app, CommandState& state);
void add_backproject_command(CLI::App& app, CommandState& state);
void add_edr_command(CLI::App& app, CommandState& state);
void add_plan_edr_command(CLI::App& app, CommandState& state);

}  // namespace cmt
