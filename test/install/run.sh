#!/usr/bin/env bash
# The install space works for a user: installs the built package (build/, prefix build/install as
# scripts/quickstart.sh configures it), builds the downstream catkin package test/install/downstream
# against it alone, and runs one nss step through it twice (catkin's variables, and the exported
# target wheel_rail_contact::core), from outside the source tree. Then the core without ROS: plain
# CMake (-DWRC_ROS=OFF, build/plain/) builds and installs the core and contact_cli alone, and a plain
# CMake project (test/install/plain) builds against that prefix alone with find_package and
# wheel_rail_contact::core and runs the same step.
# Usage: test/install/run.sh [--junit FILE]   (FILE: one JUnit testcase per check)
set -o pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
cd "$here"
junit=""
[ "${1:-}" = "--junit" ] && junit="$2"
export PATH="/usr/bin:$PATH"
logs=build/install_test
rm -rf "$logs" && mkdir -p "$logs"
prefix="$(sed -n 's/^CMAKE_INSTALL_PREFIX:PATH=//p' build/CMakeCache.txt)"

results=()  # "name|seconds|verdict|log"
check() {  # name, log, command...
  local name="$1" log="$2" t0
  shift 2
  t0=$(date +%s)
  if "$@" > "$log" 2>&1; then
    results+=("$name|$(($(date +%s) - t0))|passed|$log")
  else
    results+=("$name|$(($(date +%s) - t0))|failed|$log")
    tail -20 "$log"
  fi
}

# The install space lies inside the package's directory, where roslaunch's search for a launch file
# would find a second copy ("multiple files named contact.launch"): it exists only while this
# script runs, after the rostests (scripts/run_tests.sh).
plain_prefix="$here/build/plain/install"
trap 'rm -rf "$prefix" "$plain_prefix"' EXIT

install_space() {
  rm -rf "$prefix"
  make -C build install
  # The chi table and the calibration are compiled in: the installed library names no file of the
  # source tree.
  if grep -rl "$here/config" "$prefix/lib"; then
    echo "the installed library names $here/config"
    return 1
  fi
}

downstream() {
  # A clean environment with the install space alone (not the devel space the tests run in).
  local b="$here/$logs/downstream"
  env -i HOME="$HOME" PATH=/usr/bin:/bin prefix="$prefix" b="$b" src="$here/test/install/downstream" \
    bash -c 'set -e; set +u; source "$prefix/setup.bash"; set -u
      cmake -S "$src" -B "$b" -DCMAKE_BUILD_TYPE=Release -DPYTHON_EXECUTABLE=/usr/bin/python3
      make -C "$b" -j2
      found="$(sed -n "s/^wheel_rail_contact_DIR:PATH=//p" "$b/CMakeCache.txt")"
      echo "wheel_rail_contact_DIR=$found"
      case "$found" in "$prefix"/*) ;; *) echo "not the install space: $found"; exit 1 ;; esac
      cd /
      "$b/devel/lib/wrc_downstream_example/one_step_catkin"
      "$b/devel/lib/wrc_downstream_example/one_step_target"
      "$b/devel/lib/wrc_downstream_example/one_step_former_name"'
}

# Each in a clean environment without ROS's variables (no catkin, no devel space on the prefix path).
# Only the core, the CLI and the consumer are built (ccache when there is one).
plain_install() {
  local launcher=""
  command -v ccache > /dev/null && launcher="-DCMAKE_CXX_COMPILER_LAUNCHER=ccache"
  rm -rf "$plain_prefix"
  env -i HOME="$HOME" PATH=/usr/bin:/bin CCACHE_BASEDIR="$here" bash -c 'set -eo pipefail
    cmake -S "$1" -B "$1/build/plain" -DWRC_ROS=OFF -DBUILD_TESTING=OFF -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_INSTALL_PREFIX="$2" $3
    grep -q "^catkin_DIR" "$1/build/plain/CMakeCache.txt" && { echo "plain build looked for catkin"; exit 1; }
    make -C "$1/build/plain" -j2 contact_cli
    cmake --install "$1/build/plain"
    cd / && "$2/bin/contact_cli" run --scenario "$1/scenes/demo.csv" --model nss | tail -1' \
    _ "$here" "$plain_prefix" "$launcher"
}

plain_consumer() {
  local b="$here/$logs/plain_consumer"
  env -i HOME="$HOME" PATH=/usr/bin:/bin bash -c 'set -eo pipefail
    cmake -S "$1/test/install/plain" -B "$2" -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$3"
    make -C "$2"
    found="$(sed -n "s/^wheel_rail_contact_DIR:PATH=//p" "$2/CMakeCache.txt")"
    echo "wheel_rail_contact_DIR=$found"
    case "$found" in "$3"/*) ;; *) echo "not the plain install: $found"; exit 1 ;; esac
    cd / && "$2/one_step"' _ "$here" "$b" "$plain_prefix"
}

check install_space "$logs/install.log" install_space
if [[ "${results[0]}" == *"|passed|"* ]]; then
  check downstream_one_step "$logs/downstream.log" downstream
else
  results+=("downstream_one_step|0|not run: install failed|$logs/install.log")
fi
check plain_install "$logs/plain_install.log" plain_install
if [[ "${results[-1]}" == *"|passed|"* ]]; then
  check plain_consumer_one_step "$logs/plain_consumer.log" plain_consumer
else
  results+=("plain_consumer_one_step|0|not run: plain install failed|$logs/plain_install.log")
fi
[ -z "$junit" ] || /usr/bin/python3 scripts/write_junit.py install "$junit" "${results[@]}"
for r in "${results[@]}"; do [[ "$r" == *"|passed|"* ]] || exit 1; done
echo "[install] install space, downstream package, plain CMake install and consumer: passed"
