#include "cairn/app/blocking.h"

#include <optional>

#include "cairn/core/error.h"
#include "cairn/core/format.h"
#include "cairn/core/unit_vector.h"
#include "cairn/planning/blocking.h"
#include "cairn/report/blocking_report.h"
#include "cairn/report/html_report.h"

namespace cairn::app {

Vector3 BlockingDirection(const std::vector<double>& xyz, const Assembly& assembly,
                          const std::string& option) {
  const size_t dim = static_cast<size_t>(assembly.dimension());
  const bool planar_xyz = dim == 2 && xyz.size() == 3 && xyz[2] == 0;
  if (xyz.size() != dim && !planar_xyz)
    throw InputError("", option,
                     std::string(dim == 2 ? "a 2-D scene takes a direction of 2 numbers X,Y (or "
                                            "X,Y,0)"
                                          : "a 3-D scene takes a direction of 3 numbers X,Y,Z") +
                         ", not " +
                         (xyz.size() == 3 ? std::string("3 with Z = ") + FormatNumber(xyz[2])
                                          : std::to_string(xyz.size())));
  const Vector3 d(xyz[0], xyz[1], dim == 3 ? xyz[2] : 0.0);
  if (!d.allFinite()) throw InputError("", option, "must have finite components");
  const std::optional<Vector3> unit = UnitVector(d);
  if (!unit) throw InputError("", option, "must not be the zero vector");
  return *unit;
}

CommandResult BlockingDocument(const Model& model, const BlockingQuery& query,
                               const Monitor& monitor) {
  const Assembly& assembly = model.assembly;
  ReportOptions report;
  report.scene_file = model.file;
  // Parts taken away first, by name, as `cairn check --without` does.
  const Configuration config = WithoutParts(assembly, query.without, model.file, report.without);
  const std::function<void()>& checkpoint = monitor.checkpoint;
  // One direction (the classic ±x, ±y, ±z questions), or every cell.
  const Ndbg ndbg =
      query.direction.empty()
          ? ComputeNdbg(assembly, config, checkpoint)
          : ComputeBlockingAt(assembly, config,
                              BlockingDirection(query.direction, assembly, query.direction_option),
                              checkpoint);
  CommandResult out;
  out.document = NdbgToJson(assembly, ndbg, report);
  out.text = NdbgToText(assembly, ndbg, report);
  if (query.page)
    out.page = BlockingPage(assembly, out.document, NdbgHeadline(assembly, ndbg, report), report);
  return out;
}

}  // namespace cairn::app
