#include "hoilcd/bench/report/gate.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/safe_text.h"

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
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += safe[i];
    }
  }
  return out;
}

}  // namespace

DropAllowance DropAllowance::Parse(const std::string& text, const std::string& where) {
  DropAllowance allowed;
  if (text == "ci") {
    allowed.interval = true;
    return allowed;
  }
  const char* begin = text.c_str();
  char* end = nullptr;
  allowed.max_drop = std::strtod(begin, &end);
  if (end == begin || *end != '\0' || !(allowed.max_drop >= 0 && allowed.max_drop <= 1)) {
    throw InputError(where, "a number in [0, 1] or 'ci' (the run's 95 % interval), got '" + SafeText(text) + "'");
  }
  return allowed;
}

std::string DropAllowance::ToString() const {
  return interval ? "beyond the run's 95 % interval" : "by more than " + Number(max_drop);
}

std::string Regression::ToString(const DropAllowance& allowed) const {
  const std::string why =
      allowed.interval && !std::isnan(new_high)
          ? "old above the new run's 95 % interval [" + Number(new_low) + ", " + Number(new_high) + "]"
          : "dropped " + allowed.ToString();
  return "regression: method " + method + ", " + metric + " old " + Number(old_value) + " new " + Number(new_value) +
         " (" + why + ")";
}

std::vector<Regression> CompareToBaseline(const nlohmann::json& baseline, const nlohmann::json& current,
                                          const DropAllowance& allowed) {
  std::vector<Regression> out;
  for (const auto& [name, old_method] : baseline["methods"].items()) {
    if (!current["methods"].contains(name)) continue;
    const nlohmann::json& new_method = current["methods"][name];
    for (const char* metric : kHeadlineMetrics) {
      const double old_value = Value(old_method, metric), new_value = Value(new_method, metric);
      if (std::isnan(old_value)) continue;
      Regression r{name, metric, old_value, new_value};
      bool regressed = std::isnan(new_value);
      if (!regressed && allowed.interval) {
        r.new_low = r.new_high = new_value;  // no interval: one of zero width
        const nlohmann::json* ends = nullptr;
        if (const auto it = new_method.find("intervals"); it != new_method.end() && it->is_object()) {
          if (const auto e = it->find(metric); e != it->end() && e->is_array() && e->size() == 2) ends = &*e;
        }
        if (ends != nullptr && (*ends)[0].is_number() && (*ends)[1].is_number()) {
          r.new_low = (*ends)[0].get<double>();
          r.new_high = (*ends)[1].get<double>();
        }
        regressed = old_value > r.new_high;
      } else if (!regressed) {
        regressed = old_value - new_value > allowed.max_drop;
      }
      if (regressed) out.push_back(r);
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

std::string JUnitXml(const nlohmann::json& report, const std::vector<Regression>& regressions,
                     const DropAllowance& allowed) {
  std::ostringstream cases;
  int failures = 0, tests = 0;
  for (const auto& [name, method] : report["methods"].items()) {
    ++tests;
    cases << "  <testcase classname=\"hoilcd.loop_closure\" name=\"" << XmlText(name) << "\">\n";
    std::string lines;  // one regression a line, each line made safe on its own
    for (const Regression& r : regressions)
      if (r.method == name) lines += XmlText(r.ToString(allowed)) + "\n";
    if (!lines.empty()) {
      ++failures;
      cases << "    <failure message=\"headline metric dropped\">" << lines << "</failure>\n";
    }
    cases << "    <system-out>mrr " << Number(Value(method, "mrr")) << ", recall_at_1 "
          << Number(Value(method, "recall_at_1")) << "</system-out>\n  </testcase>\n";
  }
  std::ostringstream xml;
  xml << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuite name=\"hoilcd\" tests=\"" << tests << "\" failures=\""
      << failures << "\" errors=\"0\">\n"
      << cases.str() << "</testsuite>\n";
  return xml.str();
}

}  // namespace hoilcd
