// cairn: the command-line tool. See docs/cli.md.

#include <CLI/CLI.hpp>  // IWYU pragma: keep
#include <algorithm>
#include <cctype>
#include <cmath>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "cairn/core/error.h"
#include "cli/batch_command.h"
#include "cli/blocking_command.h"
#include "cli/check_command.h"
#include "cli/command.h"
#include "cli/convert_command.h"
#include "cli/margin_command.h"
#include "cli/mpi.h"
#include "cli/plan_command.h"
#include "cli/sequence_command.h"
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

// A comma-separated list: its parts in order. An empty part (two commas in a
// row, a comma at an end, or nothing at all) is refused, as `what` says
// (e.g. "part name"), naming the option.
std::vector<std::string> SplitCommas(const std::string& token, const std::string& option,
                                     const std::string& what) {
  std::vector<std::string> parts;
  size_t begin = 0;
  while (true) {
    const size_t comma = token.find(',', begin);
    const size_t end = comma == std::string::npos ? token.size() : comma;
    if (end == begin) {
      const bool between = begin > 0 && comma != std::string::npos;
      throw CLI::ValidationError(option, "an empty " + what +
                                             (token.empty() ? std::string()
                                              : between     ? " (between two commas)"
                                                            : " (a comma at an end)"));
    }
    parts.push_back(token.substr(begin, end - begin));
    if (comma == std::string::npos) return parts;
    begin = comma + 1;
  }
}

// A list option (--without A,B): each occurrence takes exactly one argument,
// split at its commas, so that the argument after it (the scene file) is
// never taken as more of the list; it may be given again (the lists are
// joined); an empty name is refused.
CLI::Option* AddNameList(CLI::App* cmd, const std::string& name, std::vector<std::string>& out,
                         const std::string& description) {
  return cmd
      ->add_option(
          name,
          [&out, option = name.substr(0, name.find(','))](const CLI::results_t& tokens) {
            for (const std::string& token : tokens)
              for (std::string& part : SplitCommas(token, option, "part name"))
                out.push_back(std::move(part));
            return true;
          },
          description)
      ->type_name("NAME,...")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
}

// A vector option (--tilt X,Y,Z): exactly one argument, its numbers
// comma-separated, given once. How many numbers it needs is the command's to
// say (a 2-D scene takes 2, a 3-D one 3).
CLI::Option* AddNumberList(CLI::App* cmd, const std::string& name, std::vector<double>& out,
                           const std::string& description, const std::string& type_name) {
  return cmd
      ->add_option(
          name,
          [&out, name, type_name](const CLI::results_t& tokens) {
            if (tokens.size() != 1)
              throw CLI::ValidationError(name, "given " + std::to_string(tokens.size()) +
                                                   " times; give it once, as " + type_name);
            out.clear();
            for (const std::string& part : SplitCommas(tokens[0], name, "number")) {
              double x = 0;
              if (!CLI::detail::lexical_cast(part, x))
                throw CLI::ValidationError(
                    name, "\"" + part + "\" is not a number (" + type_name + ", comma-separated)");
              out.push_back(x);
            }
            return true;
          },
          description)
      ->type_name(type_name)
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
}

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
  AddNameList(cmd, "--supports,--fixed", model.supports,
              "Also fix these parts (COMPAS blocks: node keys), comma-separated");
  // STEP and ASAP input (docs/step-format.md).
  cmd->add_option("--mesh-tolerance", model.mesh_tolerance,
                  "STEP: chordal tolerance of curved faces, metres (default: 1/1000 of the "
                  "smallest part's bounding-box diagonal)")
      ->check(kPositive);
  AddNameList(cmd, "--fastened", model.fastened,
              "STEP: pairs A:B of parts joined into one rigid part (their exact solids fused: "
              "bolts, pins, press fits), comma-separated")
      ->type_name("A:B,...");
  AddNameList(cmd, "--touching", model.touching,
              "STEP: pairs A:B of overlapping parts made to touch (B loses what it shares with "
              "A), comma-separated")
      ->type_name("A:B,...");
  cmd->add_option("--sidecar", model.sidecar,
                  "STEP, ASAP: a JSON file with what the file does not carry (friction, "
                  "densities, masses, fixed parts)")
      ->check(kNotEmpty);
  cmd->add_option("--tolerance", model.tolerance,
                  "Length tolerance: contact distance, allowed overlap, planarity (default: the "
                  "scene's, or a fraction of the size of the assembly)");
  cmd->add_option("--overlap-depth", model.overlap_depth,
                  "3-D: how deep parts meant to touch may overlap (meshes as exported): such "
                  "overlaps are contacts on their mid-surface, each listed with its depth; "
                  "deeper ones are refused (default: the scene's overlap_depth, or 0)");
  AddNumberList(cmd, "--gravity", model.gravity,
                "Gravity vector, comma-separated (e.g. 0,0,9.81: the assembly upside down)",
                "X,Y[,Z]");
  cmd->add_option("--interfaces", model.interfaces,
                  "Contacts: detect (found from the shapes, default) or stored (a COMPAS file's "
                  "stored interfaces, for blocks modelled too loosely for exact contacts)")
      ->check(CLI::IsMember({"detect", "stored"}));
  // Every file the model is read from (docs/cli.md, "Reading the model").
  cmd->add_option("--max-input-size", model.max_input_size,
                  "The largest input file read, bytes, with an optional suffix K, M or G "
                  "(default 1G)")
      ->transform(CLI::Validator(
          [](std::string& text) -> std::string {
            const std::optional<std::uint64_t> bytes = cairn::ParseByteSize(text);
            if (!bytes)
              return "must be a positive number of bytes, with an optional suffix K, M or G "
                     "(e.g. 2G), not '" +
                     text + "'";
            text = std::to_string(*bytes);
            return "";
          },
          "BYTES"));
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
  AddNameList(cmd, "--without", without, description);
}

// --html FILE: the result page (docs/html.md).
void AddHtml(CLI::App* cmd, std::string& html) {
  cmd->add_option("--html", html,
                  "Write the result as one self-contained HTML page (opens from disk in a browser)")
      ->check(kNotEmpty);
}

// --rule and --require (check, simulate, plan): one verdict, the same flags.
void AddRuleOptions(CLI::App* cmd, std::string& rule, std::string& require) {
  cmd->add_option("--rule", rule,
                  "Where rigid bodies leave a static check open (an equilibrium, and no proof "
                  "that every contact solution rests): loaded-from-rest (default: it stands iff "
                  "it stands when gravity loads it from rest on compliant contacts) or "
                  "equilibrium (it stands iff a static equilibrium exists, as "
                  "rigid-block-equilibrium tools say)")
      ->check(CLI::IsMember({"loaded-from-rest", "equilibrium"}));
  cmd->add_option("--require", require,
                  "strong: exit 3 when it stands but strong stability (every contact solution "
                  "at rest) is not proved (plan: such states are not stable)")
      ->check(CLI::IsMember({"strong"}));
}

CLI::App* AddCheck(CLI::App& app, cairn::cli::CheckArgs& check) {
  CLI::App* cmd =
      AddSceneCommand(app, "check", "Is one configuration of a scene stable under gravity?",
                      check.scene, check.json);
  cmd->add_option("--normalize", check.normalize, "Divide forces by the weight of this part")
      ->check(kNotEmpty);
  AddWithout(cmd, check.without, "Check with these parts taken away (comma-separated)");
  cmd->add_option("--contacts", check.contacts,
                  "The contact forces the summary lists: summary (the most loaded contacts and "
                  "each pair of parts' resultant, default), all (every contact) or none; --json "
                  "has every one")
      ->check(CLI::IsMember({"summary", "all", "none"}));
  AddHtml(cmd, check.html);
  AddRuleOptions(cmd, check.rule, check.require);
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
  AddRuleOptions(cmd, sim.rule, sim.require);
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
  AddNumberList(cmd, "--direction", blocking.direction,
                "Only the blocking graphs at this direction (one cell): X,Y in a 2-D scene, "
                "X,Y,Z in a 3-D one, e.g. 1,0,0",
                "X,Y[,Z]");
  AddHtml(cmd, blocking.html);
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
  AddRuleOptions(cmd, plan.rule, plan.require);
  AddNameList(cmd, "--keep", plan.keep, "Parts that stay in the assembly (comma-separated)");
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

// ---- cairn sequence (docs/sequence.md) ------------------------------------------

CLI::App* AddSequence(CLI::App& app, cairn::cli::SequenceArgs& sequence) {
  CLI::App* cmd = AddSceneCommand(
      app, "sequence",
      "Find a build order, one part a step, in which every state stands, with the fewest "
      "temporary supports",
      sequence.scene, sequence.json);
  cmd->add_option("--temporary", sequence.temporary,
                  "The temporary supports allowed: hold (a placed part held where it is, as a "
                  "robot or a crane holds a block), prop (a point support from the ground under a "
                  "part's face, as falsework) or both")
      ->check(CLI::IsMember({"hold", "prop", "both"}));
  cmd->add_option("--max-temporary", sequence.max_temporary,
                  "The most supports in place at once (default: no bound; 0: none)")
      ->check(kNonNegativeInteger);
  AddNumberList(cmd, "--direction", sequence.direction,
                "The removal direction (a part arrives along its reverse): X,Y in a 2-D scene, "
                "X,Y,Z in a 3-D one; default: against gravity",
                "X,Y[,Z]");
  cmd->add_option("--directions", sequence.directions,
                  "Removal directions tried in turn: up (against gravity, default), axes (up, "
                  "then +-x, +-y (, +-z)) or ndbg (the NDBG's cells, closest to up first)")
      ->check(CLI::IsMember({"up", "axes", "ndbg"}));
  cmd->add_option("--beam", sequence.beam, "States kept per step (default 4; 1: greedy)")
      ->check(CLI::Range(1, 1000));
  cmd->add_option("--threads", sequence.threads,
                  "Worker threads (default: every core; with --temporary both, the searches with "
                  "holds alone and with both run side by side)")
      ->check(kNonNegativeInteger);
  cmd->add_option("--time-limit", sequence.time_limit,
                  "Seconds the search may take; then (or on Ctrl-C) the best order so far, with "
                  "its bound")
      ->check(kPositive);
  cmd->add_option("--emit-plans", sequence.emit_plans,
                  "Write the order as an assembly plan (sequence.assemble.plan.json, the holds as "
                  "held parts) in this folder, for cairn simulate")
      ->check(kNotEmpty);
  AddHtml(cmd, sequence.html);
  AddRuleOptions(cmd, sequence.rule, sequence.require);
  AddModelOptions(cmd, sequence.model);
  return cmd;
}

// ---- cairn batch (docs/batch.md) ----------------------------------------------

CLI::App* AddMargin(CLI::App& app, cairn::cli::MarginArgs& margin);

CLI::App* AddBatch(CLI::App& app, cairn::cli::BatchArgs& batch) {
  CLI::App* cmd = app.add_subcommand(
      "batch",
      "Run many jobs (check, simulate, plan, blocking, margin, sequence) from a JSON-lines file");
  cmd->add_option("jobs", batch.jobs, "Jobs file (JSON lines: id, command, model, plan, options)")
      ->required();
  cmd->add_option("-o", batch.output, "Results file (JSON lines), appended job by job")
      ->required()
      ->check(kNotEmpty);
  cmd->add_flag("--fresh", batch.fresh, "Start over: empty the results file first");
  cmd->add_flag("--resume", batch.resume,
                "Skip the jobs already in the results file (the default)");
  cmd->add_flag("--retry-failed", batch.retry_failed,
                "Also run again the jobs recorded as failed (exit 2, 4 or 5)");
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
    cli::MarginArgs margin;
    cli::SequenceArgs sequence;
  };
  struct Parser {
    Parsed values;  // bound to the options below: reset, never moved
    CLI::App app{"cairn"};
    CLI::App *check, *sim, *blocking, *plan, *margin, *sequence;
    Parser()
        : check(AddCheck(app, values.check)),
          sim(AddSimulate(app, values.sim)),
          blocking(AddBlocking(app, values.blocking)),
          plan(AddPlan(app, values.plan)),
          margin(AddMargin(app, values.margin)),
          sequence(AddSequence(app, values.sequence)) {
      app.require_subcommand(1);
    }
  };
  thread_local Parser parser;
  parser.values = Parsed{};
  parser.app.clear();
  // A job's `true` is a flag: an option that takes a value would take the
  // next argument (`--` or the model) as its value instead.
  const CLI::App* command = nullptr;
  for (const CLI::App* sub :
       {parser.check, parser.sim, parser.blocking, parser.plan, parser.margin, parser.sequence})
    if (!args.empty() && sub->get_name() == args[0]) command = sub;
  if (command != nullptr) {
    for (const std::string& arg : args) {
      if (arg == "--") break;
      if (arg.rfind("--", 0) != 0 || arg.find('=') != std::string::npos) continue;
      const CLI::Option* option = command->get_option_no_throw(arg);
      if (option != nullptr && option->get_expected_min() > 0)
        throw cairn::InputError("", "options." + arg.substr(2),
                                "takes a value (a string, a number or a list), not true");
    }
  }
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
  if (*parser.margin)
    return [p](const cli::Checkpoint& c) { return cli::MarginDocument(p->margin, c); };
  if (*parser.sequence)
    return [p](const cli::Checkpoint& c) { return cli::SequenceDocument(p->sequence, c); };
  throw cairn::InputError("", "command",
                          "must be check, simulate, plan, blocking, margin or sequence");
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
  AddNumberList(cmd, "--tilt", margin.query.tilt,
                "The critical tilt about this axis X,Y,Z (the assembly turned with its fixed "
                "parts), each sense",
                "X,Y,Z");
  cmd->add_option("--load", margin.query.load,
                  "The largest force on this part (at --point, along --direction) carried at rest")
      ->check(kNotEmpty);
  AddNumberList(cmd, "--point", margin.query.point, "Where the load acts (world frame), X,Y[,Z]",
                "X,Y[,Z]");
  AddNumberList(cmd, "--direction", margin.query.direction, "The load's direction, X,Y[,Z]",
                "X,Y[,Z]");
  cmd->add_option("--rule", margin.rule,
                  "The verdict whose threshold (and exit code) the margin gives, as on check: "
                  "loaded-from-rest (default) or equilibrium")
      ->check(CLI::IsMember({"loaded-from-rest", "equilibrium"}));
  AddHtml(cmd, margin.html);
  return cmd;
}

// ---- Usage errors in a person's words ------------------------------------------

// The edit distance (insertions, deletions, substitutions and swaps of two
// neighbours) between two names: how far a typo is from what was meant.
size_t EditDistance(const std::string& a, const std::string& b) {
  std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
  for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (size_t i = 1; i <= a.size(); ++i)
    for (size_t j = 1; j <= b.size(); ++j) {
      d[i][j] = std::min(
          {d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

// A name is suggested for a typo when it is at most this many edits away per
// this many characters of the typo (at least one edit): "withot" (6) gets
// "without" (1 edit), "chek" (4) gets "check".
constexpr size_t kCharactersPerSuggestedEdit = 3;

// The nearest of `names` to `typo`, if it is near enough to be what was meant
// ("" if none is, or if two are equally near).
std::string Nearest(const std::string& typo, const std::vector<std::string>& names) {
  const size_t most = std::max<size_t>(1, typo.size() / kCharactersPerSuggestedEdit);
  std::string best;
  size_t best_distance = most + 1;
  bool tie = false;
  for (const std::string& name : names) {
    const size_t d = EditDistance(typo, name);
    if (d < best_distance) {
      best = name, best_distance = d, tie = false;
    } else if (d == best_distance && name != best) {
      tie = true;
    }
  }
  return tie ? std::string() : best;
}

std::vector<const CLI::App*> Commands(const CLI::App& app) {
  return app.get_subcommands([](const CLI::App*) { return true; });
}

// The option names of a command, with their dashes: --without, -o.
std::vector<std::string> OptionNames(const CLI::App& cmd) {
  std::vector<std::string> names;
  for (const CLI::Option* opt : cmd.get_options()) {
    for (const std::string& l : opt->get_lnames()) names.push_back("--" + l);
    for (const std::string& s : opt->get_snames()) names.push_back("-" + s);
  }
  return names;
}

// An argument that names an option (not a negative number such as -1,0,0).
bool LooksLikeOption(const std::string& arg) {
  if (arg.size() < 2 || arg[0] != '-') return false;
  return !(std::isdigit(static_cast<unsigned char>(arg[1])) || arg[1] == '.');
}

// What is wrong with a command line, said as a person would: an unknown
// command or option (with the nearest one, if one is near), an option
// without its value (CLI11 would take the option after it as its value), an
// argument too many. Empty when none of these is found: CLI11 parses it, and
// its own words are the message of what else it refuses.
std::string ExplainUsage(const CLI::App& app, const std::vector<std::string>& args) {
  std::vector<std::string> command_names;
  for (const CLI::App* c : Commands(app)) command_names.push_back(c->get_name());
  std::string list;
  for (size_t i = 0; i < command_names.size(); ++i)
    list += (i == 0 ? "" : i + 1 == command_names.size() ? " or " : ", ") + command_names[i];
  if (args.empty()) return "say which command: " + list;
  if (LooksLikeOption(args[0])) {
    const std::string name = args[0].substr(0, args[0].find('='));
    if (app.get_option_no_throw(name) == nullptr)
      return "unknown option " + name + " (a command comes first: " + list + ")";
    return "";
  }
  const CLI::App* cmd = nullptr;
  for (const CLI::App* c : Commands(app))
    if (c->get_name() == args[0]) cmd = c;
  if (cmd == nullptr) {
    const std::string near = Nearest(args[0], command_names);
    return "unknown command '" + args[0] + "'" +
           (near.empty() ? " (the commands: " + list + ")" : " (did you mean " + near + "?)");
  }
  const std::string& command = args[0];
  size_t positionals = 0, required = 0;
  for (const CLI::Option* opt : cmd->get_options())
    if (opt->get_positional()) ++positionals, required += opt->get_required() ? 1 : 0;
  size_t given = 0;
  std::string swallowed;  // an optional value that is no number: a file?
  bool only_positionals = false;
  for (size_t i = 1; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (!only_positionals && arg == "--") {
      only_positionals = true;
      continue;
    }
    if (only_positionals || !LooksLikeOption(arg)) {
      if (++given > positionals)
        return "unexpected argument '" + arg + "': " + command + " takes " +
               std::to_string(positionals) + " file" + (positionals == 1 ? "" : "s") +
               " (an option's list is one argument, without spaces: --without A,B)";
      continue;
    }
    const size_t eq = arg.find('=');
    const std::string name = arg.substr(0, eq);
    const CLI::Option* opt = cmd->get_option_no_throw(name);
    if (opt == nullptr) {
      const std::string near = Nearest(name, OptionNames(*cmd));
      if (!near.empty()) return "unknown option " + name + " (did you mean " + near + "?)";
      std::string others;
      for (const CLI::App* c : Commands(app))
        if (c != cmd && c->get_option_no_throw(name) != nullptr)
          others += (others.empty() ? "" : ", ") + c->get_name();
      return "unknown option " + name + " for " + command +
             (others.empty() ? ""
                             : " (" + others + " take" +
                                   (others.find(',') == std::string::npos ? "s" : "") + " it)") +
             "; see cairn " + command + " --help";
    }
    if (opt->get_items_expected_max() == 0) continue;  // a flag
    if (eq != std::string::npos) {
      if (eq + 1 == arg.size() && opt->get_items_expected_min() > 0)
        return name + " needs a value (nothing after '=')";
      continue;
    }
    const bool has_value = i + 1 < args.size() && !LooksLikeOption(args[i + 1]);
    if (opt->get_items_expected_min() > 0 && !has_value) return name + " needs a value";
    if (has_value && opt->get_items_expected_min() == 0) {
      double x = 0;
      if (!CLI::detail::lexical_cast(args[i + 1], x))
        swallowed = name + " took '" + args[i + 1] + "' as its value: write the file before " +
                    name + ", or " + name + "=VALUE";
    }
    if (has_value) ++i;  // the option's value (optional ones take it too)
  }
  if (given < required && !swallowed.empty()) return "a file is missing: " + swallowed;
  return "";
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
  cli::SequenceArgs sequence;
  const CLI::App* check_cmd = AddCheck(app, check);
  const CLI::App* sim_cmd = AddSimulate(app, sim);
  const CLI::App* convert_cmd = AddConvert(app, convert);
  const CLI::App* blocking_cmd = AddBlocking(app, blocking);
  const CLI::App* plan_cmd = AddPlan(app, plan);
  const CLI::App* sequence_cmd = AddSequence(app, sequence);
  cli::BatchArgs batch;
  const CLI::App* batch_cmd = AddBatch(app, batch);
  cli::MarginArgs margin;
  const CLI::App* margin_cmd = AddMargin(app, margin);
  // A usage error is bad input (exit 2), said on one line as every other
  // error is: in Cairn's words for an unknown command or option, a missing
  // value or an argument too many; else CLI11's (a value its check refused).
  const std::string explained =
      ExplainUsage(app, std::vector<std::string>(argv + std::min(argc, 1), argv + argc));
  if (!explained.empty()) {
    std::cerr << "cairn: error: " << explained << '\n';
    return cli::kExitBadInput;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version exit 0.
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
  if (*sequence_cmd) return cli::RunSequence(sequence, std::cout, std::cerr);
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
