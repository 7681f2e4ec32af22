#include "hoilcd/bench/report/gate.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "hoilcd/bench/evaluation/safe_text.h"

namespace hoilcd {
namespace {

double Value(const nlohmann::json& method, const char* metric) {
  const auto it = method.find(metric);
  return it != method.end() && it->is_number() ? it->get<double>() : NAN;
}

std::string Number(double v) {
  if (std::isnan(v)) return "none";
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.4f", v);
  return buf;
}

// Text for an XML 1.0 attribute or element: through SafeText (valid UTF-8; control characters,
// which XML 1.0 forbids even as character references, and stray bytes shown as \xNN), then the
// two noncharacters XML 1.0 also forbids (U+FFFE, U+FFFF) shown the same way, markup escaped.
std::string XmlText(const std::string& s) {
  const std::string safe = SafeText(s);
  std::string out;
  for (size_t i = 0; i < safe.size(); ++i) {
    if (safe.compare(i, 3, "\xef\xbf\xbe") == 0 || safe.compare(i, 3, "\xef\xbf\xbf") == 0) {
      out += safe[i + 2] == '\xbe' ? "\\xef\\xbf\\xbe" : "\\xef\\xbf\\xbf";
      i += 2;
      continue;
    }
    switch (safe[i]) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += safe[i];
    }
  }
  return out;
}

}  // namespace

std::string Regression::ToString(double max_drop) const {
  return "regression: method " + method + ", " + metric + " old " + Number(old_value) + " new " + Number(new_value) +
         " (dropped by more than " + Number(max_drop) + ")";
}

std::vector<Regression> CompareToBaseline(const nlohmann::json& baseline, const nlohmann::json& current,
                                          double max_drop) {
  std::vector<Regression> out;
  for (const auto& [name, old_method] : baseline["methods"].items()) {
    if (!current["methods"].contains(name)) continue;
    const nlohmann::json& new_method = current["methods"][name];
    for (const char* metric : kHeadlineMetrics) {
      const double old_value = Value(old_method, metric), new_value = Value(new_method, metric);
      if (std::isnan(old_value)) continue;
      if (std::isnan(new_value) || old_value - new_value > max_drop) out.push_back({name, metric, old_value, new_value});
    }
  }
  return out;
}

std::vector<std::string> MethodsOnlyInBaseline(const nlohmann::json& baseline, const nlohmann::json& current) {
  std::vector<std::string> out;
  for (const auto& [name, method] : baseline["methods"].items())
    if (!current["methods"].contains(name)) out.push_back(name);
  return out;
}

std::string JUnitXml(const nlohmann::json& report, const std::vector<Regression>& regressions, double max_drop) {
  std::ostringstream cases;
  int failures = 0, tests = 0;
  for (const auto& [name, method] : report["methods"].items()) {
    ++tests;
    cases << "  <testcase classname=\"hoilcd.loop_closure\" name=\"" << XmlText(name) << "\">\n";
    std::string lines;  // one regression a line, each line made safe on its own
    for (const Regression& r : regressions)
      if (r.method == name) lines += XmlText(r.ToString(max_drop)) + "\n";
    if (!lines.empty()) {
      ++failures;
      cases << "    <failure message=\"headline metric dropped\">" << lines << "</failure>\n";
    }
    cases << "    <system-out>mrr " << Number(Value(method, "mrr")) << ", recall_at_1 "
          << Number(Value(method, "recall_at_1")) << "</system-out>\n  </testcase>\n";
  }
  std::ostringstream xml;
  xml << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuite name=\"hoilcd\" tests=\"" << tests
      << "\" failures=\"" << failures << "\" errors=\"0\">\n" << cases.str() << "</testsuite>\n";
  return xml.str();
}

}  // namespace hoilcd
