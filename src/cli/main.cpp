// cairn: the command-line tool. See docs/cli.md.

#include <CLI/CLI.hpp>
#include <cmath>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>

#include "cairn/core/error.h"
#include "cli/batch_command.h"
#include "cli/blocking_command.h"
#include "cli/check_command.h"
#include "cli/command.h"
#include "cli/convert_command.h"
#include "cli/margin_command.h"
#include "cli/mpi.h"
#include "cli/plan_command.h"
#include "cli/simulate_command.h"

namespace {

// Validators that say what is wrong in Cairn's words (CLI11's own print the
// range's bounds, 1.8e308 written out in 300 digits).
const CLI::Validator kPositive(
    [](std::string& value) -> std::string {
      double x = 0;
      if (!CLI::detail::lexical_cast(value, x) || !(x > 0) || !std::isfinite(x))
        return "must be a positive number (got " + value + ")";
      return "";
    },
    "POSITIVE");
const CLI::Validator kNonNegativeInteger(
    [](std::string& value) -> std::string {
      long long x = 0;
      if (!CLI::detail::lexical_cast(value, x) || x < 0)
        return "must be a whole number ≥ 0 (got " + value + ")";
      return "";
    },
    "N ≥ 0");
const CLI::Validator kNotEmpty(
    [](std::string& value) -> std::string {
      return value.empty() ? std::string("must not be empty") : std::string();
    },
    "");

// The options that say how the input file is read and what the command line
// changes in its model: the same on check, simulate and convert.
void AddModelOptions(CLI::App* cmd, cairn::cli::ModelArgs& model) {
  cmd->add_option("--format", model.format,
                  "Input format: scene (Cairn scene format 1, default), compas (a COMPAS "
                  "assembly of compas_assembly or compas_cra), step (a STEP assembly) or asap (an "
                  "ASAP folder: meshes and config.json)")
      ->check(CLI::IsMember({"scene", "compas", "step", "asap"}));
  cmd->add_option("--friction", model.friction,
                  "Coulomb friction coefficient of every contact (required with --format compas; "
                  "replaces the scene's default friction with --format scene)");
  cmd->add_option("--supports,--fixed", model.supports,
                  "Also fix these parts (COMPAS blocks: node keys), comma-separated")
      ->delimiter(',');
  // STEP and ASAP input (docs/step-format.md).
  cmd->add_option("--mesh-tolerance", model.mesh_tolerance,
                  "STEP: chordal tolerance of curved faces, metres (default: 1/1000 of the "
                  "smallest part's bounding-box diagonal)")
      ->check(kPositive);
  cmd->add_option("--sidecar", model.sidecar,
                  "STEP, ASAP: a JSON file with what the file does not carry (friction, "
                  "densities, masses, fixed parts)")
      ->check(kNotEmpty);
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
  cmd->add_option("--without", without, description)->delimiter(',')->check(kNotEmpty);
}

// --html FILE: the result page (docs/html.md).
void AddHtml(CLI::App* cmd, std::string& html) {
  cmd->add_option("--html", html,
                  "Write the result as one self-contained HTML page (opens from disk in a browser)")
      ->check(kNotEmpty);
}

CLI::App* AddCheck(CLI::App& app, cairn::cli::CheckArgs& check) {
  CLI::App* cmd =
      AddSceneCommand(app, "check", "Is one configuration of a scene stable under gravity?",
                      check.scene, check.json);
  cmd->add_option("--normalize", check.normalize, "Divide forces by the weight of this part")
      ->check(kNotEmpty);
  AddWithout(cmd, check.without, "Check with these parts taken away (comma-separated)");
  AddHtml(cmd, check.html);
  AddModelOptions(cmd, check.model);
  return cmd;
}

CLI::App* AddSimulate(CLI::App& app, cairn::cli::SimulateArgs& sim) {
  CLI::App* cmd = AddSceneCommand(
      app, "simulate", "Run a disassembly or assembly plan: is every step stable along its path?",
      sim.scene, sim.json);
  cmd->add_option("plan", sim.plan, "Plan file (JSON, plan format 1)")->required();
  cmd->add_option("--timeline", sim.timeline,
                  "Write one CSV row per time step and contact to this file")
      ->check(kNotEmpty);
  AddHtml(cmd, sim.html);
  cmd->add_option("--margin", sim.margin,
                  "Also find the least friction (factor) for which every tick is stable, and the "
                  "tick that decides it")
      ->check(CLI::IsMember({"friction"}));
  cmd->add_option("--normalize", sim.normalize, "Divide forces by the weight of this part")
      ->check(kNotEmpty);
  cmd->add_flag("--continue", sim.continue_after_failure,
                "Go on after a failure, as if it had been prevented");
  cmd->add_flag("--suggest-fixtures", sim.suggest_fixtures,
                "When a step fails, suggest the fewest fixels (point fixtures) that make the "
                "plan stable, verified by re-running it");
  cmd->add_option("--max-ticks", sim.max_ticks,
                  "The most time steps one step of the plan may take (default 1000000)")
      ->check(kNonNegativeInteger);
  cmd->add_option("--max-fixels", sim.max_fixels,
                  "The most fixels --suggest-fixtures adds (default 3)")
      ->check(CLI::Range(1, 20));
  AddModelOptions(cmd, sim.model);
  return cmd;
}

CLI::App* AddConvert(CLI::App& app, cairn::cli::ConvertArgs& convert) {
  CLI::App* cmd = app.add_subcommand(
      "convert", "Write the model of a file (e.g. a COMPAS assembly) as a scene file, format 1");
  cmd->add_option("input", convert.input, "Input file (--format says which format)")->required();
  cmd->add_option("output", convert.output, "Scene file to write (JSON, format 1)")->required();
  AddModelOptions(cmd, convert.model);
  return cmd;
}

CLI::App* AddBlocking(CLI::App& app, cairn::cli::BlockingArgs& blocking) {
  CLI::App* cmd = AddSceneCommand(
      app, "blocking", "Which parts can be taken out, and along which directions? (the NDBG)",
      blocking.scene, blocking.json);
  AddWithout(cmd, blocking.without, "Compute it with these parts taken away (comma-separated)");
  cmd->add_option("--direction", blocking.direction,
                  "Only the blocking graphs at this direction X,Y,Z (one cell), e.g. 1,0,0")
      ->delimiter(',')
      ->expected(1, 3);
  AddModelOptions(cmd, blocking.model);
  return cmd;
}

CLI::App* AddPlan(CLI::App& app, cairn::cli::PlanArgs& plan) {
  CLI::App* cmd = AddSceneCommand(
      app, "plan", "Find stable disassembly sequences (and their assembly plans) of a scene",
      plan.scene, plan.json);
  cmd->add_option("--max", plan.max,
                  "Stop after K stable sequences (best-first search); default: all")
      ->check(kNonNegativeInteger);
  cmd->add_option("--threads", plan.threads, "Worker threads (default: every core)")
      ->check(kNonNegativeInteger);
  cmd->add_option("--paths", plan.paths,
                  "Candidate paths per part (JSON: part name -> list of paths)")
      ->check(kNotEmpty);
  cmd->add_option("--emit-plans", plan.emit_plans,
                  "Write each sequence as plan files (disassembly and assembly) in this folder")
      ->check(kNotEmpty);
  cmd->add_option("--dot", plan.dot,
                  "Write the AND/OR graph (Graphviz dot) with stable and unstable edges")
      ->check(kNotEmpty);
  AddHtml(cmd, plan.html);
  cmd->add_option("--keep", plan.keep, "Parts that stay in the assembly (comma-separated)")
      ->delimiter(',');
  cmd->add_option("--support", plan.support,
                  "Support of straight removals: full (carried, default), none (pushed "
                  "along the path), both")
      ->check(CLI::IsMember({"full", "none", "both"}));
  cmd->add_flag("--single-parts", plan.no_subassemblies,
                "Remove one part per step (no subassemblies)");
  cmd->add_option("--dt", plan.dt, "Time step of simulated paths (s; default: size/100)")
      ->check(kPositive);
  cmd->add_option("--speed", plan.speed, "Gripper speed (length/s; default 1)")->check(kPositive);
  cmd->add_option("--allow-fixtures", plan.allow_fixtures,
                  "When nothing is stable, allow up to N fixels (fewest first)")
      ->check(CLI::Range(0, 20));
  cmd->add_option(
         "--directions", plan.directions,
         "Straight removal directions: ndbg (every cell of the NDBG, default) or axes "
         "(+-x, +-y, +-z only: for tessellated CAD models, whose NDBG has a cell per facet)")
      ->check(CLI::IsMember({"ndbg", "axes"}));
  AddModelOptions(cmd, plan.model);
  return cmd;
}

// ---- cairn batch (docs/batch.md) ----------------------------------------------

CLI::App* AddBatch(CLI::App& app, cairn::cli::BatchArgs& batch) {
  CLI::App* cmd = app.add_subcommand(
      "batch", "Run many jobs (check, simulate, plan, blocking) from a JSON-lines file");
  cmd->add_option("jobs", batch.jobs, "Jobs file (JSON lines: id, command, model, plan, options)")
      ->required();
  cmd->add_option("-o", batch.output, "Results file (JSON lines), appended job by job")
      ->required()
      ->check(kNotEmpty);
  cmd->add_flag("--fresh", batch.fresh, "Start over: empty the results file first");
  cmd->add_flag("--resume", batch.resume,
                "Skip the jobs already in the results file (the default)");
  cmd->add_option("--job-timeout", batch.job_timeout,
                  "Seconds a job may take; one that takes longer is recorded as timed out")
      ->check(kPositive);
  cmd->add_option("--threads", batch.threads,
                  "Jobs run at once without MPI ranks (default: every core)")
      ->check(kNonNegativeInteger);
  return cmd;
}

// A job's command line parsed as `cairn` parses it (the same subcommands,
// options and checks), to run in-process: what RunBatch calls per job.
// Building CLI11's options costs a sixth of a small check, so each thread
// builds them once and, per job, resets the values to their defaults and the
// parser to unparsed; the job keeps a copy of its values.
cairn::cli::JobCommand ParseJob(const std::vector<std::string>& args) {
  namespace cli = cairn::cli;
  struct Parsed {
    cli::CheckArgs check;
    cli::SimulateArgs sim;
    cli::BlockingArgs blocking;
    cli::PlanArgs plan;
  };
  struct Parser {
    Parsed values;  // bound to the options below: reset, never moved
    CLI::App app{"cairn"};
    CLI::App *check, *sim, *blocking, *plan;
    Parser()
        : check(AddCheck(app, values.check)),
          sim(AddSimulate(app, values.sim)),
          blocking(AddBlocking(app, values.blocking)),
          plan(AddPlan(app, values.plan)) {
      app.require_subcommand(1);
    }
  };
  thread_local Parser parser;
  parser.values = Parsed{};
  parser.app.clear();
  std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 takes them so
  try {
    parser.app.parse(reversed);
  } catch (const CLI::ParseError& e) {
    std::string what = e.what();
    for (char& c : what)
      if (c == '\n' || c == '\r') c = ' ';
    throw cairn::InputError("", "options", what);
  }
  const auto p = std::make_shared<const Parsed>(parser.values);
  if (*parser.check)
    return [p](const cli::Checkpoint& c) { return cli::CheckDocument(p->check, c); };
  if (*parser.sim)
    return [p](const cli::Checkpoint& c) { return cli::SimulateDocument(p->sim, c); };
  if (*parser.blocking)
    return [p](const cli::Checkpoint& c) { return cli::BlockingDocument(p->blocking, c); };
  if (*parser.plan) return [p](const cli::Checkpoint& c) { return cli::PlanDocument(p->plan, c); };
  throw cairn::InputError("", "command", "must be check, simulate, plan or blocking");
}

// `--friction [MU]` replaces the model option of the same name: alone it asks
// for the friction margin (MU, if given, is still the model's μ).
CLI::App* AddMargin(CLI::App& app, cairn::cli::MarginArgs& margin) {
  CLI::App* cmd = AddSceneCommand(
      app, "margin",
      "How far from failing? The critical friction, tilt about an axis, or largest load",
      margin.scene, margin.json);
  AddWithout(cmd, margin.without, "Compute it with these parts taken away (comma-separated)");
  AddModelOptions(cmd, margin.model);
  cmd->remove_option(cmd->get_option("--friction"));
  CLI::Option* friction =
      cmd->add_option("--friction", margin.friction_value,
                      "The critical friction: the least mu (or factor on every friction pair) "
                      "at which the assembly stands; with a value, also the model's mu")
          ->expected(0, 1);
  cmd->callback([&margin, friction] { margin.friction_given = friction->count() > 0; });
  cmd->add_option("--tilt", margin.query.tilt,
                  "The critical tilt about this axis X,Y,Z (the assembly turned with its fixed "
                  "parts), each sense")
      ->delimiter(',');
  cmd->add_option("--load", margin.query.load,
                  "The largest force on this part (at --point, along --direction) carried at rest")
      ->check(kNotEmpty);
  cmd->add_option("--point", margin.query.point, "Where the load acts (world frame), X,Y[,Z]")
      ->delimiter(',');
  cmd->add_option("--direction", margin.query.direction, "The load's direction, X,Y[,Z]")
      ->delimiter(',');
  return cmd;
}

// The command line: its subcommands and their options, parsed; then the
// chosen command runs. Returns the exit code.
int Run(int argc, char** argv) {
  namespace cli = cairn::cli;
  CLI::App app{"Cairn: does an assembly stay put while parts are taken out?"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "cairn 0.1.0");
  cli::CheckArgs check;
  cli::SimulateArgs sim;
  cli::ConvertArgs convert;
  cli::BlockingArgs blocking;
  cli::PlanArgs plan;
  const CLI::App* check_cmd = AddCheck(app, check);
  const CLI::App* sim_cmd = AddSimulate(app, sim);
  const CLI::App* convert_cmd = AddConvert(app, convert);
  const CLI::App* blocking_cmd = AddBlocking(app, blocking);
  const CLI::App* plan_cmd = AddPlan(app, plan);
  cli::BatchArgs batch;
  const CLI::App* batch_cmd = AddBatch(app, batch);
  cli::MarginArgs margin;
  const CLI::App* margin_cmd = AddMargin(app, margin);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version exit 0; a usage error is bad input (exit 2), said
    // on one line as every other error is.
    if (e.get_exit_code() == 0) return app.exit(e);
    std::string what = e.what();
    for (char& c : what)
      if (c == '\n' || c == '\r') c = ' ';
    std::cerr << "cairn: error: " << what << " (see cairn --help)\n";
    return cli::kExitBadInput;
  }
  if (*check_cmd) return cli::RunCheck(check, std::cout, std::cerr);
  if (*sim_cmd) return cli::RunSimulate(sim, std::cout, std::cerr);
  if (*convert_cmd) return cli::RunConvert(convert, std::cout, std::cerr);
  if (*blocking_cmd) return cli::RunBlocking(blocking, std::cout, std::cerr);
  // Under mpirun, rank 0 alone speaks: the others' streams go nowhere.
  std::ostringstream quiet_out, quiet_err;
  std::ostream& out = cli::MpiRank() == 0 ? std::cout : quiet_out;
  std::ostream& err = cli::MpiRank() == 0 ? std::cerr : quiet_err;
  if (*plan_cmd) {
    // A rank per core is MPI's way: --threads defaults to 1 per rank.
    if (cli::MpiSize() > 1 && plan.threads == 0) plan.threads = 1;
    return cli::RunPlan(plan, out, err);
  }
  if (*batch_cmd) return cli::RunBatch(batch, ParseJob, out, err);
  if (*margin_cmd) return cli::RunMargin(margin, out, err);
  return cli::kExitBadInput;
}

}  // namespace

// Any exception that escapes a command (they catch their own) is a defect:
// reported as an internal error with exit code 4, never a crash.
int main(int argc, char** argv) {
  // MPI, when started by mpirun (cli/mpi.h); ended after the command.
  const cairn::cli::MpiSession mpi(argc, argv);
  return cairn::cli::RunGuarded(std::cerr, [&] { return Run(argc, argv); });
}
