#!/usr/bin/env bash
# The closed-loop wheelset demo (doc/wheelset_demo.md): roslaunch launch/wheelset_demo.launch once
# per contact model — wheelset_sim drives two real contact_nodes (left and right wheel) in lock-step
# through their step services — then prints what the model changes in the vehicle and plots it.
# Needs the built devel space sourced (scripts/demo.sh does both; so does `quickstart.sh demo`).
# Environment: WHEELSET_MODELS (default "steady nss"; "exact" and "shen-li" also run, exact slowly),
# WHEELSET_DT (sim step [s], default 0.0005). Outputs in build/wheelset_demo/.
set -eo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$here"
out="$here/build/wheelset_demo"
models="${WHEELSET_MODELS:-steady nss}"
dt="${WHEELSET_DT:-0.0005}"
rm -rf "$out" && mkdir -p "$out"
export ROS_HOSTNAME="${ROS_HOSTNAME:-localhost}" ROS_HOME="${ROS_HOME:-$here/build/ros_home}"
export ROSCONSOLE_STDOUT_LINE_BUFFERED=1
mkdir -p "$ROS_HOME"
for model in $models; do
  # A private master on a free port: never disturbs (or joins) another ROS system on this machine.
  port="$(/usr/bin/python3 -c 'import socket; s = socket.socket(); s.bind(("", 0)); print(s.getsockname()[1])')"
  export ROS_MASTER_URI="http://localhost:$port"
  echo "[wheelset_demo] roslaunch wheel_rail_contact wheelset_demo.launch model:=$model dt:=$dt"
  timeout 600 roslaunch -p "$port" wheel_rail_contact wheelset_demo.launch model:="$model" dt:="$dt" \
    output_dir:="$out" > "$out/roslaunch_$model.log" 2>&1 || true
  grep -E "wheelset_sim: result" "$out/roslaunch_$model.log" | sed "s/^/  /" || true
  [ -s "$out/wheelset_${model}_summary.csv" ] ||
    { echo "[wheelset_demo] $model: no summary (see $out/roslaunch_$model.log)"; grep -E "FATAL|ERROR" "$out/roslaunch_$model.log" | sed "s/\x1b\[[0-9;]*m//g" | head -5; exit 1; }
done
/usr/bin/python3 scripts/plot_wheelset.py "$out" "$out/wheelset_demo.png" $models
echo "[wheelset_demo] plot (PNG):      $out/wheelset_demo.png"
echo "[wheelset_demo] summaries (CSV): $out/wheelset_<model>_summary.csv, one CSV per case beside them"
