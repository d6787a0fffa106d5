#!/usr/bin/env bash
# The closed-loop wheelset demos (doc/wheelset_demo.md), each through roslaunch:
#   profiles   launch/profile_wheelset_demo.launch: a wheelset on S1002 / UIC60 1:40 through
#              WheelsetContact (profile_wheelset_sim), steady and nss: hunting at Klingel's
#              wavelength and a lateral impact into flange contact; prints the figures and plots them
#   conicity   launch/wheelset_demo.launch once per contact model: an equivalent-conicity wheelset
#              (wheelset_sim) driving two real contact_nodes in lock-step through their step
#              services; what nss changes against steady at short wavelengths
# Needs the built devel space sourced (scripts/demo.sh does both; so does `quickstart.sh demo`).
# Environment: WHEELSET_DEMO (default "profiles conicity"), WHEELSET_MODELS (default "steady nss";
# "exact" and "shen-li" also run, exact slowly), WHEELSET_DT (sim step [s], default 0.0005).
# Outputs in build/wheelset_demo/ (profiles: its profiles/ folder).
set -eo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$here"
out="$here/build/wheelset_demo"
demos="${WHEELSET_DEMO:-profiles conicity}"
models="${WHEELSET_MODELS:-steady nss}"
rm -rf "$out" && mkdir -p "$out"
export ROS_HOSTNAME="${ROS_HOSTNAME:-localhost}" ROS_HOME="${ROS_HOME:-$here/build/ros_home}"
export ROSCONSOLE_STDOUT_LINE_BUFFERED=1
mkdir -p "$ROS_HOME"
# A private master on a free port: never disturbs (or joins) another ROS system on this machine.
master() {
  port="$(/usr/bin/python3 -c 'import socket; s = socket.socket(); s.bind(("", 0)); print(s.getsockname()[1])')"
  export ROS_MASTER_URI="http://localhost:$port"
}
for demo in $demos; do
  case "$demo" in
    profiles)
      dir="$out/profiles"
      mkdir -p "$dir"
      dt="${WHEELSET_DT:-0.0005}"
      list="[$(echo $models | sed 's/ /, /g')]"
      master
      echo "[wheelset_demo] roslaunch wheel_rail_contact profile_wheelset_demo.launch models:=\"$list\" dt:=$dt"
      start=$(date +%s)
      timeout 900 roslaunch -p "$port" wheel_rail_contact profile_wheelset_demo.launch \
        models:="$list" dt:="$dt" output_dir:="$dir" > "$dir/roslaunch.log" 2>&1 || true
      [ -s "$dir/profile_summary.csv" ] ||
        { echo "[wheelset_demo] profiles: no summary (see $dir/roslaunch.log)"; grep -E "FATAL|ERROR" "$dir/roslaunch.log" | sed "s/\x1b\[[0-9;]*m//g" | head -5; exit 1; }
      grep -E "profile_wheelset_sim: kinematics" "$dir/roslaunch.log" | sed "s/^/  /" || true
      /usr/bin/python3 scripts/plot_profile_wheelset.py "$dir" "$out/wheelset_profiles.png"
      echo "[wheelset_demo] profiles: $(( $(date +%s) - start )) s wall"
      echo "[wheelset_demo] plot (PNG):      $out/wheelset_profiles.png"
      echo "[wheelset_demo] summary (CSV):   $dir/profile_summary.csv, one CSV per model and case beside it" ;;
    conicity)
      dt="${WHEELSET_DT:-0.0005}"
      for model in $models; do
        master
        echo "[wheelset_demo] roslaunch wheel_rail_contact wheelset_demo.launch model:=$model dt:=$dt"
        timeout 600 roslaunch -p "$port" wheel_rail_contact wheelset_demo.launch model:="$model" dt:="$dt" \
          output_dir:="$out" > "$out/roslaunch_$model.log" 2>&1 || true
        grep -E "wheelset_sim: result" "$out/roslaunch_$model.log" | sed "s/^/  /" || true
        [ -s "$out/wheelset_${model}_summary.csv" ] ||
          { echo "[wheelset_demo] $model: no summary (see $out/roslaunch_$model.log)"; grep -E "FATAL|ERROR" "$out/roslaunch_$model.log" | sed "s/\x1b\[[0-9;]*m//g" | head -5; exit 1; }
      done
      /usr/bin/python3 scripts/plot_wheelset.py "$out" "$out/wheelset_demo.png" $models
      echo "[wheelset_demo] plot (PNG):      $out/wheelset_demo.png"
      echo "[wheelset_demo] summaries (CSV): $out/wheelset_<model>_summary.csv, one CSV per case beside them" ;;
    *) echo "[wheelset_demo] WHEELSET_DEMO: unknown demo '$demo' (profiles, conicity)" >&2; exit 2 ;;
  esac
done
