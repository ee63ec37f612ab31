// `cairn blocking`: the NDBG of a scene (planning/blocking.h) and, per cell,
// the parts that can be taken out along its directions.
#include "cli/blocking_command.h"

#include <optional>
#include <ostream>

#include "cairn/core/error.h"
#include "cairn/core/format.h"
#include "cairn/core/unit_vector.h"
#include "cairn/planning/blocking.h"
#include "cairn/report/blocking_report.h"
#include "cli/command.h"
#include "cli/model.h"

namespace cairn::cli {

namespace {

// --direction: X,Y (or X,Y,0) in a 2-D scene, X,Y,Z in a 3-D one; finite, not
// all zero. As margin's --direction and --point take them.
Vector3 DirectionFlag(const std::vector<double>& xyz, const Assembly& assembly) {
  const size_t dim = static_cast<size_t>(assembly.dimension());
  const bool planar_xyz = dim == 2 && xyz.size() == 3 && xyz[2] == 0;
  if (xyz.size() != dim && !planar_xyz)
    throw InputError("", "--direction",
                     std::string(dim == 2 ? "a 2-D scene takes a direction of 2 numbers X,Y (or "
                                            "X,Y,0)"
                                          : "a 3-D scene takes a direction of 3 numbers X,Y,Z") +
                         ", not " +
                         (xyz.size() == 3 ? std::string("3 with Z = ") + FormatNumber(xyz[2])
                                          : std::to_string(xyz.size())));
  const Vector3 d(xyz[0], xyz[1], dim == 3 ? xyz[2] : 0.0);
  if (!d.allFinite()) throw InputError("", "--direction", "must have finite components");
  const std::optional<Vector3> unit = UnitVector(d);
  if (!unit) throw InputError("", "--direction", "must not be the zero vector");
  return *unit;
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
