#include "hoilcd/bench/report/html.h"

#include "hoilcd/core/util/safe_text.h"
#include "hoilcd/core/util/text.h"

namespace hoilcd {
namespace {

// The page's one style sheet: readable tables, the gallery's tiles in rows that wrap.
const char* const kStyle = R"css(
body { font: 14px/1.45 system-ui, sans-serif; margin: 1.5em auto; max-width: 1400px; padding: 0 1em; color: #222; }
h1 { font-size: 1.6em; } h2 { border-bottom: 1px solid #ccc; margin-top: 2em; } h3 { margin-top: 1.5em; }
table { border-collapse: collapse; margin: .8em 0; }
th, td { border: 1px solid #ccc; padding: 3px 8px; text-align: right; }
th:first-child, td:first-child { text-align: left; }
table.sortable th { cursor: pointer; background: #f2f2f2; user-select: none; }
table.sortable th[aria-sort=ascending]::after { content: " \25B2"; }
table.sortable th[aria-sort=descending]::after { content: " \25BC"; }
tr:nth-child(even) td { background: #fafafa; }
.note { color: #555; } .figure img { max-width: 100%; border: 1px solid #ddd; }
.filters { position: sticky; top: 0; background: #fff; padding: .5em 0; border-bottom: 1px solid #ddd; z-index: 1; }
.filters label { margin-right: 1.2em; }
.entry { border: 1px solid #ccc; border-radius: 4px; margin: 1em 0; padding: .5em .8em; }
.entry h4 { margin: .2em 0; } .entry .conditions { color: #555; font-size: 12px; margin: .2em 0 .5em; }
.tiles { display: flex; flex-wrap: wrap; gap: 8px; }
.tile { margin: 0; width: 190px; } .tile.pair { width: 384px; }
.wide { overflow-x: auto; } details summary { cursor: pointer; }
.tile svg { width: 100%; display: block; background: #000; }
.tile figcaption { font-size: 12px; } .hit { color: #176d17; } .miss { color: #b01010; }
.legend span { margin-right: 1.2em; } .hidden { display: none; }
)css";

// The page's one script: sort a table on a header click; filter the gallery by its selects.
const char* const kScript = R"js(
(function () {
  function key(cell) {
    var k = cell.getAttribute('data-sort');
    return k === null ? null : parseFloat(k);
  }
  function compare(a, b) {
    var ka = key(a), kb = key(b);
    if (ka !== null && kb !== null) return ka - kb;
    if (ka !== null) return -1;
    if (kb !== null) return 1;
    return a.textContent.localeCompare(b.textContent);
  }
  document.querySelectorAll('table.sortable').forEach(function (table) {
    table.querySelectorAll('th').forEach(function (th, column) {
      th.addEventListener('click', function () {
        var descending = th.getAttribute('aria-sort') === 'ascending';
        table.querySelectorAll('th').forEach(function (h) { h.removeAttribute('aria-sort'); });
        th.setAttribute('aria-sort', descending ? 'descending' : 'ascending');
        var body = table.tBodies[0];
        var rows = Array.prototype.slice.call(body.rows);
        rows.sort(function (r, s) {
          var c = compare(r.cells[column], s.cells[column]);
          return descending ? -c : c;
        });
        rows.forEach(function (r) { body.appendChild(r); });
      });
    });
  });
  var method = document.getElementById('gallery-method');
  if (!method) return;
  var stratum = document.getElementById('gallery-stratum');
  var outcome = document.getElementById('gallery-outcome');
  var shown = document.getElementById('gallery-shown');
  var entries = document.querySelectorAll('#gallery .entry');
  function filter() {
    var m = method.value, s = stratum.value, o = outcome.value, count = 0;
    entries.forEach(function (e) {
      var outcomes = e.getAttribute('data-outcomes').split('|');
      var strata = e.getAttribute('data-strata').split('|');
      var ok = s === '*' || strata.indexOf(s) >= 0;
      if (o === 'blank') ok = ok && e.getAttribute('data-blank') === '1';
      else if (o !== '*') ok = ok && outcomes.some(function (t) { return m === '*' ? t.endsWith(':' + o) : t === m + ':' + o; });
      e.classList.toggle('hidden', !ok);
      if (ok) count++;
      e.querySelectorAll('[data-method]').forEach(function (t) {
        t.classList.toggle('hidden', m !== '*' && t.getAttribute('data-method') !== m);
      });
    });
    shown.textContent = count + ' of ' + entries.length + ' entries shown';
  }
  [method, stratum, outcome].forEach(function (select) { select.addEventListener('change', filter); });
  filter();
})();
)js";

}  // namespace

std::string EscapeHtml(std::string_view text) {
  const std::string safe = SafeText(text);
  std::string out;
  out.reserve(safe.size());
  for (char c : safe) {
    switch (c) {
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
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// Hand-written: twenty lines, where a library (OpenSSL's EVP_EncodeBlock) would be a new dependency.
std::string Base64(std::string_view bytes) {
  static const char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const uint32_t v = (static_cast<uint8_t>(bytes[i]) << 16) | (static_cast<uint8_t>(bytes[i + 1]) << 8) |
                       static_cast<uint8_t>(bytes[i + 2]);
    for (int shift : {18, 12, 6, 0}) out += kAlphabet[(v >> shift) & 63];
  }
  if (i < bytes.size()) {
    const bool two = i + 1 < bytes.size();
    const uint32_t v = (static_cast<uint8_t>(bytes[i]) << 16) | (two ? static_cast<uint8_t>(bytes[i + 1]) << 8 : 0);
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += two ? kAlphabet[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

std::string DataUri(const std::string& mime, std::string_view bytes) {
  return "data:" + mime + ";base64," + Base64(bytes);
}

HtmlCell TextCell(const std::string& text) { return {EscapeHtml(text), NAN}; }

HtmlCell NumberCell(double value, int digits) { return {Fixed(value, digits), value}; }

HtmlCell IntervalCell(double value, const Interval& interval) {
  return {Fixed(value) + " <span class=\"note\">[" + Fixed(interval.low) + ", " + Fixed(interval.high) + "]</span>",
          value};
}

std::string SortableTable(const std::vector<std::string>& headers, const std::vector<std::vector<HtmlCell>>& rows) {
  std::string html = "<div class=\"wide\"><table class=\"sortable\"><thead><tr>";
  for (const std::string& h : headers) html += "<th>" + EscapeHtml(h) + "</th>";
  html += "</tr></thead><tbody>\n";
  for (const std::vector<HtmlCell>& row : rows) {
    html += "<tr>";
    for (const HtmlCell& cell : row) {
      html += std::isfinite(cell.sort_key) ? "<td data-sort=\"" + ShortestDouble(cell.sort_key) + "\">" : "<td>";
      html += cell.html + "</td>";
    }
    html += "</tr>\n";
  }
  return html + "</tbody></table></div>\n";
}

std::string HtmlPage(const std::string& title, const std::string& body) {
  return "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
         "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>" +
         EscapeHtml(title) + "</title>\n<style>" + kStyle + "</style>\n</head>\n<body>\n" + body + "<script>" +
         kScript + "</script>\n</body>\n</html>\n";
}

}  // namespace hoilcd
