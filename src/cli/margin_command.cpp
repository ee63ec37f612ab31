#include "cli/margin_command.h"

#include <cmath>
#include <optional>
#include <ostream>

#include "cairn/core/error.h"
#include "cairn/core/format.h"
#include "cairn/core/tolerances.h"
#include "cairn/core/unit_vector.h"
#include "cairn/report/margin_report.h"
#include "cli/command.h"

namespace cairn::cli {

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
    const std::optional<Vector3> axis = UnitVector(ReadVector(q.tilt, 3, "--tilt", file));
    if (!axis) throw InputError(file, "--tilt", "the axis must not be zero");
    req.axis = *axis;
    if (!assembly.is_3d() && (req.axis.x() != 0 || req.axis.y() != 0))
      throw InputError(file, "--tilt",
                       "a 2-D scene turns in its plane: the axis must be 0,0,1 or 0,0,-1");
  } else {
    req.quantity = MarginQuantity::kLoad;
    req.part = ResolvePart(assembly, q.load, "--load", file);
    const int dim = assembly.dimension();
    if (q.point.empty()) throw InputError(file, "--point", "is required with --load");
    if (q.direction.empty()) throw InputError(file, "--direction", "is required with --load");
    req.point = ReadVector(q.point, dim, "--point", file);
    if (req.point.cwiseAbs().maxCoeff() > limits::kMaxCoordinate)
      throw InputError(file, "--point",
                       "must be within the scene's coordinate range, |x| <= " +
                           FormatNumber(limits::kMaxCoordinate));
    const std::optional<Vector3> direction =
        UnitVector(ReadVector(q.direction, dim, "--direction", file));
    if (!direction) throw InputError(file, "--direction", "must not be the zero vector");
    req.direction = *direction;
    if (assembly.part(req.part).fixed)
      throw InputError(file, "--load",
                       "part \"" + q.load + "\" is fixed: a load on it goes to the ground");
  }
  return req;
}

int RunMargin(const MarginArgs& args, std::ostream& out, std::ostream& err) {
  return RunGuarded(err, [&]() -> int {
    // --friction [MU]: the margin asked for, and/or the model's μ.
    ModelArgs model = args.model;
    MarginQuery query = args.query;
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
    const Model m = LoadModel(args.scene, model);
    const Assembly& assembly = m.assembly;
    ReportOptions report;
    report.scene_file = args.scene;
    const Configuration config = WithoutParts(assembly, args.without, args.scene, report.without);
    const MarginRequest request = ResolveMarginQuery(assembly, query, args.scene);
    const MarginResult result = ComputeMargin(m.def, assembly, config, request);
    if (args.json)
      out << MarginToJson(assembly, request, result, report).dump(2) << '\n';
    else
      out << MarginToText(assembly, request, result, report);
    if (!result.solved) {
      err << "cairn: internal error: " << result.message << '\n';
      return kExitInternalError;
    }
    return result.holds_at_nominal ? kExitStable : kExitUnstable;
  });
}

}  // namespace cairn::cli
