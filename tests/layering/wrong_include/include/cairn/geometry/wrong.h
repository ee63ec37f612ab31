#pragma once
// A fixture of the layering test (tests/layering/): a geometry header that
// includes a later stage. The checker must reject it.
#include "cairn/core/types.h"
#include "cairn/report/report.h"
