// The one way user-given text (a method name, a path, bytes quoted from a file in a message)
// goes into JSON, XML, Markdown and terminal messages: JSON takes only valid UTF-8, XML and
// terminals no control characters, and a C string ends at its first NUL.
#pragma once

#include <string>
#include <string_view>

namespace hoilcd {

// `text` with every byte that is not part of a valid UTF-8 character, and every control character
// (U+0000 to U+001F, U+007F, U+0080 to U+009F), written as \xNN per byte: Latin-1 "café" becomes
// "caf\xe9", a NUL "\x00". Printable valid UTF-8 comes out unchanged, so applying it twice
// changes nothing more.
std::string SafeText(std::string_view text);

}  // namespace hoilcd
