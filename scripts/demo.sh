#!/usr/bin/env bash
# The demo behind `bash scripts/quickstart.sh demo` (which builds and sources the devel space): by
# default the closed-loop wheelset demos (scripts/wheelset_demo.sh: a wheelset on S1002 / UIC60
# through WheelsetContact, then an equivalent-conicity wheelset driving a left and a right
# contact_node; steady against nss; doc/wheelset_demo.md). DEMO=scenes instead:
# roslaunch launch/demo.launch — two real contact_nodes fed the paper's combined-creepage and
# varying-load scenes by scene_player, recorded by force_recorder — then plots the forces and checks
# them against `contact_cli run` on the same scenes. Ends by itself; prints where its outputs are.
# Environment: DEMO_MODEL (default nss), DEMO_TIME_SCALE (scene s per wall s, default 8).
set -eo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$here"
if [ "${DEMO:-wheelset}" = wheelset ]; then exec bash scripts/wheelset_demo.sh; fi
[ "${DEMO}" = scenes ] || { echo "[demo] DEMO must be wheelset (default) or scenes" >&2; exit 2; }
out="$here/build/demo"
model="${DEMO_MODEL:-nss}"
rm -rf "$out" && mkdir -p "$out"
export ROS_HOSTNAME="${ROS_HOSTNAME:-localhost}" ROS_HOME="${ROS_HOME:-$here/build/ros_home}"
mkdir -p "$ROS_HOME"
# A private master on a free port: never disturbs (or joins) another ROS system on this machine.
port="$(/usr/bin/python3 -c 'import socket; s = socket.socket(); s.bind(("", 0)); print(s.getsockname()[1])')"
export ROS_MASTER_URI="http://localhost:$port"
echo "[demo] roslaunch wheel_rail_contact demo.launch model:=$model (master on port $port)"
timeout 300 roslaunch -p "$port" wheel_rail_contact demo.launch model:="$model" \
  output_dir:="$out" time_scale:="${DEMO_TIME_SCALE:-8}" 2>&1 | tee "$out/roslaunch.log" |
  grep -E "\] (scene_player|force_recorder)|FATAL|ERROR\]" | sed "s/\x1b\[[0-9;]*m//g" || true
for scene in combined varying_load; do
  [ -s "$out/${scene}_forces.csv" ] || { echo "[demo] no output for $scene (see $out/roslaunch.log)"; exit 1; }
done
/usr/bin/python3 scripts/plot_forces.py "$out/demo_forces.png" "$out/combined_forces.csv" \
  "$out/varying_load_forces.csv" > /dev/null
# The same scenes through contact_cli (same YAML, same model): the node must agree.
cli="$here/build/devel/lib/wheel_rail_contact/contact_cli"
for scene in combined varying_load; do
  "$cli" run --scenario "scenes/paper_$scene.csv" --config config/paper.yaml --model "$model" \
    > "$out/${scene}_contact_cli.csv"
done
/usr/bin/python3 - "$out" <<'PY'
import csv, sys
out = sys.argv[1]
for scene in ("combined", "varying_load"):
    node = list(csv.DictReader(open(f"{out}/{scene}_forces.csv")))
    cli = list(csv.DictReader(line for line in open(f"{out}/{scene}_contact_cli.csv")))
    scale = max(max(abs(float(r["fx"])), abs(float(r["fy"]))) for r in cli) or 1.0
    dev = max(abs(float(n[k]) - float(c[k])) for n, c in zip(node, cli) for k in ("fx", "fy", "mz"))
    print(f"[demo] {scene}: {len(node)} steps through contact_node ({len(cli)} in the scene), "
          f"max |node - contact_cli| / max|F| = {dev / scale:.2e}")
PY
echo "[demo] forces (CSV): $out/combined_forces.csv $out/varying_load_forces.csv"
echo "[demo] plot (PNG):   $out/demo_forces.png"
echo "[demo] contact_cli:  $out/combined_contact_cli.csv $out/varying_load_contact_cli.csv"
echo "[demo] launch log:   $out/roslaunch.log"
