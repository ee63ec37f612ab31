#include "cairn/app/margin.h"

#include <cmath>

#include "cairn/core/error.h"
#include "cairn/core/unit_vector.h"
#include "cairn/report/html_report.h"
#include "cairn/report/margin_report.h"

namespace cairn::app {

namespace {

// A point or vector of `dim` numbers (3-D; 2-D: x, y, or x, y, 0).
Vector3 ReadVector(const std::vector<double>& v, int dim, const std::string& flag,
                   const std::string& file) {
  const bool ok = static_cast<int>(v.size()) == dim || (dim == 2 && v.size() == 3 && v[2] == 0);
  if (!ok)
    throw InputError(file, flag,
                     "takes " + std::to_string(dim) + " comma-separated numbers (got " +
                         std::to_string(v.size()) + ")");
  for (double x : v)
    if (!std::isfinite(x)) throw InputError(file, flag, "must be finite numbers");
  return {v[0], v[1], v.size() == 3 ? v[2] : 0.0};
}

}  // namespace

MarginRequest ResolveMarginQuery(const Assembly& assembly, const MarginQuery& q,
                                 const std::string& file) {
  // The flags are read here; what they ask is checked by the stability stage
  // (CheckMarginRequest), the one place its messages are written.
  const int asked = (q.friction ? 1 : 0) + (q.tilt.empty() ? 0 : 1) + (q.load.empty() ? 0 : 1);
  if (asked != 1)
    throw InputError(file, "margin",
                     asked == 0 ? "say which margin: --friction, --tilt X,Y,Z or --load PART"
                                : "one margin at a time: --friction, --tilt or --load");
  MarginRequest req;
  if (q.friction) {
    req.quantity = MarginQuantity::kFriction;
  } else if (!q.tilt.empty()) {
    req.quantity = MarginQuantity::kTilt;
    if (q.tilt.size() != 3)
      throw InputError(file, "--tilt",
                       "takes an axis of 3 comma-separated numbers (2-D scenes: 0,0,1)");
    req.axis = ReadVector(q.tilt, 3, "--tilt", file);
  } else {
    req.quantity = MarginQuantity::kLoad;
    req.part = ResolvePart(assembly, q.load, "--load", file);
    const int dim = assembly.dimension();
    if (q.point.empty()) throw InputError(file, "--point", "is required with --load");
    if (q.direction.empty()) throw InputError(file, "--direction", "is required with --load");
    req.point = ReadVector(q.point, dim, "--point", file);
    req.direction = ReadVector(q.direction, dim, "--direction", file);
  }
  req.rule = q.rule;
  CheckMarginRequest(assembly, req, file);
  if (req.quantity == MarginQuantity::kTilt) req.axis = *UnitVector(req.axis);
  if (req.quantity == MarginQuantity::kLoad) req.direction = *UnitVector(req.direction);
  return req;
}

CommandResult MarginDocument(const Model& model, const MarginQuery& query, const Monitor& monitor) {
  const Assembly& assembly = model.assembly;
  ReportOptions report;
  report.scene_file = model.file;
  const Configuration config = WithoutParts(assembly, query.without, model.file, report.without);
  const MarginRequest request = ResolveMarginQuery(assembly, query, model.file);
  monitor.Poll();
  const MarginResult result = ComputeMargin(model.def, assembly, config, request);
  CommandResult out;
  out.document = MarginToJson(assembly, request, result, report);
  out.text = MarginToText(assembly, request, result, report);
  if (query.page) out.page = MarginPage(assembly, out.document, out.text, report);
  if (!result.solved) {
    out.exit = kExitInternalError;
    out.failure = result.message;
  } else {
    out.exit = result.stands_at_nominal ? kExitStable : kExitUnstable;
  }
  return out;
}

}  // namespace cairn::app
