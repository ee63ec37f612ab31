
#include "cli/convert_command.h"

#include <ostream>

#include "cairn/core/format.h"
#include "cairn/io/scene_writer.h"
#include "cli/command.h"
#include "cli/output_files.h"

namespace cairn::cli {

int RunConvert(const ConvertArgs& args, std::ostream& out, std::ostream& err) {
  return RunGuarded(err, [&]() -> int {
    // The model is validated (Assembly::Create) before anything is written,
    // so a scene that convert writes is one `cairn check` reads.
    const Model m = LoadModel(args.input, args.model, &err);
    const std::string text = WriteSceneJson(m.def);
    // Whole or not at all, never over the input (OutputFiles).
    OutputFiles files(ModelInputs(args.input, args.model, "the input file"));
    files.Add(args.output, text, "the output file");
    files.Commit();
    int fixed = 0;
    for (const Part& p : m.assembly.parts()) fixed += p.fixed ? 1 : 0;
    out << "cairn: wrote " << args.output << ": " << m.assembly.num_parts() << " parts (" << fixed
        << " fixed), " << m.assembly.dimension() << "-D, friction " << FormatNumber(m.def.friction)
        << '\n';
    return kExitStable;
  });
}

}  // namespace cairn::cli
