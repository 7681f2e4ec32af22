#include "hoilcd/bench/report/online_report.h"

#include "hoilcd/bench/report/html_report.h"
#include "hoilcd/bench/report/output_folder.h"
#include "hoilcd/bench/report/report.h"
#include "hoilcd/core/util/file_io.h"
#include "hoilcd/core/util/folder_lock.h"
#include "hoilcd/core/util/safe_text.h"

namespace hoilcd {

void WriteOnlineReport(const OnlineResult& result, const Dataset& dataset, const std::string& dir) {
  CheckReportFolder(dir);
  nlohmann::json report = OnlineResultToJson(result);
  report["hoilcd_version"] = HOILCD_VERSION;
  report["dataset"] = {{"dir", SafeText(dataset.dir())},
                       {"scene_hash", dataset.manifest().scene_hash},
                       {"seed", dataset.manifest().seed},
                       {"frames", dataset.num_frames()}};
  const FolderLock lock(dir, FolderLock::IfBusy::kWait);  // one writer at a time: never a mix of two reports
  WriteFileAtomic(dir + "/report.json", report.dump(2) + "\n");
  WriteFileAtomic(dir + "/report.md", OnlineResultToMarkdown(result));
  WriteFileAtomic(dir + "/report.html", OnlineReportHtml(result, dataset));
}

}  // namespace hoilcd
