#!/usr/bin/env bash
# Every link in the repository's Markdown files (README.md, CHANGELOG.md, */README.md and every
# .md file under docs/, at any depth) resolves to a file or folder inside the repository; web
# links (http, https, mailto) and in-page anchors are not checked. Usage: links_test.sh SOURCE_DIR
set -euo pipefail
root="$(cd "$1" && pwd -P)"
status=0
checked=0
while IFS= read -r md; do
  dir="$(dirname "$md")"
  # Targets of [text](target) and ![alt](target), one per line, with their line numbers.
  while IFS=: read -r line target; do
    target="${target%%#*}"          # drop an anchor
    target="${target%% *}"          # drop a title ("path "title"")
    case "$target" in ''|http://*|https://*|mailto:*) continue ;; esac
    checked=$((checked + 1))
    resolved="$(realpath -m "$dir/$target")"
    if [[ "$resolved" != "$root"/* ]]; then
      echo "${md#$root/}:$line: link '$target' leaves the repository"; status=1
    elif [[ ! -e "$resolved" ]]; then
      echo "${md#$root/}:$line: link '$target' names a missing file"; status=1
    fi
  done < <(grep -no '\](\([^)]*\))' "$md" | sed 's/^\([0-9]*\):](\(.*\))$/\1:\2/')
  # A path outside the repository written as code (`../shared/...`) is a broken link too.
  while IFS=: read -r line text; do
    echo "${md#$root/}:$line: '$text' points outside the repository"; status=1
  done < <(grep -no '`\.\./\.\./[^`]*`\|`\.\./shared/[^`]*`' "$md" || true)
done < <(cd "$root" && {
  for f in README.md CHANGELOG.md */README.md; do [[ -f "$f" ]] && echo "$root/$f"; done
  [[ -d docs ]] && find docs -name '*.md' -type f | LC_ALL=C sort | sed "s|^|$root/|"
})
echo "checked $checked links"
exit $status
