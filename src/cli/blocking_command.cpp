// `cairn blocking`: the NDBG of a scene (planning/blocking.h) and, per cell,
// the parts that can be taken out along its directions.
#include "cli/blocking_command.h"

#include <ostream>

#include "cairn/core/error.h"
#include "cairn/planning/blocking.h"
#include "cairn/report/blocking_report.h"
#include "cli/command.h"
#include "cli/model.h"

namespace cairn::cli {

namespace {

struct Computed {
  Assembly assembly;
  ReportOptions report;
  Ndbg ndbg;
};

Computed Compute(const BlockingArgs& args) {
  Assembly assembly = LoadModel(args.scene, args.model).assembly;
  ReportOptions report;
  report.scene_file = args.scene;
  // Parts taken away first, by name, as `cairn check --without` does.
  const Configuration config = WithoutParts(assembly, args.without, args.scene, report.without);
  Ndbg ndbg = ComputeNdbg(assembly, config);
  return {std::move(assembly), std::move(report), std::move(ndbg)};
}

}  // namespace

CommandDocument BlockingDocument(const BlockingArgs& args) {
  const Computed c = Compute(args);
  return {NdbgToJson(c.assembly, c.ndbg, c.report), kExitStable};
}

int RunBlocking(const BlockingArgs& args, std::ostream& out, std::ostream& err) {
  return RunGuarded(err, [&]() -> int {
    if (args.json) {
      out << BlockingDocument(args).json.dump(2) << '\n';
      return kExitStable;
    }
    const Computed c = Compute(args);
    out << NdbgToText(c.assembly, c.ndbg, c.report);
    return kExitStable;
  });
}

}  // namespace cairn::cli
