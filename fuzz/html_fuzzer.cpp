// Fuzz target: `cairn check --html` behind the scene reader, on small
// scenes: read → check → the JSON document → the page. The page must carry
// the document unharmed whatever the scene's names and numbers: its data
// block, cut out as a browser's HTML parser cuts it (up to the first
// "</script"), parses back to the same document, and the title holds no raw
// markup. Anything else is a finding, as is any exception but an InputError.
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>

#include "cairn/io/scene_reader.h"
#include "cairn/report/check_report.h"
#include "cairn/report/html_report.h"
#include "cairn/report/words.h"
#include "cairn/stability/analyze.h"
#include "fuzz_input.h"

namespace {

[[noreturn]] void Finding(const char* what) {
  std::fprintf(stderr, "html_fuzzer: %s\n", what);
  std::abort();
}

// The text between `open` and the first "</" + `tag` after it, as an HTML
// parser reads a raw-text element.
std::string RawElement(const std::string& page, const std::string& open, const std::string& tag) {
  const size_t begin = page.find(open);
  if (begin == std::string::npos) Finding("the page has no such element");
  const size_t from = begin + open.size();
  const size_t end = page.find("</" + tag, from);
  if (end == std::string::npos) Finding("an element is not closed");
  return page.substr(from, end - from);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return cairn::fuzz::Run("html_fuzzer", [&] {
    const std::string file = cairn::fuzz::AsFile(data, size, ".scene.json");
    const cairn::Assembly a = cairn::ReadScene(file);
    if (a.num_parts() > 12) return;
    int vertices = 0;
    for (int i = 0; i < a.num_parts(); ++i) vertices += static_cast<int>(a.part(i).vertices.size());
    if (vertices > 200) return;
    const cairn::Configuration config = cairn::Configuration::Assembled(a);
    cairn::StabilityOptions analysis;
    analysis.check_equilibrium = true;
    const cairn::StabilityResult r = cairn::AnalyzeConfiguration(a, config, analysis);
    cairn::ReportOptions options;
    options.scene_file = file;
    const nlohmann::json doc = cairn::StabilityToJson(a, config, r, options);
    const std::string page = cairn::CheckPage(a, doc, cairn::CheckStory(a, r), options);
    const std::string block =
        RawElement(page, "<script id=\"cairn-data\" type=\"application/json\">", "script");
    const nlohmann::json back = nlohmann::json::parse(block, nullptr, /*allow_exceptions=*/false);
    if (back.is_discarded()) Finding("the page's data block is not JSON");
    if (back.value("result", nlohmann::json()) != doc)
      Finding("the page's data block is not the check's document");
    const std::string title = RawElement(page, "<title>", "title");
    if (title.find('<') != std::string::npos) Finding("raw markup in the page's title");
  });
}
