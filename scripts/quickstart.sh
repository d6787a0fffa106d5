#!/usr/bin/env bash
# One entry point for a fresh Debian 12 machine: installs what is missing, builds, then
#   demo  runs the demo scene through the real node (the README's first command)
#   test       unit, validation at coarse settings, CLI, rostests and the install space; ends with
#              "N passed, N failed" (non-zero exit on any failure)
#   test-fast  the gtest binaries only (unit, validation, CLI, the node's ROS-free part)
#   test-full  test, then the stress rostests, sanitizers and fuzzing (CI: .ci/run)
#   build only installs and builds
set -eo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$here"
# shellcheck source=scripts/make_retry.sh
source scripts/make_retry.sh
mode="${1:-demo}"

# Debian 12's own ROS 1 and the tools the build, the tests and the figures need.
packages=(g++ make cmake catkin libroscpp-dev ros-message-generation
  libstd-msgs-dev ros-std-msgs libgeometry-msgs-dev ros-geometry-msgs
  libeigen3-dev libgtest-dev librostest-dev python3-rostest python3-std-msgs python3-geometry-msgs
  rosbash python3-rostopic python3-rosservice python3-rosnode ros-message-runtime
  libdiagnostic-updater-dev libnodeletlib-dev libnodeletlib-tools
  libyaml-cpp-dev libbenchmark-dev libfftw3-dev libhwy-dev
  python3-matplotlib python3-yaml python3-numpy clang-format
  librosbag-storage-dev python3-rosbag  # rostest pairing: writes a bag, plays it
  clang libclang-rt-14-dev)  # clang + its runtime: libFuzzer (scripts/run_fuzz.sh)

install_missing() {
  local missing=()
  for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "[quickstart] installing: ${missing[*]}"
  local sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
}

build() {
  # /usr/bin first: a pyenv python3 elsewhere on PATH lacks catkin_pkg and rospy.
  export PATH="/usr/bin:$PATH"
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DPYTHON_EXECUTABLE=/usr/bin/python3 \
    -DCATKIN_ENABLE_TESTING=ON -DCMAKE_INSTALL_PREFIX="$here/build/install" -DWRC_WERROR="${WRC_WERROR:-OFF}" > build.log 2>&1 || { cat build.log; exit 1; }
  make_retry build.log -C build -j"$(nproc)" all tests || { tail -60 build.log; exit 1; }
  echo "[quickstart] built (log: build.log)"
}

ros_env() {
  export ROS_HOSTNAME=localhost ROS_HOME="$here/build/ros_home" ROSCONSOLE_STDOUT_LINE_BUFFERED=1
  export PYTHONUNBUFFERED=1
  mkdir -p "$ROS_HOME"
  set +u
  # shellcheck disable=SC1091
  source build/devel/setup.bash
}

install_missing
build
case "$mode" in
  build) ;;
  test) exec bash scripts/run_tests.sh standard ;;
  test-fast) exec bash scripts/run_tests.sh fast ;;
  test-full) exec bash scripts/run_tests.sh full ;;
  demo)
    if [ -x scripts/demo.sh ]; then ros_env; exec bash scripts/demo.sh; fi
    echo "[quickstart] no ROS demo yet: replaying scenes/demo.csv through contact_cli"
    build/devel/lib/wheel_rail_contact/contact_cli run --scenario scenes/demo.csv --model steady ;;
  *) echo "usage: $0 {demo|test|test-fast|test-full|build}" >&2; exit 2 ;;
esac
