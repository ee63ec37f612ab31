#include "cairn/io/paths_reader.h"

#include <nlohmann/json.hpp>
#include <string>

#include "cairn/core/error.h"
#include "cairn/io/plan_reader.h"
#include "json_checks.h"

namespace cairn {

using nlohmann::json;

std::map<int, std::vector<CandidatePath>> ReadCandidatePaths(const std::string& file,
                                                             const Assembly& assembly,
                                                             std::uint64_t max_input_size) {
  const json doc = io_internal::ReadJsonFile(file, max_input_size);
  if (!doc.is_object())
    throw InputError(file, "", "must be a JSON object from part name to a list of paths");
  std::map<int, std::vector<CandidatePath>> out;
  for (auto it = doc.begin(); it != doc.end(); ++it) {
    // The key is the part's name: its path is the key (escaped), named when
    // the part exists, `B ("B")`, and `B ("B")[k]` its k-th path.
    const std::string& name = it.key();
    const std::string key = EscapedName(name);
    const int part = assembly.FindPart(name);
    if (part < 0) throw InputError(file, key, "no part named '" + key + "' in the scene");
    const std::string named = NamedPath(key, name);
    if (assembly.part(part).fixed)
      throw InputError(file, named, "part '" + key + "' is fixed: it is never removed");
    if (assembly.part(part).tool)
      throw InputError(file, named, "part '" + key + "' is a tool: it is never removed");
    if (!it.value().is_array() || it.value().empty())
      throw InputError(file, named, "must be a non-empty list of paths");
    for (size_t k = 0; k < it.value().size(); ++k) {
      const std::string where = named + "[" + std::to_string(k) + "]";
      json step = it.value()[k];
      std::string label = "given path " + std::to_string(k + 1);
      if (step.is_array()) {
        step = json{{"path", step}};
      } else if (step.is_object()) {
        if (step.contains("remove"))
          throw InputError(file, where + ".remove",
                           "a candidate path removes its part: give no `remove`");
        if (step.contains("label")) {
          if (!step["label"].is_string())
            throw InputError(file, where + ".label", "must be a string");
          label = step["label"].get<std::string>();
          step.erase("label");
        }
      } else {
        throw InputError(file, where,
                         "must be a list of points or an object with `path` or `direction`");
      }
      step["remove"] = json::array({name});
      const json plan_doc = {{"cairn_plan", 1}, {"steps", json::array({step})}};
      Plan plan;
      try {
        plan = Plan::Create(ParsePlanJson(plan_doc, file, assembly.dimension()), assembly, file);
      } catch (const InputError& e) {
        // The plan's path of the step, `steps[0] ("B")` (or bare `steps[0]`),
        // is this candidate's.
        std::string path = e.json_path();
        for (const std::string& prefix : {NamedPath("steps[0]", name), std::string("steps[0]")}) {
          if (path.rfind(prefix, 0) == 0) {
            path = where + path.substr(prefix.size());
            break;
          }
        }
        throw InputError(file, path, e.message());
      }
      const PlanStep& s = plan.steps[0];
      CandidatePath c;
      c.path = s.path;
      c.support = s.support;
      for (int g : s.grip)
        if (g != part) c.grip.push_back(g);
      c.label = label;
      out[part].push_back(c);
    }
  }
  return out;
}

}  // namespace cairn
