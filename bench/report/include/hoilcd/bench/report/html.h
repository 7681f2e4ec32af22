// The pieces every report.html is built from: text escaped for HTML, bytes as base64 data URIs
// (so a page needs no other file and no network), sortable tables, and the page shell with its one
// inline style sheet and small vanilla script (sorting on a header click, the gallery's filters).
#pragma once

#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "hoilcd/bench/evaluation/bootstrap.h"

namespace hoilcd {

// `text` made safe (SafeText: valid UTF-8, no control characters) with & < > " ' escaped, for
// element text and attribute values alike.
std::string EscapeHtml(std::string_view text);

// RFC 4648 base64 of `bytes`, with padding and no line breaks.
std::string Base64(std::string_view bytes);

// "data:<mime>;base64,<Base64(bytes)>".
std::string DataUri(const std::string& mime, std::string_view bytes);

// One cell of a sortable table: its HTML and the key a click sorts it by (NaN: sorted by its text,
// after every number).
struct HtmlCell {
  std::string html;  // escaped already
  double sort_key = NAN;
};
HtmlCell TextCell(const std::string& text);         // escaped; sorted by its text
HtmlCell NumberCell(double value, int digits = 3);  // Fixed(value, digits); sorted by value
// "0.123 [0.100, 0.150]", sorted by the value.
HtmlCell IntervalCell(double value, const Interval& interval);

// <table class="sortable"> with a header row (each header sorts its column on a click, again to
// reverse) and the rows, in the given order.
std::string SortableTable(const std::vector<std::string>& headers, const std::vector<std::vector<HtmlCell>>& rows);

// A whole page: doctype, UTF-8, the title (escaped), the style sheet and script, then `body`
// (HTML). Nothing is loaded from elsewhere.
std::string HtmlPage(const std::string& title, const std::string& body);

}  // namespace hoilcd
