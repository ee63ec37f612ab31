#include "cairn/io/paths_reader.h"

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cairn/core/error.h"
#include "cairn/io/plan_reader.h"

namespace cairn {

using nlohmann::json;

std::map<int, std::vector<CandidatePath>> ReadCandidatePaths(const std::string& file,
                                                             const Assembly& assembly) {
  std::ifstream in(file);
  if (!in) throw InputError(file, "", "cannot read the file");
  json doc;
  try {
    doc = json::parse(in);
  } catch (const json::parse_error& e) {
    throw InputError(file, "", std::string("not valid JSON: ") + e.what());
  }
  if (!doc.is_object())
    throw InputError(file, "", "must be a JSON object from part name to a list of paths");
  std::map<int, std::vector<CandidatePath>> out;
  for (auto it = doc.begin(); it != doc.end(); ++it) {
    const std::string& name = it.key();
    const int part = assembly.FindPart(name);
    if (part < 0) throw InputError(file, name, "no part named '" + name + "' in the scene");
    if (assembly.part(part).fixed)
      throw InputError(file, name, "part '" + name + "' is fixed: it is never removed");
    if (!it.value().is_array() || it.value().empty())
      throw InputError(file, name, "must be a non-empty list of paths");
    for (size_t k = 0; k < it.value().size(); ++k) {
      const std::string where = name + "[" + std::to_string(k) + "]";
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
        std::string path = e.json_path();
        const std::string prefix = "steps[0]";
        if (path.rfind(prefix, 0) == 0) path = where + path.substr(prefix.size());
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
