// cairn: the command-line tool. See docs/cli.md.

#include <CLI/CLI.hpp>
#include <iostream>

#include "cli/commands.h"

namespace {

// The options that say how the input file is read and what the command line
// changes in its model: the same on check, simulate and convert.
void AddModelOptions(CLI::App* cmd, cairn::cli::ModelArgs& model) {
  cmd->add_option("--format", model.format,
                  "Input format: scene (Cairn scene format 1, default) or compas (a COMPAS "
                  "assembly of compas_assembly or compas_cra)")
      ->check(CLI::IsMember({"scene", "compas"}));
  cmd->add_option("--friction", model.friction,
                  "Coulomb friction coefficient of every contact (required with --format compas; "
                  "replaces the scene's default friction with --format scene)");
  cmd->add_option("--supports", model.supports,
                  "Also fix these parts (COMPAS blocks: node keys), comma-separated")
      ->delimiter(',');
  cmd->add_option("--tolerance", model.tolerance,
                  "Length tolerance: contact distance, allowed overlap, planarity (default: the "
                  "scene's, or a fraction of the size of the assembly)");
  cmd->add_option("--gravity", model.gravity,
                  "Gravity vector, comma-separated (e.g. 0,0,9.81: the assembly upside down)")
      ->delimiter(',');
  cmd->add_option("--interfaces", model.interfaces,
                  "Contacts: detect (found from the shapes, default) or stored (a COMPAS file's "
                  "stored interfaces, for blocks modelled too loosely for exact contacts)")
      ->check(CLI::IsMember({"detect", "stored"}));
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Cairn: does an assembly stay put while parts are taken out?"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "cairn 0.1.0");

  cairn::cli::CheckArgs check;
  CLI::App* check_cmd =
      app.add_subcommand("check", "Is one configuration of a scene stable under gravity?");
  check_cmd->add_option("scene", check.scene, "Scene file (JSON: format 1, or --format compas)")
      ->required();
  check_cmd->add_flag("--json", check.json, "Print a JSON document instead of a summary");
  check_cmd->add_option("--normalize", check.normalize, "Divide forces by the weight of this part");
  check_cmd
      ->add_option("--without", check.without,
                   "Check with these parts taken away (comma-separated)")
      ->delimiter(',');
  AddModelOptions(check_cmd, check.model);

  cairn::cli::SimulateArgs sim;
  CLI::App* sim_cmd = app.add_subcommand(
      "simulate", "Run a disassembly or assembly plan: is every step stable along its path?");
  sim_cmd->add_option("scene", sim.scene, "Scene file (JSON: format 1, or --format compas)")
      ->required();
  sim_cmd->add_option("plan", sim.plan, "Plan file (JSON, plan format 1)")->required();
  sim_cmd->add_flag("--json", sim.json, "Print a JSON document instead of a summary");
  sim_cmd->add_option("--timeline", sim.timeline,
                      "Write one CSV row per time step and contact to this file");
  sim_cmd->add_option("--normalize", sim.normalize, "Divide forces by the weight of this part");
  sim_cmd->add_flag("--continue", sim.continue_after_failure,
                    "Go on after a failure, as if it had been prevented");
  AddModelOptions(sim_cmd, sim.model);

  cairn::cli::ConvertArgs convert;
  CLI::App* convert_cmd = app.add_subcommand(
      "convert", "Write the model of a file (e.g. a COMPAS assembly) as a scene file, format 1");
  convert_cmd->add_option("input", convert.input, "Input file (--format says which format)")
      ->required();
  convert_cmd->add_option("output", convert.output, "Scene file to write (JSON, format 1)")
      ->required();
  AddModelOptions(convert_cmd, convert.model);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version exit 0; a usage error is bad input (exit 2).
    const int code = app.exit(e);
    return code == 0 ? 0 : cairn::cli::kExitBadInput;
  }
  if (*check_cmd) return cairn::cli::RunCheck(check, std::cout, std::cerr);
  if (*sim_cmd) return cairn::cli::RunSimulate(sim, std::cout, std::cerr);
  if (*convert_cmd) return cairn::cli::RunConvert(convert, std::cout, std::cerr);
  return cairn::cli::kExitBadInput;
}
