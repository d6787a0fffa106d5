#!/usr/bin/env bash
# Runs every test of the built package (gtest, rostest, sanitizers, fuzzing) and prints the
# verdict line.
# Called by scripts/quickstart.sh test after the build; not meant to be run before it.
set -o pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
export PATH="/usr/bin:$PATH"
export ROS_HOSTNAME=localhost ROS_HOME="$PWD/build/ros_home" ROSCONSOLE_STDOUT_LINE_BUFFERED=1
export PYTHONUNBUFFERED=1
mkdir -p "$ROS_HOME"
set +u
# shellcheck disable=SC1091
source build/devel/setup.bash
rm -rf build/test_results
make -C build run_tests > build/run_tests.log 2>&1
grep -E "^\[  FAILED  \]|Failure$|FAILURE" build/run_tests.log | sort -u | head -40
# Hardening (README "Fuzzing and sanitizers"): the ASan+UBSan build of the tests and the fuzz
# targets, one JUnit testcase per sanitized executable and per fuzz target. WRC_HARDENING=0 skips.
if [ "${WRC_HARDENING:-1}" = "1" ]; then
  bash scripts/run_sanitizers.sh --junit build/test_results/hardening/sanitizers.xml
  bash scripts/run_fuzz.sh --junit build/test_results/hardening/fuzz.xml
fi
/usr/bin/python3 scripts/test_summary.py build/test_results
