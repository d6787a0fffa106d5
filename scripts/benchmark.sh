#!/usr/bin/env bash
# Latency and throughput of contact_node on this machine (a measurement, not a test): for 1 and 8
# contacts (default config: nss, 20x20 fixed mesh, load pairing by stamp: each tick sends its load
# and its creepage), p50/p99 publish->contact_state round trip
# and the sustained message rate. Needs a build (bash scripts/quickstart.sh build).
# usage: scripts/benchmark.sh [CONTACT_COUNTS...]   (default: 1 8)
set -eo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$here"
export PATH="/usr/bin:$PATH" ROS_HOSTNAME=localhost ROS_HOME="$here/build/ros_home"
mkdir -p "$ROS_HOME"
set +u
# shellcheck disable=SC1091
source build/devel/setup.bash
bin="$here/build/devel/lib/wheel_rail_contact"
port="$(/usr/bin/python3 -c 'import socket; s = socket.socket(); s.bind(("", 0)); print(s.getsockname()[1])')"
export ROS_MASTER_URI="http://localhost:$port"
rosmaster --core -p "$port" > "$ROS_HOME/benchmark_master.log" 2>&1 &
master=$!
pids=()
stop_nodes() {
  [ ${#pids[@]} -eq 0 ] && return 0
  for p in "${pids[@]}"; do kill -INT "$p" 2>/dev/null || true; done
  wait "${pids[@]}" 2>/dev/null || true
  pids=()
}
cleanup() {
  stop_nodes
  kill "$master" 2>/dev/null || true
  wait "$master" 2>/dev/null || true
}
trap cleanup EXIT
sleep 1
counts=("$@")
[ ${#counts[@]} -eq 0 ] && counts=(1 8)
echo "# $(date -u +%FT%TZ) $(nproc) cores, $(uname -m); load average: $(cut -d' ' -f1-3 /proc/loadavg)"
for n in "${counts[@]}"; do
  names=()
  for ((i = 0; i < n; i++)); do
    "$bin/contact_node" __ns:="/bench$n/c$i" > "$ROS_HOME/benchmark_node_$i.log" 2>&1 &
    pids+=($!)
    names+=("bench$n/c$i")
  done
  list="$(IFS=,; echo "${names[*]}")"
  "$bin/contact_benchmark" _contacts:="$list" _round_trips:=1000 _messages:=$((20000 / n)) \
    _window:=50
  stop_nodes
done
