#pragma once
// The reading process's work (cairn-step-reader): a STEP file's text into the
// model, through OpenCASCADE. Private to the io stage.

#include <string>

#include "cairn/io/step_reader.h"

namespace cairn {

/// The model of `text` (the file `path`'s contents, already checked by
/// CheckStepText) serialised by step_codec.h, or the InputError that reading
/// it raised. Never throws: OpenCASCADE's exceptions, a failed allocation
/// and anything else become an error naming the file.
std::string ReadInChild(const std::string& path, const std::string& text,
                        const StepReadOptions& options) noexcept;

}  // namespace cairn
