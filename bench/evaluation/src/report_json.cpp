#include "hoilcd/bench/evaluation/report_json.h"

#include <cstdint>

#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/file_io.h"
#include "hoilcd/core/util/json_reader.h"
#include "hoilcd/core/util/safe_text.h"

namespace hoilcd {
namespace {

constexpr uint64_t kMaxReportJsonBytes = uint64_t{64} << 20;  // a bench report of every method: ~1 MB

}  // namespace

nlohmann::json ReportJsonFromText(std::string_view text, const std::string& source) {
  nlohmann::json j;
  try {
    j = ParseJson(text, source);
  } catch (const JsonSyntaxError& e) {  // parse errors and number overflow (1e400)
    throw InputError(source, "is not JSON: expected a hoilcd report.json (" + SafeText(e.detail()) + ")");
  }
  if (!j.is_object() || !j.contains("methods") || !j["methods"].is_object()) {
    throw InputError(source, "/methods: expected an object of methods (a hoilcd report.json)");
  }
  for (const auto& [name, method] : j["methods"].items()) {
    const std::string where = source + ": /methods/" + SafeText(JsonPointerToken(name));
    if (!method.is_object()) throw InputError(where, "expected an object of the method's metrics");
    for (const char* metric : kHeadlineMetrics) {
      const auto it = method.find(metric);
      const bool valid = it != method.end() &&
                         (it->is_null() || (it->is_number() && it->get<double>() >= 0 && it->get<double>() <= 1));
      if (!valid) throw InputError(where + "/" + metric, "expected a number or null (a fraction, in [0, 1])");
    }
  }
  return j;
}

nlohmann::json ReadReportJson(const std::string& path) {
  RegularFile file(path);
  const auto too_long = [&](const std::string& size) {
    return InputError(path, "is " + size + " bytes: expected a hoilcd report.json, at most " +
                                std::to_string(kMaxReportJsonBytes >> 20) + " MiB");
  };
  if (file.size() > kMaxReportJsonBytes) throw too_long(std::to_string(file.size()));
  const std::string text = file.Read(kMaxReportJsonBytes + 1);
  if (text.size() > kMaxReportJsonBytes) throw too_long("more than " + std::to_string(kMaxReportJsonBytes));
  return ReportJsonFromText(text, path);
}

}  // namespace hoilcd
