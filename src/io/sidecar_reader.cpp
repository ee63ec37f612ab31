#include "cairn/io/sidecar_reader.h"

#include <algorithm>

#include "cairn/core/tolerances.h"
#include "io/json_checks.h"

namespace cairn {

namespace {

using io_internal::Child;
using io_internal::JsonChecker;
using nlohmann::json;

// A density or mass: positive and finite.
double Positive(const JsonChecker& check, const json& j, const std::string& path) {
  const double x = check.Number(j, path);
  if (!(x > 0)) check.Fail(path, "must be positive (got " + FormatNumber(x) + ")");
  return x;
}

}  // namespace

std::map<std::string, std::string> ApplySidecar(const std::string& path, AssemblyDef& def,
                                                std::uint64_t max_input_size) {
  std::map<std::string, std::string> set_by;
  const json doc = io_internal::ReadJsonFile(path, max_input_size);
  const JsonChecker check(path);
  check.Object(doc, "");
  check.CheckVersion(doc, "cairn_sidecar", "sidecar");
  check.CheckKeys(doc, "", {"cairn_sidecar", "friction", "density", "parts"});
  if (doc.contains("friction")) {
    const double mu = check.Number(doc["friction"], "friction");
    if (mu < 0 || mu > limits::kMaxFriction)
      check.Fail("friction", "must be in [0, " + FormatNumber(limits::kMaxFriction) + "] (got " +
                                 FormatNumber(mu) + ")");
    def.friction = mu;
  }
  if (doc.contains("density")) {
    const double rho = Positive(check, doc["density"], "density");
    for (PartDef& p : def.parts) {
      p.density = rho;
      set_by[p.name] = "density";
    }
  }
  if (!doc.contains("parts")) return set_by;
  const json& parts = check.Object(doc["parts"], "parts");
  for (const auto& item : parts.items()) {
    const std::string part_path = Child("parts", item.key());
    const auto it = std::find_if(def.parts.begin(), def.parts.end(),
                                 [&](const PartDef& p) { return p.name == item.key(); });
    if (it == def.parts.end()) check.Fail(part_path, "the model has no part of this name");
    const json& part = check.Object(item.value(), part_path);
    check.CheckKeys(part, part_path, {"fixed", "density", "mass"});
    if (part.contains("fixed")) it->fixed = check.Bool(part["fixed"], Child(part_path, "fixed"));
    if (part.contains("density")) {
      it->density = Positive(check, part["density"], Child(part_path, "density"));
      set_by[it->name] = Child(part_path, "density");
    }
    if (part.contains("mass")) {
      const std::string mass_path = Child(part_path, "mass");
      const double m = Positive(check, part["mass"], mass_path);
      if (m < limits::kMinMass || m > limits::kMaxMass)
        check.Fail(mass_path, "the part's mass " + FormatNumber(m) + " is out of range (" +
                                  FormatNumber(limits::kMinMass) + " to " +
                                  FormatNumber(limits::kMaxMass) + " mass units)");
      it->mass = m;
      set_by[it->name] = mass_path;
    }
  }
  return set_by;
}

}  // namespace cairn
