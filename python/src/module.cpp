// The compiled half of the Python module `cairn` (docs/python.md): the
// commands of the CLI as functions of a loaded model, each returning the very
// JSON document (as text) that `cairn <command> --json` prints, built by the
// same report functions. The Python half (python/cairn/__init__.py) parses it
// and adds the numpy columns; nothing here decides anything the CLI does not.
//
// Threads: every solve runs with the GIL released (a Model is immutable, an
// Assembly may be analysed from many threads); arguments are converted before
// and results after, with the GIL held.

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cairn/core/error.h"
#include "cairn/io/compas_reader.h"
#include "cairn/io/paths_reader.h"
#include "cairn/io/plan_reader.h"
#include "cairn/motion/simulate.h"
#include "cairn/planning/blocking.h"
#include "cairn/planning/fixtures.h"
#include "cairn/planning/planner.h"
#include "cairn/report/blocking_report.h"
#include "cairn/report/check_report.h"
#include "cairn/report/fixture_report.h"
#include "cairn/report/margin_report.h"
#include "cairn/report/plan_report.h"
#include "cairn/report/simulation_report.h"
#include "cairn/stability/analyze.h"
#include "cli/blocking_command.h"
#include "cli/margin_command.h"
#include "cli/model.h"

namespace py = pybind11;

namespace cairn::python {
namespace {

// A loaded model: the CLI's Model (definition and validated Assembly) and the
// name of the file it came from (the reports' `scene_file`). Immutable once
// made, so one model may be checked from many threads at once.
struct PyModel {
  cli::Model model;
  std::string file;
};
using ModelPtr = std::shared_ptr<PyModel>;

// What a cairn.Model that no loader made says: `cairn.Model.__new__` without
// a loader leaves the object without a model (pybind11 would otherwise hand
// out its unconstructed memory).
constexpr const char* kNoModel =
    "this cairn.Model holds no model: make models with cairn.load(file) or "
    "cairn.from_compas(data), not cairn.Model.__new__";

// The model of a Python object given as a cairn.Model: a TypeError (never a
// crash) when it is something else, or a Model that no loader filled.
const PyModel& ModelOf(const py::handle& obj) {
  if (!py::isinstance<PyModel>(obj))
    throw py::type_error(
        std::string("expected a cairn.Model (cairn.load, cairn.from_compas), not ") +
        std::string(py::str(py::type::handle_of(obj).attr("__name__"))));
  // A holder that was never constructed does not cast (pybind11 checks it):
  // no value is read.
  ModelPtr p;
  try {
    p = obj.cast<ModelPtr>();
  } catch (const py::cast_error&) {
  }
  if (!p) throw py::type_error(kNoModel);
  return *p;  // owned by `obj`, which the caller holds
}

// The model options of every command (docs/cli.md, "Reading the model").
cli::ModelArgs MakeModelArgs(const std::string& format, std::optional<double> friction,
                             const std::vector<std::string>& supports,
                             const std::vector<double>& gravity, std::optional<double> tolerance,
                             const std::string& interfaces) {
  cli::ModelArgs args;
  args.format = format;
  args.friction = friction;
  args.supports = supports;
  args.gravity = gravity;
  args.tolerance = tolerance;
  args.interfaces = interfaces;
  return args;
}

// Parses a JSON document given as text by the Python half (a dict it dumped).
// @throws InputError naming `file` when the text is not JSON.
nlohmann::json ParseText(const std::string& text, const std::string& file) {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(file, "", std::string("not a JSON document: ") + e.what());
  }
}

ModelPtr Load(const std::string& file, const std::string& format, std::optional<double> friction,
              const std::vector<std::string>& supports, const std::vector<double>& gravity,
              std::optional<double> tolerance, const std::string& interfaces) {
  const cli::ModelArgs args =
      MakeModelArgs(format, friction, supports, gravity, tolerance, interfaces);
  py::gil_scoped_release release;
  return std::make_shared<PyModel>(PyModel{cli::LoadModel(file, args), file});
}

ModelPtr FromCompas(const std::string& text, const std::string& name,
                    std::optional<double> friction, const std::vector<std::string>& supports,
                    const std::vector<double>& gravity, std::optional<double> tolerance,
                    const std::string& interfaces) {
  const cli::ModelArgs args =
      MakeModelArgs("compas", friction, supports, gravity, tolerance, interfaces);
  py::gil_scoped_release release;
  const CompasAssembly parsed = ParseCompasAssembly(ParseText(text, name), name);
  return std::make_shared<PyModel>(PyModel{cli::LoadCompasModel(parsed, name, args), name});
}

// `cairn check --json`.
std::string Check(const py::object& model, const std::vector<std::string>& without,
                  const std::string& normalize) {
  const PyModel& m = ModelOf(model);
  py::gil_scoped_release release;
  const Assembly& assembly = m.model.assembly;
  ReportOptions report;
  report.scene_file = m.file;
  report.normalize_part = cli::ResolveNormalize(assembly, normalize, m.file);
  const Configuration config = cli::WithoutParts(assembly, without, m.file, report.without);
  StabilityOptions analysis;
  analysis.check_equilibrium = true;  // as the CLI: report jamming too
  const StabilityResult result = AnalyzeConfiguration(assembly, config, analysis);
  return StabilityToJson(assembly, config, result, report).dump(2);
}

// `cairn simulate --json` and the `--timeline` CSV of the same run.
std::pair<std::string, std::string> Simulate(const py::object& model, const std::string& plan_file,
                                             const std::string& plan_text,
                                             bool continue_after_failure,
                                             const std::string& normalize, bool suggest_fixtures,
                                             int max_fixels, long long max_ticks) {
  const PyModel& m = ModelOf(model);
  py::gil_scoped_release release;
  const Assembly& assembly = m.model.assembly;
  cli::RefuseGivenInterfaces(assembly, m.file,
                             "parts cannot be moved along a plan (check it, with without= for "
                             "subassemblies, or let Cairn find the contacts from the shapes)");
  // A plan file, or a plan given as a dict (named "plan" in messages).
  const Plan plan = plan_text.empty() ? ReadPlan(plan_file, assembly, max_ticks)
                                      : Plan::Create(ParsePlanJson(ParseText(plan_text, plan_file),
                                                                   plan_file, assembly.dimension()),
                                                     assembly, plan_file, max_ticks);
  ReportOptions report;
  report.scene_file = m.file;
  report.normalize_part = cli::ResolveNormalize(assembly, normalize, m.file);
  SimulationOptions options;
  options.continue_after_failure = continue_after_failure;
  options.record_timeline = true;
  const SimulationResult result = SimulatePlan(assembly, plan, options);
  nlohmann::json doc = SimulationToJson(assembly, plan, result, report);
  if (suggest_fixtures) {
    FixtureSearchOptions search;
    search.max_fixels = max_fixels;
    // null: asked for, but the plan is stable without fixels (as the CLI).
    doc["fixtures"] =
        result.stable()
            ? nlohmann::json(nullptr)
            : FixtureSuggestionToJson(assembly,
                                      SuggestFixtures(m.model.def, assembly, plan, result, search),
                                      search, report);
  }
  return {doc.dump(2), TimelineToCsv(assembly, result, report)};
}

// `cairn plan --json`.
std::string PlanSequences(const py::object& model, int max, bool single_parts,
                          const std::string& paths, int allow_fixtures,
                          const std::vector<std::string>& keep, const std::string& support,
                          int threads) {
  const PyModel& m = ModelOf(model);
  py::gil_scoped_release release;
  const Assembly& assembly = m.model.assembly;
  cli::RefuseGivenInterfaces(assembly, m.file,
                             "parts cannot be moved, so no removal can be planned");
  PlannerOptions options;
  options.max_sequences = max;
  options.threads = threads;
  options.subassemblies = !single_parts;
  options.allow_fixtures = allow_fixtures;
  if (support != "full" && support != "none" && support != "both")
    throw InputError("", "support",
                     "must be \"full\", \"none\" or \"both\", not \"" + support + "\"");
  options.support = support == "none"   ? SupportChoice::kNone
                    : support == "both" ? SupportChoice::kBoth
                                        : SupportChoice::kFull;
  for (const std::string& name : keep)
    options.keep.push_back(cli::ResolvePart(assembly, name, "keep", m.file));
  if (!paths.empty()) options.given_paths = ReadCandidatePaths(paths, assembly);
  const PlannerResult result = PlanDisassembly(m.model.def, assembly, options);
  return PlannerToJson(assembly, result, m.file).dump(2);
}

// `cairn blocking --json`.
std::string Blocking(const py::object& model, const std::vector<std::string>& without,
                     const std::vector<double>& direction) {
  const PyModel& m = ModelOf(model);
  py::gil_scoped_release release;
  const Assembly& assembly = m.model.assembly;
  ReportOptions report;
  report.scene_file = m.file;
  const Configuration config = cli::WithoutParts(assembly, without, m.file, report.without);
  // With a direction, `cairn blocking --direction`: its resolver (which
  // names the option "direction" here) and the one cell at it.
  if (direction.empty()) return NdbgToJson(assembly, ComputeNdbg(assembly, config), report).dump(2);
  const Vector3 d = cli::BlockingDirection(direction, assembly, "direction");
  return NdbgToJson(assembly, ComputeBlockingAt(assembly, config, d), report).dump(2);
}

// `cairn margin --json`: friction (a flag), tilt (an axis) or load (a part,
// a point, a direction), as the CLI's --friction, --tilt, --load.
std::string Margin(const py::object& model, bool friction, const std::vector<double>& tilt,
                   const std::string& load, const std::vector<double>& point,
                   const std::vector<double>& direction, const std::vector<std::string>& without) {
  const PyModel& m = ModelOf(model);
  py::gil_scoped_release release;
  const Assembly& assembly = m.model.assembly;
  ReportOptions report;
  report.scene_file = m.file;
  const Configuration config = cli::WithoutParts(assembly, without, m.file, report.without);
  const cli::MarginQuery query{friction, tilt, load, point, direction};
  const MarginRequest request = cli::ResolveMarginQuery(assembly, query, m.file);
  const MarginResult result = ComputeMargin(m.model.def, assembly, config, request);
  return MarginToJson(assembly, request, result, report).dump(2);
}

}  // namespace
}  // namespace cairn::python

PYBIND11_MODULE(_cairn, m) {
  using namespace cairn::python;  // NOLINT(google-build-using-namespace)
  m.doc() = "Cairn's compiled core: the CLI's commands as functions (use the package `cairn`).";

  // cairn.InputError: a ValueError whose str() is the CLI's message, with the
  // parts of it as attributes `file`, `json_path` and `message`.
  static py::handle input_error =
      py::exception<cairn::InputError>(m, "InputError", PyExc_ValueError).release();
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const cairn::InputError& e) {
      py::object error = py::reinterpret_borrow<py::object>(input_error)(e.what());
      error.attr("file") = e.file();
      error.attr("json_path") = e.json_path();
      error.attr("message") = e.message();
      PyErr_SetObject(input_error.ptr(), error.ptr());
    }
  });

  // Models come from cairn.load and cairn.from_compas only: no __init__, and
  // a __new__ that refuses (instances made by C++ do not call it). Every
  // attribute and function reads the model through ModelOf all the same.
  py::class_<PyModel, std::shared_ptr<PyModel>> model(m, "Model");
  model.attr("__new__") = py::staticmethod(py::cpp_function(
      [](const py::args&, const py::kwargs&) -> py::object { throw py::type_error(kNoModel); },
      py::name("__new__")));
  model
      .def("__repr__",
           [](const py::object& self) {
             const PyModel& s = ModelOf(self);
             const cairn::Assembly& a = s.model.assembly;
             return "<cairn.Model " + cairn::JsonQuoted(s.model.def.name) + " (" +
                    std::to_string(a.dimension()) + "-D, " + std::to_string(a.num_parts()) +
                    " parts) from " + cairn::JsonQuoted(s.file) + ">";
           })
      .def_property_readonly("file", [](const py::object& self) { return ModelOf(self).file; })
      .def_property_readonly("name",
                             [](const py::object& self) { return ModelOf(self).model.def.name; })
      .def_property_readonly(
          "dimension",
          [](const py::object& self) { return ModelOf(self).model.assembly.dimension(); })
      .def_property_readonly("parts",
                             [](const py::object& self) {
                               std::vector<std::string> names;
                               const cairn::Assembly& a = ModelOf(self).model.assembly;
                               for (int i = 0; i < a.num_parts(); ++i)
                                 names.push_back(a.part(i).name);
                               return names;
                             })
      .def_property_readonly("fixed",
                             [](const py::object& self) {
                               std::vector<std::string> names;
                               const cairn::Assembly& a = ModelOf(self).model.assembly;
                               for (int i = 0; i < a.num_parts(); ++i)
                                 if (a.part(i).fixed) names.push_back(a.part(i).name);
                               return names;
                             })
      .def_property_readonly(
          "has_interfaces",
          [](const py::object& self) { return ModelOf(self).model.assembly.has_interfaces(); })
      // Each part's vertices in the assembled pose, `dimension` numbers each
      // (2-D: the polygon in order), for drawing (cairn.plot.scene).
      .def_property_readonly("vertices", [](const py::object& self) {
        const cairn::Assembly& a = ModelOf(self).model.assembly;
        const cairn::Configuration config = cairn::Configuration::Assembled(a);
        std::vector<std::vector<std::vector<double>>> parts;
        for (int i = 0; i < a.num_parts(); ++i) {
          std::vector<std::vector<double>> points;
          for (const cairn::Vector3& p : config.WorldVertices(a, i)) {
            points.push_back({p.x(), p.y()});
            if (a.is_3d()) points.back().push_back(p.z());
          }
          parts.push_back(std::move(points));
        }
        return parts;
      });

  m.attr("DEFAULT_MAX_TICKS") = cairn::Plan::kDefaultMaxTicks;
  m.def("load", &Load, py::arg("file"), py::arg("format"), py::arg("friction"), py::arg("supports"),
        py::arg("gravity"), py::arg("tolerance"), py::arg("interfaces"));
  m.def("from_compas", &FromCompas, py::arg("text"), py::arg("name"), py::arg("friction"),
        py::arg("supports"), py::arg("gravity"), py::arg("tolerance"), py::arg("interfaces"));
  m.def("check", &Check, py::arg("model"), py::arg("without"), py::arg("normalize"));
  m.def("simulate", &Simulate, py::arg("model"), py::arg("plan_file"), py::arg("plan_text"),
        py::arg("continue_after_failure"), py::arg("normalize"), py::arg("suggest_fixtures"),
        py::arg("max_fixels"), py::arg("max_ticks"));
  m.def("plan", &PlanSequences, py::arg("model"), py::arg("max"), py::arg("single_parts"),
        py::arg("paths"), py::arg("allow_fixtures"), py::arg("keep"), py::arg("support"),
        py::arg("threads"));
  m.def("blocking", &Blocking, py::arg("model"), py::arg("without"), py::arg("direction"));
  m.def("margin", &Margin, py::arg("model"), py::arg("friction"), py::arg("tilt"), py::arg("load"),
        py::arg("point"), py::arg("direction"), py::arg("without"));
}
