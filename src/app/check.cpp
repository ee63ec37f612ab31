#include "cairn/app/check.h"

#include "cairn/report/check_report.h"
#include "cairn/report/html_report.h"
#include "cairn/report/words.h"
#include "cairn/stability/analyze.h"

namespace cairn::app {

CommandResult CheckDocument(const Model& model, const CheckQuery& query, const Monitor& monitor) {
  const Assembly& assembly = model.assembly;
  ReportOptions report;
  report.scene_file = model.file;
  report.normalize_part = ResolveNormalize(assembly, query.normalize, model.file);
  report.contacts = query.contacts;
  const Configuration config = WithoutParts(assembly, query.without, model.file, report.without);
  monitor.Poll();
  StabilityOptions analysis;
  analysis.check_equilibrium = true;  // report jamming (weak stability) too
  analysis.rule = query.rule;
  const StabilityResult result = AnalyzeConfiguration(assembly, config, analysis);
  CommandResult out;
  out.document = StabilityToJson(assembly, config, result, report);
  out.exit = !result.stable()                                                      ? kExitUnstable
             : query.require_strong && result.stability != StabilityProof::kStrong ? kExitNotStrong
                                                                                   : kExitStable;
  out.text = StabilityToText(assembly, config, result, report);
  if (query.page)
    out.page = CheckPage(assembly, out.document, CheckStory(assembly, result), report);
  return out;
}

}  // namespace cairn::app
