// cairn: the command-line tool. See docs/cli.md.

#include <CLI/CLI.hpp>
#include <iostream>

#include "cli/commands.h"

int main(int argc, char** argv) {
  CLI::App app{"Cairn: does an assembly stay put while parts are taken out?"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "cairn 0.1.0");

  cairn::cli::CheckArgs check;
  CLI::App* check_cmd =
      app.add_subcommand("check", "Is one configuration of a scene stable under gravity?");
  check_cmd->add_option("scene", check.scene, "Scene file (JSON, format 1)")->required();
  check_cmd->add_flag("--json", check.json, "Print a JSON document instead of a summary");
  check_cmd->add_option("--normalize", check.normalize, "Divide forces by the weight of this part");
  check_cmd
      ->add_option("--without", check.without,
                   "Check with these parts taken away (comma-separated)")
      ->delimiter(',');

  cairn::cli::SimulateArgs sim;
  CLI::App* sim_cmd = app.add_subcommand(
      "simulate", "Run a disassembly or assembly plan: is every step stable along its path?");
  sim_cmd->add_option("scene", sim.scene, "Scene file (JSON, format 1)")->required();
  sim_cmd->add_option("plan", sim.plan, "Plan file (JSON, plan format 1)")->required();
  sim_cmd->add_flag("--json", sim.json, "Print a JSON document instead of a summary");
  sim_cmd->add_option("--timeline", sim.timeline,
                      "Write one CSV row per time step and contact to this file");
  sim_cmd->add_option("--normalize", sim.normalize, "Divide forces by the weight of this part");
  sim_cmd->add_flag("--continue", sim.continue_after_failure,
                    "Go on after a failure, as if it had been prevented");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version exit 0; a usage error is bad input (exit 2).
    const int code = app.exit(e);
    return code == 0 ? 0 : cairn::cli::kExitBadInput;
  }
  if (*check_cmd) return cairn::cli::RunCheck(check, std::cout, std::cerr);
  if (*sim_cmd) return cairn::cli::RunSimulate(sim, std::cout, std::cerr);
  return cairn::cli::kExitBadInput;
}
