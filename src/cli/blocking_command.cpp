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

// --direction: 3 finite numbers, not all zero (in 2-D, z = 0).
Vector3 DirectionFlag(const std::vector<double>& xyz, const Assembly& assembly) {
  if (xyz.size() != 3)
    throw InputError("", "--direction",
                     "must have 3 numbers X,Y,Z, not " + std::to_string(xyz.size()));
  const Vector3 d(xyz[0], xyz[1], xyz[2]);
  if (!d.allFinite()) throw InputError("", "--direction", "must have finite components");
  if (!assembly.is_3d() && d.z() != 0)
    throw InputError("", "--direction", "must have Z = 0 in a 2-D scene");
  if (!(d.norm() > 0)) throw InputError("", "--direction", "must not be the zero vector");
  return d;
}

struct Computed {
  Assembly assembly;
  ReportOptions report;
  Ndbg ndbg;
};

Computed Compute(const BlockingArgs& args, const Checkpoint& checkpoint,
                 std::ostream* notes = nullptr) {
  Assembly assembly = LoadModel(args.scene, args.model, notes).assembly;
  ReportOptions report;
  report.scene_file = args.scene;
  // Parts taken away first, by name, as `cairn check --without` does.
  const Configuration config = WithoutParts(assembly, args.without, args.scene, report.without);
  // One direction (the classic ±x, ±y, ±z questions), or every cell.
  Ndbg ndbg = args.direction.empty()
                  ? ComputeNdbg(assembly, config, checkpoint)
                  : ComputeBlockingAt(assembly, config, DirectionFlag(args.direction, assembly),
                                      checkpoint);
  return {std::move(assembly), std::move(report), std::move(ndbg)};
}

}  // namespace

Vector3 BlockingDirection(const std::vector<double>& xyz, const Assembly& assembly,
                          const std::string& option) {
  try {
    return DirectionFlag(xyz, assembly);
  } catch (const InputError& e) {
    if (option == "--direction") throw;
    throw InputError(e.file(), option, e.message());
  }
}

CommandDocument BlockingDocument(const BlockingArgs& args, const Checkpoint& checkpoint) {
  const Computed c = Compute(args, checkpoint);
  return {NdbgToJson(c.assembly, c.ndbg, c.report), kExitStable};
}

int RunBlocking(const BlockingArgs& args, std::ostream& out, std::ostream& err) {
  return RunGuarded(err, [&]() -> int {
    const Computed c = Compute(args, {}, &err);
    if (args.json)
      out << NdbgToJson(c.assembly, c.ndbg, c.report).dump(2) << '\n';
    else
      out << NdbgToText(c.assembly, c.ndbg, c.report);
    return kExitStable;
  });
}

}  // namespace cairn::cli
