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

int RunBlocking(const BlockingArgs& args, std::ostream& out, std::ostream& err) {
  return RunGuarded(err, [&]() -> int {
    const Assembly assembly = LoadModel(args.scene, args.model).assembly;
    ReportOptions report;
    report.scene_file = args.scene;
    // Parts taken away first, by name, as `cairn check --without` does.
    const Configuration config = WithoutParts(assembly, args.without, args.scene, report.without);
    const Ndbg ndbg = ComputeNdbg(assembly, config);
    if (args.json)
      out << NdbgToJson(assembly, ndbg, report).dump(2) << '\n';
    else
      out << NdbgToText(assembly, ndbg, report);
    return kExitStable;
  });
}

}  // namespace cairn::cli
