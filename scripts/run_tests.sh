#!/usr/bin/env bash
# Runs the tests of the built package in stages and prints one verdict line "N passed, N failed"
# counting every stage run (scripts/test_summary.py over build/test_results).
#   fast      the gtest binaries: unit, validation at coarse settings, CLI, the node's ROS-free part
#   standard  fast + every rostest but the stress ones + the launch check + the install space
#             (test/install/run.sh): the README's test command
#   full      standard + the stress rostests + sanitizers + fuzzing: CI (.ci/run)
# Each stage prints its wall time. Called by scripts/quickstart.sh after the build.
# Env: WRC_HARDENING=0 skips sanitizers and fuzzing in full.
set -o pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
mode="${1:-standard}"
case "$mode" in fast | standard | full) ;; *)
  echo "usage: $0 {fast|standard|full}" >&2
  exit 2
  ;;
esac
export PATH="/usr/bin:$PATH"
export ROS_HOSTNAME=localhost ROS_HOME="$PWD/build/ros_home" ROSCONSOLE_STDOUT_LINE_BUFFERED=1
export PYTHONUNBUFFERED=1
mkdir -p "$ROS_HOME"
set +u
# shellcheck disable=SC1091
source build/devel/setup.bash
rm -rf build/test_results
: > build/run_tests.log

# catkin's per-test targets (one per gtest binary, rostest launch file and launch check).
leaves="$(make -C build help | sed -n -E \
  's/^\.\.\. (run_tests_wheel_rail_contact_(gtest|rostest|roslaunch-check)_.+)$/\1/p')"
gtests="$(grep -E '_gtest_' <<< "$leaves")"
rostests="$(grep -vE '_gtest_' <<< "$leaves" | grep -v stress)"
stress="$(grep -vE '_gtest_' <<< "$leaves" | grep stress)"

stage() {  # name, command...: runs it and prints its wall time
  local name="$1" t0
  shift
  t0=$(date +%s)
  "$@"
  echo "[tests] $name: $(($(date +%s) - t0)) s"
}
run_targets() {  # catkin run_tests targets, one after the other (rostests pick free ports)
  # shellcheck disable=SC2086
  make -C build $* >> build/run_tests.log 2>&1
  grep -E "^\[  FAILED  \]|Failure$|FAILURE" build/run_tests.log | sort -u | head -40
}

stage gtests run_targets $gtests
if [ "$mode" != fast ]; then
  stage rostests run_targets $rostests
  stage install bash test/install/run.sh --junit build/test_results/install/install.xml
fi
if [ "$mode" = full ]; then
  [ -z "$stress" ] || stage stress run_targets $stress
  # Hardening (doc/hardening.md): the ASan+UBSan build of the tests and the fuzz targets, one JUnit
  # testcase per sanitized executable and per fuzz target.
  if [ "${WRC_HARDENING:-1}" = "1" ]; then
    stage sanitizers bash scripts/run_sanitizers.sh --junit build/test_results/hardening/sanitizers.xml
    stage fuzz bash scripts/run_fuzz.sh --junit build/test_results/hardening/fuzz.xml
  fi
fi
/usr/bin/python3 scripts/test_summary.py build/test_results
