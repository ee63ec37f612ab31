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

// A subcommand that reads one scene (the positional `scene`) and prints a
// summary, or with --json a document.
CLI::App* AddSceneCommand(CLI::App& app, const char* name, const char* description,
                          std::string& scene, bool& json) {
  CLI::App* cmd = app.add_subcommand(name, description);
  cmd->add_option("scene", scene, "Scene file (JSON: format 1, or --format compas)")->required();
  cmd->add_flag("--json", json, "Print a JSON document instead of a summary");
  return cmd;
}

// --without: parts taken away before the command's work.
void AddWithout(CLI::App* cmd, std::vector<std::string>& without, const char* description) {
  cmd->add_option("--without", without, description)->delimiter(',');
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Cairn: does an assembly stay put while parts are taken out?"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "cairn 0.1.0");

  cairn::cli::CheckArgs check;
  CLI::App* check_cmd =
      AddSceneCommand(app, "check", "Is one configuration of a scene stable under gravity?",
                      check.scene, check.json);
  check_cmd->add_option("--normalize", check.normalize, "Divide forces by the weight of this part");
  AddWithout(check_cmd, check.without, "Check with these parts taken away (comma-separated)");
  AddModelOptions(check_cmd, check.model);

  cairn::cli::SimulateArgs sim;
  CLI::App* sim_cmd = AddSceneCommand(
      app, "simulate", "Run a disassembly or assembly plan: is every step stable along its path?",
      sim.scene, sim.json);
  sim_cmd->add_option("plan", sim.plan, "Plan file (JSON, plan format 1)")->required();
  sim_cmd->add_option("--timeline", sim.timeline,
                      "Write one CSV row per time step and contact to this file");
  sim_cmd->add_option("--normalize", sim.normalize, "Divide forces by the weight of this part");
  sim_cmd->add_flag("--continue", sim.continue_after_failure,
                    "Go on after a failure, as if it had been prevented");
  sim_cmd->add_flag("--suggest-fixtures", sim.suggest_fixtures,
                    "When a step fails, suggest the fewest fixels (point fixtures) that make the "
                    "plan stable, verified by re-running it");
  sim_cmd
      ->add_option("--max-fixels", sim.max_fixels,
                   "The most fixels --suggest-fixtures adds (default 3)")
      ->check(CLI::Range(1, 20));
  AddModelOptions(sim_cmd, sim.model);

  cairn::cli::ConvertArgs convert;
  CLI::App* convert_cmd = app.add_subcommand(
      "convert", "Write the model of a file (e.g. a COMPAS assembly) as a scene file, format 1");
  convert_cmd->add_option("input", convert.input, "Input file (--format says which format)")
      ->required();
  convert_cmd->add_option("output", convert.output, "Scene file to write (JSON, format 1)")
      ->required();
  AddModelOptions(convert_cmd, convert.model);

  cairn::cli::BlockingArgs blocking;
  CLI::App* blocking_cmd = AddSceneCommand(
      app, "blocking", "Which parts can be taken out, and along which directions? (the NDBG)",
      blocking.scene, blocking.json);
  AddWithout(blocking_cmd, blocking.without,
             "Compute it with these parts taken away (comma-separated)");
  AddModelOptions(blocking_cmd, blocking.model);

  cairn::cli::PlanArgs plan;
  CLI::App* plan_cmd = AddSceneCommand(
      app, "plan", "Find stable disassembly sequences (and their assembly plans) of a scene",
      plan.scene, plan.json);
  plan_cmd
      ->add_option("--max", plan.max,
                   "Stop after K stable sequences (best-first search); default: all")
      ->check(CLI::NonNegativeNumber);
  plan_cmd->add_option("--threads", plan.threads, "Worker threads (default: every core)")
      ->check(CLI::NonNegativeNumber);
  plan_cmd->add_option("--paths", plan.paths,
                       "Candidate paths per part (JSON: part name -> list of paths)");
  plan_cmd->add_option(
      "--emit-plans", plan.emit_plans,
      "Write each sequence as plan files (disassembly and assembly) in this folder");
  plan_cmd->add_option("--dot", plan.dot,
                       "Write the AND/OR graph (Graphviz dot) with stable and unstable edges");
  plan_cmd->add_option("--keep", plan.keep, "Parts that stay in the assembly (comma-separated)")
      ->delimiter(',');
  plan_cmd
      ->add_option("--support", plan.support,
                   "Support of straight removals: full (carried, default), none (pushed "
                   "along the path), both")
      ->check(CLI::IsMember({"full", "none", "both"}));
  plan_cmd->add_flag("--single-parts", plan.no_subassemblies,
                     "Remove one part per step (no subassemblies)");
  plan_cmd->add_option("--dt", plan.dt, "Time step of simulated paths (s; default: size/100)")
      ->check(CLI::PositiveNumber);
  plan_cmd->add_option("--speed", plan.speed, "Gripper speed (length/s; default 1)")
      ->check(CLI::PositiveNumber);
  plan_cmd
      ->add_option("--allow-fixtures", plan.allow_fixtures,
                   "When nothing is stable, allow up to N fixels (fewest first)")
      ->check(CLI::Range(0, 20));
  AddModelOptions(plan_cmd, plan.model);

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
  if (*blocking_cmd) return cairn::cli::RunBlocking(blocking, std::cout, std::cerr);
  if (*plan_cmd) return cairn::cli::RunPlan(plan, std::cout, std::cerr);
  return cairn::cli::kExitBadInput;
}
