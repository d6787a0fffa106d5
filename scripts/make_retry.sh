# Sourced by the build scripts. make_retry LOG MAKE_ARGS...: runs make, appending to LOG; if it
# failed on a compiler crash ("internal compiler error", seen once in CI on GCC 12's ASan build of
# a rostest, not reproducible here on the same commit), runs it once more on one job. Any other
# failure is returned as it is. make gets a 64 MiB stack for GCC's deep recursion, in a subshell
# (an unlimited stack in the caller would change the address layout the ASan tests run in).
make_retry() {
  local log="$1"
  shift
  (ulimit -s 65536 2> /dev/null; make "$@") >> "$log" 2>&1 && return 0
  grep -q "internal compiler error" "$log" || return 1
  echo "[build] the compiler crashed (internal compiler error); retrying once on one job" | tee -a "$log"
  (ulimit -s 65536 2> /dev/null; make "$@" -j1) >> "$log" 2>&1
}
