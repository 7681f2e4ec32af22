// What hoilcd export-mcap and render --outputs ...,mcap share: the summary they print.
#pragma once

#include "hoilcd/bench/export/mcap_export.h"

namespace hoilcd {

// "wrote FILE: N frames, M messages, S MB in T s (R frames/s)", then each topic's message count.
void PrintMcapExport(const McapExportResult& result);

}  // namespace hoilcd
