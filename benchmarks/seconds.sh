# Sourced by the benchmark scripts: `seconds CMD...` runs CMD (its stdout dropped) and prints
# "wall user system" in seconds, from bash's own `time`.
TIMEFORMAT='%R %U %S'
seconds() { { time "$@" > /dev/null; } 2>&1 | tail -1; }
