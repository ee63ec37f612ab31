// The compiled half of the Python module `cairn` (docs/python.md): the
// commands as functions of a loaded model, each calling the very function
// the CLI calls (include/cairn/app/) and returning its JSON document (as
// text) and, when asked, its page and files. The Python half
// (python/cairn/__init__.py) converts arguments, parses the document, adds
// the numpy columns and writes the files; nothing here decides anything.
//
// Threads: every solve runs with the GIL released (a Model is immutable, an
// Assembly may be analysed from many threads); arguments are converted before
// and results after, with the GIL held.

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>  // IWYU pragma: keep

#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "cairn/app/blocking.h"
#include "cairn/app/check.h"
#include "cairn/app/margin.h"
#include "cairn/app/model.h"
#include "cairn/app/plan.h"
#include "cairn/app/sequence.h"
#include "cairn/app/simulate.h"
#include "cairn/core/error.h"
#include "cairn/geometry/plan.h"
#include "cairn/io/compas_reader.h"

namespace py = pybind11;

namespace cairn::python {
namespace {

// A loaded model: app's Model (definition, validated Assembly, the file it
// came from). Immutable once made, so one model may be checked from many
// threads at once.
using PyModel = app::Model;
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

// The model options of every command (docs/cli.md, "Reading the model"),
// as the Python half passes them (a dict of the keywords).
app::ModelArgs ModelArgsOf(const std::string& format, const py::dict& o) {
  app::ModelArgs args;
  args.format = format;
  args.friction = o["friction"].cast<std::optional<double>>();
  args.supports = o["supports"].cast<std::vector<std::string>>();
  args.gravity = o["gravity"].cast<std::vector<double>>();
  args.tolerance = o["tolerance"].cast<std::optional<double>>();
  if (o.contains("overlap_depth"))
    args.overlap_depth = o["overlap_depth"].cast<std::optional<double>>();
  args.interfaces = o["interfaces"].cast<std::string>();
  args.mesh_tolerance = o["mesh_tolerance"].cast<std::optional<double>>();
  args.sidecar = o["sidecar"].cast<std::string>();
  if (o.contains("fastened")) args.fastened = o["fastened"].cast<std::vector<std::string>>();
  if (o.contains("touching")) args.touching = o["touching"].cast<std::vector<std::string>>();
  args.max_input_size = o["max_input_size"].cast<std::uint64_t>();
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

ModelPtr Load(const std::string& file, const std::string& format, const py::dict& options) {
  const app::ModelArgs args = ModelArgsOf(format, options);
  py::gil_scoped_release release;
  return std::make_shared<PyModel>(app::LoadModel(file, args));
}

ModelPtr FromCompas(const std::string& text, const std::string& name, const py::dict& options) {
  const app::ModelArgs args = ModelArgsOf("compas", options);
  py::gil_scoped_release release;
  const CompasAssembly parsed = ParseCompasAssembly(ParseText(text, name), name);
  return std::make_shared<PyModel>(app::LoadCompasModel(parsed, name, args));
}

// A command's answer for the Python half: the document (as text), the exit
// code, the page ("" unless asked for) and the files.
using Answer = std::tuple<std::string, int, std::string, std::string, std::string,
                          std::vector<std::pair<std::string, std::string>>>;
Answer AnswerOf(app::CommandResult&& r) {
  if (r.exit == app::kExitInternalError) throw std::runtime_error(r.failure);
  return {r.document.dump(2),    r.exit,           std::move(r.page),
          std::move(r.timeline), std::move(r.dot), std::move(r.plans)};
}

// The CLI's --rule, by name.
VerdictRule RuleOf(const std::string& rule) {
  if (rule == "equilibrium") return VerdictRule::kEquilibrium;
  if (rule != "loaded-from-rest")
    throw InputError("", "rule",
                     "must be \"loaded-from-rest\" or \"equilibrium\", not \"" + rule + "\"");
  return VerdictRule::kLoadedFromRest;
}

// `cairn check --json`.
Answer Check(const py::object& model, const std::vector<std::string>& without,
             const std::string& normalize, bool page, const std::string& rule) {
  const PyModel& m = ModelOf(model);
  app::CheckQuery q;
  q.rule = RuleOf(rule);
  py::gil_scoped_release release;
  q.without = without;
  q.normalize = normalize;
  q.page = page;
  return AnswerOf(app::CheckDocument(m, q));
}

// `cairn simulate --json`, the `--timeline` CSV of the same run, and the page.
Answer Simulate(const py::object& model, const std::string& plan_file, const std::string& plan_text,
                bool continue_after_failure, const std::string& normalize, bool suggest_fixtures,
                int max_fixels, long long max_ticks, const std::string& margin, bool page) {
  const PyModel& m = ModelOf(model);
  py::gil_scoped_release release;
  app::SimulateQuery q;
  // A plan file, or a plan given as a dict (named "plan" in messages).
  q.plan_file = plan_file;
  if (!plan_text.empty()) q.plan_data = ParseText(plan_text, plan_file);
  q.normalize = normalize;
  q.continue_after_failure = continue_after_failure;
  q.suggest_fixtures = suggest_fixtures;
  q.max_fixels = max_fixels;
  q.max_ticks = max_ticks;
  q.margin = margin;
  q.timeline = true;
  q.page = page;
  return AnswerOf(app::SimulateDocument(m, q));
}

// `cairn plan --json`, with its page, graph and plans when asked.
Answer PlanSequences(const py::object& model, const py::dict& o) {
  const PyModel& m = ModelOf(model);
  app::PlanQuery q;
  q.max = o["max"].cast<int>();
  q.threads = o["threads"].cast<int>();
  q.paths = o["paths"].cast<std::string>();
  q.keep = o["keep"].cast<std::vector<std::string>>();
  q.support = o["support"].cast<std::string>();
  q.single_parts = o["single_parts"].cast<bool>();
  q.dt = o["dt"].cast<double>();
  q.speed = o["speed"].cast<double>();
  q.allow_fixtures = o["allow_fixtures"].cast<int>();
  q.directions = o["directions"].cast<std::string>();
  q.dot = o["dot"].cast<bool>();
  q.emit_plans = o["emit_plans"].cast<bool>();
  q.page = o["page"].cast<bool>();
  py::gil_scoped_release release;
  return AnswerOf(app::PlanDocument(m, q));
}

// `cairn sequence --json`: a build order with the fewest holds.
Answer Sequence(const py::object& model, const py::dict& o) {
  const PyModel& m = ModelOf(model);
  app::SequenceQuery q;
  q.temporary = o["temporary"].cast<std::string>();
  q.max_temporary = o["max_temporary"].cast<int>();
  q.direction = o["direction"].cast<std::vector<double>>();
  q.directions = o["directions"].cast<std::string>();
  q.beam_width = o["beam"].cast<int>();
  q.threads = o["threads"].cast<int>();
  q.time_limit = o["time_limit"].cast<double>();
  q.rule = RuleOf(o["rule"].cast<std::string>());
  const std::string require = o["require"].cast<std::string>();
  if (!require.empty() && require != "strong")
    throw InputError("", "require", "must be \"strong\" or None, not \"" + require + "\"");
  q.require_strong = require == "strong";
  q.emit_plans = o["emit_plans"].cast<bool>();
  q.page = o["page"].cast<bool>();
  py::gil_scoped_release release;
  return AnswerOf(app::SequenceDocument(m, q));
}

// `cairn blocking --json` (with a direction, `--direction`).
Answer Blocking(const py::object& model, const std::vector<std::string>& without,
                const std::vector<double>& direction, bool page) {
  const PyModel& m = ModelOf(model);
  py::gil_scoped_release release;
  return AnswerOf(app::BlockingDocument(m, {without, direction, "direction", page}));
}

// `cairn margin --json`: friction (a flag), tilt (an axis) or load (a part,
// a point, a direction), as the CLI's --friction, --tilt, --load.
Answer Margin(const py::object& model, bool friction, const std::vector<double>& tilt,
              const std::string& load, const std::vector<double>& point,
              const std::vector<double>& direction, const std::vector<std::string>& without,
              const std::string& rule, bool page) {
  const PyModel& m = ModelOf(model);
  const app::MarginQuery q{friction, tilt, load, point, direction, without, RuleOf(rule), page};
  py::gil_scoped_release release;
  return AnswerOf(app::MarginDocument(m, q));
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
             const cairn::Assembly& a = s.assembly;
             return "<cairn.Model " + cairn::JsonQuoted(s.def.name) + " (" +
                    std::to_string(a.dimension()) + "-D, " + std::to_string(a.num_parts()) +
                    " parts) from " + cairn::JsonQuoted(s.file) + ">";
           })
      .def_property_readonly("file", [](const py::object& self) { return ModelOf(self).file; })
      .def_property_readonly("name", [](const py::object& self) { return ModelOf(self).def.name; })
      .def_property_readonly(
          "dimension", [](const py::object& self) { return ModelOf(self).assembly.dimension(); })
      .def_property_readonly("parts",
                             [](const py::object& self) {
                               std::vector<std::string> names;
                               const cairn::Assembly& a = ModelOf(self).assembly;
                               for (int i = 0; i < a.num_parts(); ++i)
                                 names.push_back(a.part(i).name);
                               return names;
                             })
      .def_property_readonly("fixed",
                             [](const py::object& self) {
                               std::vector<std::string> names;
                               const cairn::Assembly& a = ModelOf(self).assembly;
                               for (int i = 0; i < a.num_parts(); ++i)
                                 if (a.part(i).fixed) names.push_back(a.part(i).name);
                               return names;
                             })
      // The pairs read as touching where they overlap (within the overlap
      // depth): {"parts": [a, b], "depth": d, "point": deepest}.
      .def_property_readonly(
          "overlaps",
          [](const py::object& self) {
            const cairn::Assembly& a = ModelOf(self).assembly;
            py::list out;
            for (const cairn::PartOverlap& o : a.touching_overlaps()) {
              py::dict d;
              d["parts"] = py::make_tuple(a.part(o.earlier).name, a.part(o.later).name);
              d["depth"] = o.depth;
              d["point"] = py::make_tuple(o.witness.x(), o.witness.y(), o.witness.z());
              out.append(d);
            }
            return out;
          })
      .def_property_readonly(
          "has_interfaces",
          [](const py::object& self) { return ModelOf(self).assembly.has_interfaces(); })
      // Each part's vertices in the assembled pose, `dimension` numbers each
      // (2-D: the polygon in order), for drawing (cairn.plot.scene).
      .def_property_readonly("vertices", [](const py::object& self) {
        const cairn::Assembly& a = ModelOf(self).assembly;
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
  m.attr("DEFAULT_MAX_INPUT_SIZE") = cairn::kDefaultMaxInputSize;
  m.def("load", &Load, py::arg("file"), py::arg("format"), py::arg("options"));
  m.def("from_compas", &FromCompas, py::arg("text"), py::arg("name"), py::arg("options"));
  m.def("check", &Check, py::arg("model"), py::arg("without"), py::arg("normalize"),
        py::arg("page"), py::arg("rule") = "loaded-from-rest");
  m.def("simulate", &Simulate, py::arg("model"), py::arg("plan_file"), py::arg("plan_text"),
        py::arg("continue_after_failure"), py::arg("normalize"), py::arg("suggest_fixtures"),
        py::arg("max_fixels"), py::arg("max_ticks"), py::arg("margin"), py::arg("page"));
  m.def("plan", &PlanSequences, py::arg("model"), py::arg("options"));
  m.def("sequence", &Sequence, py::arg("model"), py::arg("options"));
  m.def("blocking", &Blocking, py::arg("model"), py::arg("without"), py::arg("direction"),
        py::arg("page") = false);
  m.def("margin", &Margin, py::arg("model"), py::arg("friction"), py::arg("tilt"), py::arg("load"),
        py::arg("point"), py::arg("direction"), py::arg("without"),
        py::arg("rule") = "loaded-from-rest", py::arg("page") = false);
}
