# Sourced by the install tests: `moved_prefix CMAKE BUILD_DIR NAME` makes the test's own work
# folder ($work, removed on exit), installs BUILD_DIR into a prefix and MOVES it to $moved, so
# nothing can work through the path it was installed to. Defines fail MESSAGE.
fail() { echo "FAIL: $*" >&2; exit 1; }

moved_prefix() {
  local cmake=$1 build=$2 name=$3
  work="${TMPDIR:-/tmp}/hoilcd_$$_$name"
  rm -rf "$work"
  mkdir -p "$work"
  trap 'rm -rf "$work"' EXIT
  unset HOILCD_DATA_DIR
  "$cmake" --install "$build" --prefix "$work/prefix" > "$work/install.log" || { cat "$work/install.log"; fail "install"; }
  mv "$work/prefix" "$work/moved"
  moved="$work/moved"
}
