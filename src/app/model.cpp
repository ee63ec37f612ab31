#include "cairn/app/model.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <optional>
#include <ostream>

#include "cairn/core/error.h"
#include "cairn/core/tolerances.h"
#include "cairn/io/asap_reader.h"
#include "cairn/io/compas_reader.h"
#include "cairn/io/scene_reader.h"
#include "cairn/io/sidecar_reader.h"
#include "cairn/io/step_reader.h"

namespace cairn::app {

namespace {

// "A:B" of --fastened or --touching as its two names. @throws InputError
// naming `flag` when it is not two non-empty names around one ':'.
std::pair<std::string, std::string> PartPair(const std::string& pair, const std::string& flag) {
  const size_t colon = pair.find(':');
  if (colon == std::string::npos || colon == 0 || colon + 1 == pair.size() ||
      pair.find(':', colon + 1) != std::string::npos)
    throw InputError("", flag, "\"" + EscapedName(pair) + "\" is not a pair of part names A:B");
  return {pair.substr(0, colon), pair.substr(colon + 1)};
}

std::vector<std::pair<std::string, std::string>> PartPairs(const std::vector<std::string>& pairs,
                                                           const std::string& flag) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const std::string& pair : pairs) out.push_back(PartPair(pair, flag));
  return out;
}

// The model options' own numbers: finite, and of their sign.
void CheckModelFlags(const ModelArgs& args) {
  // The CLI's parser takes only these; the Python module passes strings.
  if (args.format != "scene" && args.format != "compas" && args.format != "step" &&
      args.format != "asap")
    throw InputError("", "--format",
                     "must be scene, compas, step or asap, not \"" + args.format + "\"");
  if (args.interfaces != "detect" && args.interfaces != "stored")
    throw InputError("", "--interfaces",
                     "must be detect or stored, not \"" + args.interfaces + "\"");
  if (args.friction) {
    // CLI11 parses "nan" and "inf" as doubles; neither is a coefficient.
    if (!std::isfinite(*args.friction))
      throw InputError("", "--friction",
                       "must be a finite number (got " + FormatNumber(*args.friction) + ")");
    if (*args.friction < 0)
      throw InputError("", "--friction",
                       "must not be negative (got " + FormatNumber(*args.friction) + ")");
    if (*args.friction > limits::kMaxFriction)
      throw InputError("", "--friction",
                       "is out of range (got " + FormatNumber(*args.friction) + "; at most " +
                           FormatNumber(limits::kMaxFriction) + ")");
  }
  if (args.tolerance && !(std::isfinite(*args.tolerance) && *args.tolerance > 0))
    throw InputError("", "--tolerance",
                     "must be a positive length (got " + FormatNumber(*args.tolerance) + ")");
  if (args.overlap_depth && !(std::isfinite(*args.overlap_depth) && *args.overlap_depth >= 0))
    throw InputError("", "--overlap-depth",
                     "must be a length ≥ 0 (got " + FormatNumber(*args.overlap_depth) + ")");
  if (args.mesh_tolerance && !(std::isfinite(*args.mesh_tolerance) && *args.mesh_tolerance > 0))
    throw InputError(
        "", "--mesh-tolerance",
        "must be a positive length in metres (got " + FormatNumber(*args.mesh_tolerance) + ")");
  if (args.mesh_tolerance && args.format != "step")
    throw InputError("", "--mesh-tolerance", "applies to --format step only");
  for (const auto* pairs : {&args.fastened, &args.touching}) {
    const std::string flag = pairs == &args.fastened ? "--fastened" : "--touching";
    if (!pairs->empty() && args.format != "step")
      throw InputError("", flag,
                       "applies to --format step only (it joins the parts' exact solids)");
    for (const std::string& pair : *pairs) PartPair(pair, flag);
  }
  if (!args.sidecar.empty() && args.format != "step" && args.format != "asap" &&
      args.format != "compas")
    throw InputError("", "--sidecar",
                     "applies to --format step, asap and compas (a scene file says it all itself)");
  if (args.max_input_size == 0)
    throw InputError("", "--max-input-size", "must be a positive number of bytes");
  for (double g : args.gravity) {
    if (!std::isfinite(g))
      throw InputError("", "--gravity",
                       "must have finite components (got " + FormatNumber(g) + ")");
  }
}

// --supports and --gravity applied to the definition read from `file`.
void ApplyModelFlags(const ModelArgs& args, const std::string& file, AssemblyDef& def) {
  const bool is3 = !def.parts.empty() && def.parts[0].polyhedron.has_value();
  for (const std::string& name : args.supports) {
    const auto it = std::find_if(def.parts.begin(), def.parts.end(),
                                 [&](const PartDef& p) { return p.name == name; });
    if (it == def.parts.end())
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
    def.gravity = Vector3(args.gravity[0], args.gravity[1], is3 ? args.gravity[2] : 0.0);
    def.gravity_option = "--gravity";
  }
  if (args.tolerance) def.tolerance_option = "--tolerance";
  if (args.overlap_depth) {
    def.overlap_depth = *args.overlap_depth;
    def.overlap_depth_option = "--overlap-depth";
  }
}

// COMPAS files store no friction coefficient, and guessing one (0 is
// "everything slides", compas_cra's 0.84 is a choice of theirs) would change
// the verdict silently.
void RequireCompasFriction(const ModelArgs& args) {
  if (!args.friction)
    throw InputError("", "--friction",
                     "is required with --format compas (COMPAS files store no friction "
                     "coefficient; give 0 for frictionless contacts)");
}

// One line per part a STEP reading approximated: the chordal tolerance of
// its tessellation and what it did to the volume; and one per part the
// reading did more to (a mesher's fallback, a closed shell read as a solid,
// parts fastened or cut to touch).
void NoteApproximations(const std::string& file, const StepModel& step, std::ostream& notes) {
  for (const StepPartReport& r : step.parts) {
    if (!r.approximated) {
      if (!r.fallback.empty())
        notes << "cairn: note: " << file << ": part '" << EscapedName(r.name) << "': " << r.fallback
              << "\n";
      continue;
    }
    const double change =
        r.exact_volume > 0 ? 100.0 * (r.volume - r.exact_volume) / r.exact_volume : 0.0;
    char percent[32];
    std::snprintf(percent, sizeof percent, "%+.3g%%", change);
    notes << "cairn: note: " << file << ": part '" << EscapedName(r.name)
          << "' approximated: " << r.tessellated_faces << " face"
          << (r.tessellated_faces == 1 ? "" : "s")
          << " with curved surfaces or edges tessellated within " << FormatNumber(r.mesh_tolerance)
          << " m (chordal), " << r.exact_faces << " planar face" << (r.exact_faces == 1 ? "" : "s")
          << " exact; volume " << FormatNumber(r.volume) << " m^3 against "
          << FormatNumber(r.exact_volume) << " m^3 exact (" << percent << ")\n";
    if (!r.fallback.empty())
      notes << "cairn: note: " << file << ": part '" << EscapedName(r.name) << "': " << r.fallback
            << "\n";
  }
}

StepReadOptions StepOptions(const ModelArgs& args) {
  StepReadOptions options;
  options.mesh_tolerance = args.mesh_tolerance.value_or(0.0);
  options.max_input_size = args.max_input_size;
  options.fastened = PartPairs(args.fastened, "--fastened");
  options.touching = PartPairs(args.touching, "--touching");
  return options;
}

// The definition of a STEP assembly or an ASAP folder, with its sidecar;
// `set_by` gets the sidecar's JSON path of each mass or density it set.
AssemblyDef ReadCadDef(const std::string& file, const ModelArgs& args, std::ostream* notes,
                       std::map<std::string, std::string>& set_by) {
  // The sidecar is checked first: before minutes of reading a large model.
  if (!args.sidecar.empty()) CheckInputFile(args.sidecar, args.max_input_size);
  AssemblyDef def;
  if (args.format == "step") {
    const StepModel step = ReadStepAssembly(file, StepOptions(args));
    if (notes) NoteApproximations(file, step, *notes);
    def = step.def;
  } else {
    def = ReadAsapAssembly(file, args.max_input_size);
  }
  if (!args.sidecar.empty()) set_by = ApplySidecar(args.sidecar, def, args.max_input_size);
  return def;
}

// The power of ten above `tol` (1e-4 for 1.87702e-05; 1e-5 for 1e-6), as
// the command line writes it.
std::string NextPowerOfTen(double tol) {
  int exponent = static_cast<int>(std::ceil(std::log10(tol)));
  if (std::pow(10.0, exponent) <= tol * (1 + 1e-9)) ++exponent;
  return "1e" + std::to_string(exponent);
}

// `x` (> 0) rounded up to one significant digit (0.045 → 0.05), as the
// command line writes it.
std::string RoundedUp(double x) {
  const double unit = std::pow(10.0, std::floor(std::log10(x)));
  return FormatNumber(std::ceil(x / unit * (1 - 1e-12)) * unit);
}

// Parts that overlap by more than the tolerance: the message says that
// --tolerance raises it and, in 3-D, that --overlap-depth reads parts meant
// to touch as touching where they overlap (with an overlap depth already,
// that it raises it), each with an example: the power of ten above the
// tolerance, or half as much again as the deepest pair's depth (a witness's
// depth is a lower bound on its pair's), rounded up.
[[noreturn]] void OverlapFault(const OverlapError& e, const ModelArgs& args,
                               const AssemblyDef& def) {
  if (!(e.tolerance() > 0) || !std::isfinite(e.tolerance())) throw e;
  double deepest = 0;
  for (const PartOverlap& o : e.overlaps()) deepest = std::max(deepest, o.depth);
  const std::string depth_example =
      deepest > 0 ? "--overlap-depth " + RoundedUp(1.5 * std::max(deepest, e.tolerance()))
                  : std::string();
  if (def.overlap_depth > 0 && deepest > 0)
    throw InputError(e.file(), e.json_path(),
                     e.message() + " (raise it with --overlap-depth" +
                         (args.format == "scene" ? " or the scene's `overlap_depth`" : "") +
                         ", e.g. " + depth_example + ")");
  const std::string example = "--tolerance " + NextPowerOfTen(e.tolerance());
  throw InputError(
      e.file(), e.json_path(),
      e.message() + " (raise it with --tolerance" +
          (args.format == "scene" ? " or the scene's `tolerance`" : "") + ", e.g. " + example +
          (depth_example.empty()
               ? std::string()
               : "; or, for parts meant to touch, read their overlap as contact with " +
                     depth_example) +
          ")");
}

// Parts of a STEP model that overlap: an interference, measured on the exact
// solids (the file read again for the common volume of each pair), listed
// with the ways on: --fastened joins them, --touching makes them touch.
// Returns (for OverlapFault) when no pair shares a volume of the exact
// solids: the tessellations alone cross, which --tolerance or
// --mesh-tolerance answers.
void StepInterference(const std::string& file, const ModelArgs& args, const AssemblyDef& def,
                      const OverlapError& e) {
  StepReadOptions options = StepOptions(args);
  for (const PartOverlap& o : e.overlaps())
    options.common_volumes_of.emplace_back(def.parts[o.earlier].name, def.parts[o.later].name);
  const StepModel measured = ReadStepAssembly(file, options);
  std::string pairs, fastened, touching;
  size_t interfering = 0;
  for (size_t k = 0; k < e.overlaps().size(); ++k) {
    const PartOverlap& o = e.overlaps()[k];
    const std::string &a = def.parts[o.earlier].name, &b = def.parts[o.later].name;
    const double volume = measured.common_volumes[k];
    // A common volume below the allowance's cube is the exact solids
    // touching, not sharing material.
    const double tol = std::max(def.overlap_allowance, def.tolerance);
    pairs += std::string(pairs.empty() ? "" : "; ") + "'" + EscapedName(a) + "' and '" +
             EscapedName(b) + "': " +
             (volume > tol * tol * tol ? FormatNumber(volume) + " m^3 in common (exact solids)"
                                       : "no common volume in the exact solids (the "
                                         "tessellations cross)") +
             ", e.g. at " + FormatPoint(o.witness, 3) + ", " + FormatNumber(o.depth) + " m deep";
    if (volume > tol * tol * tol) {
      ++interfering;
      fastened += (fastened.empty() ? "" : ",") + a + ":" + b;
      touching += (touching.empty() ? "" : ",") + a + ":" + b;
    }
  }
  if (interfering == 0) return;
  throw InputError(file, e.json_path(),
                   std::to_string(interfering) + " pair" + (interfering == 1 ? "" : "s") +
                       " of parts interfere" +
                       (interfering < e.overlaps().size()
                            ? " (of " + std::to_string(e.overlaps().size()) + " that overlap)"
                            : std::string()) +
                       ": " + pairs + ". A bolt or a press fit held fast: --fastened " + fastened +
                       " joins each pair into one rigid part; parts that only touch in the "
                       "design: --touching " +
                       touching + " cuts the second of each pair where they overlap");
}

// One note per pair of parts read as touching where they overlap (within
// the overlap depth), with its depth.
void NoteTouchingOverlaps(const Model& m, std::ostream& notes) {
  const Assembly& a = m.assembly;
  for (const PartOverlap& o : a.touching_overlaps())
    notes << "cairn: note: " << m.file << ": parts '" << EscapedName(a.part(o.earlier).name)
          << "' and '" << EscapedName(a.part(o.later).name) << "' overlap " << FormatNumber(o.depth)
          << " deep (deepest at " << FormatPoint(o.witness, 3)
          << "): read as touching on the overlap's mid-surface (overlap depth "
          << FormatNumber(a.overlap_depth()) << ")\n";
}

// Assembly::Create (`create`) with what the model layer knows added to its
// faults: a mass or density the sidecar set is the sidecar's fault, at its
// JSON path; parts that overlap by more than the tolerance say that
// --tolerance raises it.
Assembly CreateAssembly(const std::function<Assembly()>& create, const AssemblyDef& def,
                        const ModelArgs& args, const std::map<std::string, std::string>& set_by,
                        const std::string& file = "") {
  try {
    return create();
  } catch (const OverlapError& e) {
    if (args.format == "step") StepInterference(file, args, def, e);
    OverlapFault(e, args, def);
  } catch (const InputError& e) {
    for (size_t k = 0; k < def.parts.size() && !set_by.empty(); ++k) {
      const std::string part = NamedPath("parts[" + std::to_string(k) + "]", def.parts[k].name);
      const auto it = set_by.find(def.parts[k].name);
      if (it != set_by.end() &&
          (e.json_path() == part + ".mass" || e.json_path() == part + ".density"))
        throw InputError(args.sidecar, it->second, e.message());
    }
    throw;
  }
}

}  // namespace

Model LoadModel(const std::string& file, const ModelArgs& args, std::ostream* notes) {
  CheckModelFlags(args);
  if (args.format == "compas") {
    RequireCompasFriction(args);
    return LoadCompasModel(ReadCompasAssembly(file, args.max_input_size), file, args);
  }
  if (args.interfaces == "stored")
    throw InputError("", "--interfaces",
                     "stored is for --format compas (a scene file gives its interfaces in "
                     "`interfaces`)");
  Model m;
  std::map<std::string, std::string> set_by;
  try {
    m.def = args.format == "step" || args.format == "asap"
                ? ReadCadDef(file, args, notes, set_by)
                : ReadSceneDef(file, args.max_input_size);
  } catch (const InputError& e) {
    // A COMPAS file read as a scene misses the version key first: say what
    // to do instead of only what is wrong.
    if (e.json_path() != "cairn" || e.message().find("required key is missing") != 0) throw;
    throw InputError(e.file(), e.json_path(),
                     e.message() + "; if this is a COMPAS assembly, give --format compas");
  }
  if (notes)
    for (const std::string& note : m.def.notes)
      *notes << "cairn: note: " << file << ": " << note << "\n";
  if (args.friction) m.def.friction = *args.friction;
  if (args.tolerance) m.def.tolerance = *args.tolerance;
  ApplyModelFlags(args, file, m.def);
  m.assembly =
      CreateAssembly([&] { return Assembly::Create(m.def, file); }, m.def, args, set_by, file);
  m.file = file;
  if (notes) NoteTouchingOverlaps(m, *notes);
  return m;
}

Model LoadCompasModel(const CompasAssembly& parsed, const std::string& file,
                      const ModelArgs& args) {
  CheckModelFlags(args);
  RequireCompasFriction(args);
  CompasOptions options;
  options.friction = *args.friction;
  options.tolerance = args.tolerance.value_or(0.0);
  options.stored_interfaces = args.interfaces == "stored";
  CompasModel compas = CompasToModel(parsed, options, file);
  // The sidecar: densities, masses, fixed blocks the file does not carry
  // (the CRA bridge's weights, density 3.51).
  if (!args.sidecar.empty()) {
    CheckInputFile(args.sidecar, args.max_input_size);
    ApplySidecar(args.sidecar, compas.def, args.max_input_size);
  }
  ApplyModelFlags(args, file, compas.def);
  Model m;
  m.def = compas.def;
  m.assembly =
      CreateAssembly([&] { return CreateCompasAssembly(compas, file); }, compas.def, args, {});
  m.file = file;
  return m;
}

int ResolvePart(const Assembly& assembly, const std::string& name, const std::string& flag,
                const std::string& file) {
  if (name.empty()) throw InputError("", flag, "a part name is empty");
  const int i = assembly.FindPart(name);
  if (i < 0) throw InputError("", flag, "no part named '" + EscapedName(name) + "' in " + file);
  return i;
}

std::optional<int> ResolveNormalize(const Assembly& assembly, const std::string& name,
                                    const std::string& file) {
  if (name.empty()) return std::nullopt;
  const int i = ResolvePart(assembly, name, "--normalize", file);
  if (!(assembly.part(i).mass * assembly.gravity().norm() > 0))
    throw InputError("", "--normalize",
                     "part '" + EscapedName(name) + "' has no weight (" +
                         (assembly.gravity().norm() > 0 ? "no mass" : "the scene has no gravity") +
                         "): forces cannot be given in units of it");
  return i;
}

Configuration WithoutParts(const Assembly& assembly, const std::vector<std::string>& names,
                           const std::string& file, std::vector<int>& taken) {
  Configuration config = Configuration::Assembled(assembly);
  for (const std::string& name : names) {
    const int i = ResolvePart(assembly, name, "--without", file);
    config.present[i] = false;
    taken.push_back(i);
  }
  // A scene of fixed parts alone is stable (nothing can move); taking away
  // every movable one leaves nothing to ask about.
  bool movable = false, had_movable = false;
  for (int i = 0; i < assembly.num_parts(); ++i) {
    had_movable = had_movable || !assembly.part(i).fixed;
    movable = movable || (config.present[i] && !assembly.part(i).fixed);
  }
  if (had_movable && !movable)
    throw InputError("", "--without", "takes away every movable part: nothing is left to check");
  return config;
}

void RefuseGivenInterfaces(const Assembly& assembly, const std::string& file,
                           const std::string& consequence) {
  if (assembly.has_interfaces())
    throw InputError(
        file, "interfaces",
        "the contacts are given as interfaces of the assembled configuration: " + consequence);
}

}  // namespace cairn::app
