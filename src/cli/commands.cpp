#include "cli/commands.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>

#include "cairn/core/error.h"
#include "cairn/io/compas_reader.h"
#include "cairn/io/plan_reader.h"
#include "cairn/io/scene_reader.h"
#include "cairn/motion/simulate.h"
#include "cairn/report/report.h"
#include "cairn/stability/analyze.h"
#include "cli/scene_writer.h"

namespace cairn::cli {

namespace {

// ---- Reading the model -----------------------------------------------------

// A model read from a file with the command line's changes applied: the
// definition (what convert writes) and the validated Assembly.
struct Model {
  AssemblyDef def;
  Assembly assembly;
};

std::string Num(double x) {
  std::ostringstream os;
  os << x;
  return os.str();
}

// Reads `file` in `args.format` and applies --friction, --supports and
// --gravity. Every fault is an InputError: of the file (with its JSON path),
// or of a flag (the flag as path).
Model LoadModel(const std::string& file, const ModelArgs& args) {
  if (args.friction) {
    // CLI11 parses "nan" and "inf" as doubles; neither is a coefficient.
    if (!std::isfinite(*args.friction))
      throw InputError("", "--friction",
                       "must be a finite number (got " + Num(*args.friction) + ")");
    if (*args.friction < 0)
      throw InputError("", "--friction", "must not be negative (got " + Num(*args.friction) + ")");
  }
  if (args.tolerance && !(std::isfinite(*args.tolerance) && *args.tolerance > 0))
    throw InputError("", "--tolerance",
                     "must be a positive length (got " + Num(*args.tolerance) + ")");
  for (double g : args.gravity) {
    if (!std::isfinite(g))
      throw InputError("", "--gravity", "must have finite components (got " + Num(g) + ")");
  }

  Model m;
  std::optional<CompasModel> compas;
  if (args.format == "compas") {
    // COMPAS files store no friction coefficient, and guessing one (0 is
    // "everything slides", compas_cra's 0.84 is a choice of theirs) would
    // change the verdict silently.
    if (!args.friction)
      throw InputError("", "--friction",
                       "is required with --format compas (COMPAS files store no friction "
                       "coefficient; give 0 for frictionless contacts)");
    CompasOptions options;
    options.friction = *args.friction;
    options.tolerance = args.tolerance.value_or(0.0);
    options.stored_interfaces = args.interfaces == "stored";
    compas = CompasToModel(ReadCompasAssembly(file), options, file);
    m.def = compas->def;
  } else {
    if (args.interfaces == "stored")
      throw InputError("", "--interfaces",
                       "stored is for --format compas (a scene file gives its interfaces in "
                       "`interfaces`)");
    try {
      m.def = ReadSceneDef(file);
    } catch (const InputError& e) {
      // A COMPAS file read as a scene misses the version key first: say what
      // to do instead of only what is wrong.
      if (e.json_path() != "cairn" || e.message().find("required key is missing") != 0) throw;
      throw InputError(e.file(), e.json_path(),
                       e.message() + "; if this is a COMPAS assembly, give --format compas");
    }
    if (args.friction) m.def.friction = *args.friction;
    if (args.tolerance) m.def.tolerance = *args.tolerance;
  }

  const bool is3 = !m.def.parts.empty() && m.def.parts[0].polyhedron.has_value();
  for (const std::string& name : args.supports) {
    const auto it = std::find_if(m.def.parts.begin(), m.def.parts.end(),
                                 [&](const PartDef& p) { return p.name == name; });
    if (it == m.def.parts.end())
      throw InputError("", "--supports", "no part named '" + name + "' in " + file);
    if (it->tool)
      throw InputError("", "--supports",
                       "part '" + name + "' is a tool (a gripper's pad): it cannot be fixed");
    it->fixed = true;
  }
  if (!args.gravity.empty()) {
    const size_t dim = is3 ? 3 : 2;
    if (args.gravity.size() != dim)
      throw InputError("", "--gravity",
                       "must have " + std::to_string(dim) + " numbers in a " + std::to_string(dim) +
                           "-D scene, not " + std::to_string(args.gravity.size()));
    m.def.gravity = Vector3(args.gravity[0], args.gravity[1], is3 ? args.gravity[2] : 0.0);
  }

  if (compas) {
    compas->def = m.def;
    m.assembly = CreateCompasAssembly(*compas, file);
  } else {
    m.assembly = Assembly::Create(m.def, file);
  }
  return m;
}

}  // namespace

int RunCheck(const CheckArgs& args, std::ostream& out, std::ostream& err) {
  try {
    const Assembly assembly = LoadModel(args.scene, args.model).assembly;
    ReportOptions report;
    report.scene_file = args.scene;
    // Resolve part names given on the command line.
    const auto resolve = [&](const std::string& name, const std::string& flag) {
      const int i = assembly.FindPart(name);
      if (i < 0) throw InputError("", flag, "no part named '" + name + "' in " + args.scene);
      return i;
    };
    if (!args.normalize.empty()) {
      report.normalize_part = resolve(args.normalize, "--normalize");
      if (assembly.part(*report.normalize_part).mass <= 0)
        throw InputError("", "--normalize", "part '" + args.normalize + "' has no weight");
    }
    Configuration config = Configuration::Assembled(assembly);
    for (const std::string& name : args.without) {
      const int i = resolve(name, "--without");
      config.present[i] = false;
      report.without.push_back(i);
    }
    StabilityOptions analysis;
    analysis.check_equilibrium = true;  // report jamming (weak stability) too
    const StabilityResult result = AnalyzeConfiguration(assembly, config, analysis);
    if (args.json)
      out << StabilityToJson(assembly, config, result, report).dump(2) << '\n';
    else
      out << StabilityToText(assembly, config, result, report);
    return result.stable() ? kExitStable : kExitUnstable;
  } catch (const InputError& e) {
    err << "cairn: error: " << e.what() << '\n';
    return kExitBadInput;
  }
}

namespace {

// Writes `text` to `path` whole or not at all: a temporary file beside it,
// renamed over it once complete. @throws InputError naming the flag.
void WriteAtomically(const std::string& path, const std::string& text, const std::string& flag) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary);
    if (!(f << text) || !f.flush()) {
      std::remove(tmp.c_str());
      throw InputError("", flag, "cannot write '" + path + "'");
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::remove(tmp.c_str());
    throw InputError("", flag, "cannot write '" + path + "': " + ec.message());
  }
}

}  // namespace

int RunSimulate(const SimulateArgs& args, std::ostream& out, std::ostream& err) {
  try {
    const Assembly assembly = LoadModel(args.scene, args.model).assembly;
    if (assembly.has_interfaces())
      throw InputError(args.scene, "interfaces",
                       "the contacts are given as interfaces of the assembled configuration: "
                       "parts cannot be moved along a plan (check it, with --without for "
                       "subassemblies, or let Cairn find the contacts from the shapes)");
    const Plan plan = ReadPlan(args.plan, assembly);
    ReportOptions report;
    report.scene_file = args.scene;
    if (!args.normalize.empty()) {
      const int i = assembly.FindPart(args.normalize);
      if (i < 0)
        throw InputError("", "--normalize",
                         "no part named '" + args.normalize + "' in " + args.scene);
      report.normalize_part = i;
    }
    SimulationOptions options;
    options.continue_after_failure = args.continue_after_failure;
    options.record_timeline = !args.timeline.empty();
    const SimulationResult result = SimulatePlan(assembly, plan, options);
    // Everything is computed before anything is written.
    const std::string text = args.json
                                 ? SimulationToJson(assembly, plan, result, report).dump(2) + "\n"
                                 : SimulationToText(assembly, plan, result, report);
    if (!args.timeline.empty())
      WriteAtomically(args.timeline, TimelineToCsv(assembly, result, report), "--timeline");
    out << text;
    switch (result.verdict) {
      case MotionVerdict::kStable:
        return kExitStable;
      case MotionVerdict::kInfeasible:
        return kExitInfeasible;
      default:
        return kExitUnstable;
    }
  } catch (const InputError& e) {
    err << "cairn: error: " << e.what() << '\n';
    return kExitBadInput;
  }
}

int RunConvert(const ConvertArgs& args, std::ostream& out, std::ostream& err) {
  try {
    // The model is validated (Assembly::Create) before anything is written,
    // so a scene that convert writes is one `cairn check` reads.
    const Model m = LoadModel(args.input, args.model);
    const std::string text = WriteSceneJson(m.def);
    WriteAtomically(args.output, text, "");
    int fixed = 0;
    for (const Part& p : m.assembly.parts()) fixed += p.fixed ? 1 : 0;
    out << "cairn: wrote " << args.output << ": " << m.assembly.num_parts() << " parts (" << fixed
        << " fixed), " << m.assembly.dimension() << "-D, friction " << Num(m.def.friction) << '\n';
    return kExitStable;
  } catch (const InputError& e) {
    err << "cairn: error: " << e.what() << '\n';
    return kExitBadInput;
  }
}

}  // namespace cairn::cli
