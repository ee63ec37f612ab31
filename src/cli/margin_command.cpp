#include "cli/margin_command.h"

#include <ostream>
#include <stdexcept>
#include <string>
#include <utility>

#include "cairn/core/error.h"
#include "cli/command.h"
#include "cli/output_files.h"

namespace cairn::cli {

namespace {

// --friction [MU]: the margin asked for, and/or the model's μ.
std::pair<app::ModelArgs, app::MarginQuery> Resolve(const MarginArgs& args) {
  app::ModelArgs model = args.model;
  app::MarginQuery query = args.query;
  query.without = args.without;
  query.rule = RuleOf(args.rule);
  query.page = !args.html.empty();
  if (args.friction_given && !args.friction_value.empty()) {
    double mu = 0;
    size_t used = 0;
    try {
      mu = std::stod(args.friction_value, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != args.friction_value.size())
      throw InputError("", "--friction",
                       "takes a number, or nothing to ask for the friction margin (got \"" +
                           args.friction_value + "\")");
    model.friction = mu;
  }
  // A COMPAS file stores no friction: its μ comes from --friction MU, also
  // when another margin is asked for.
  if (args.friction_given && args.friction_value.empty() && model.format == "compas" &&
      !model.friction)
    throw InputError("", "--friction",
                     "needs a value with --format compas: the blocks' friction coefficient "
                     "(e.g. --friction 0.6; alone, --friction MU also asks for the friction "
                     "margin)");
  // Without a value --friction asks for the friction margin (and
  // ResolveMarginQuery refuses it beside --tilt or --load).
  if (args.friction_given &&
      (args.friction_value.empty() || (query.tilt.empty() && query.load.empty())))
    query.friction = true;
  return {model, query};
}

}  // namespace

CommandDocument MarginDocument(const MarginArgs& args, const Checkpoint& checkpoint) {
  const auto [model, query] = Resolve(args);
  const app::CommandResult r =
      app::MarginDocument(LoadModel(args.scene, model), query, {checkpoint, {}});
  if (r.exit == kExitInternalError) throw std::runtime_error(r.failure);
  return {r.document, r.exit};
}

int RunMargin(const MarginArgs& args, std::ostream& out, std::ostream& err) {
  return RunGuarded(err, [&]() -> int {
    const auto [model, query] = Resolve(args);
    // The output is checked first (never over the input), written last.
    const std::vector<NamedFile> inputs = ModelInputs(args.scene, model, "the model file");
    CheckOutputs({{args.html, "--html"}}, inputs);
    const app::CommandResult r = app::MarginDocument(LoadModel(args.scene, model, &err), query);
    OutputFiles files(inputs);
    if (!args.html.empty()) files.Add(args.html, r.page, "--html");
    files.Commit();
    out << (args.json ? r.document.dump(2) + "\n" : r.text);
    if (r.exit == kExitInternalError) err << "cairn: internal error: " << r.failure << '\n';
    return r.exit;
  });
}

}  // namespace cairn::cli
