#!/usr/bin/env python3
"""Round trip of wheelset_node driven by a Python (rospy) client at a wall-clock rate: one
WheelsetInput per tick with every wheelset (a sway on the treads at 30 m/s, 60 kN per wheel;
--sway, --offset), sent on a fixed schedule. `topic`: published on wheelset_input on schedule
whatever the answers do, answers collected from wheelset_forces as they come; `service`: one
wheelset_step call per tick (a late call delays the next). Round trip: from just before the
publish or call to the answer's arrival (time.perf_counter). Prints one line per run; a stall is
a round trip over --stall.

What keeps the client's own pauses out of the numbers (a client of one's own needs the same):
the service proxy is persistent (one connection, no master lookup per call); the answers'
subscriber asks for tcp_nodelay and exists only during a topic run (during a service run it would
decode every answer a second time on rospy's thread); an answer is reduced at receipt to what the
run counts, so the heap does not grow with the run (a full collector pass over a heap of every
answer took 0.1-0.6 s); and the garbage collector is off during the timed loop (--gc on keeps
Python's default). The line gives the node's own time per tick (its answers' solver_time
summed), the transport (each round trip less its tick's node time) and the collector's passes
during the run.

  scripts/wheelset_latency.py --launch --seconds 10 --rate 1000 --runs topic,service

--launch starts `roslaunch wheel_rail_contact wheelset.launch wheelsets:=4` on its own master port
(and stops it); without it the script uses the running master and --ns. The contact table takes
about 10 s to build at start-up: the script waits for the service. Exit code 1 if a tick was lost
or a wheel's answer was not ok. The C++ client is `rosrun wheel_rail_contact wheelset_latency`.
"""
import argparse
import contextlib
import math
import os
import subprocess
import sys
import time

from latency_common import (GcPasses, NodeLink, collector_off, keep_schedule, percentile,
                            wait_for_master, wait_for_param)


def parse_args():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--ns", default="wheelsets", help="namespace of the wheelset node")
    p.add_argument("--model", default="nss", help="with --launch: the model")
    p.add_argument("--seconds", type=float, default=10.0, help="seconds of ticks per run")
    p.add_argument("--rate", type=float, default=1000.0, help="ticks per second [Hz]")
    p.add_argument("--runs", default="topic,service", help="comma-separated: topic, service")
    p.add_argument("--stall", type=float, default=0.02, help="a longer round trip is a stall [s]")
    p.add_argument("--launch", action="store_true", help="start the wheelset node (own master)")
    p.add_argument("--port", type=int, default=11470, help="with --launch: master port")
    p.add_argument("--sway", type=float, default=3e-3, help="lateral amplitude [m]")
    p.add_argument("--offset", type=float, default=0.0,
                   help="lateral centre of the sway [m] (2e-3 with --sway 1e-3: clear of the "
                   "centred tread)")
    p.add_argument("--gc", choices=("off", "on"), default="off",
                   help="garbage collector during the timed loop: off (frozen and disabled) or "
                   "on (Python's default)")
    return p.parse_args()


class Client:
    def __init__(self, ns, names, sway=3e-3, offset=0.0):
        import rospy
        from wheel_rail_contact.msg import WheelsetForces, WheelsetInput, WheelsetKinematics
        from wheel_rail_contact.srv import Reset, WheelsetStep
        self.rospy, self.Input, self.Kinematics = rospy, WheelsetInput, WheelsetKinematics
        self.names, self.sway, self.offset = names, sway, offset
        self.link = NodeLink("wheelset node", ns,
                             ("wheelset_input", "wheelset_forces", "wheelset_step"),
                             (WheelsetInput, WheelsetForces, WheelsetStep), 100000, 120.0,
                             keep=self.summary, listen=False)
        self.pub, self.step, self.answers = self.link.pub, self.link.step, self.link.answers
        self.reset = rospy.ServiceProxy(ns + "/reset", Reset)

    def tick(self, k, stamp):
        msg = self.Input()
        msg.header.stamp = stamp
        for i, name in enumerate(self.names):
            w = 2.0 * math.pi * 1.5 * 1e-3 * k + i
            s = self.Kinematics(name=name, lateral=self.offset + self.sway * math.sin(w),
                                yaw=1e-3 * math.cos(w),
                                velocity=30.0, pitch_rate=30.0 / 0.46,
                                lateral_velocity=self.sway * 2.0 * math.pi * 1.5 * math.cos(w),
                                yaw_rate=-1e-3 * 2.0 * math.pi * 1.5 * math.sin(w),
                                load_left=6e4 + 2e3 * math.sin(w),
                                load_right=6e4 - 2e3 * math.sin(w))
            msg.wheelsets.append(s)
        return msg

    def summary(self, forces):
        """What a run keeps of an answer: its wheels not ok (or entries missing or extra) and the
        node's time for the tick (its WheelsetContact steps, solver_time summed) [s]."""
        return self.bad(forces), sum(w.solver_time for w in forces.wheelsets)

    def bad(self, forces):
        n = abs(len(forces.wheelsets) - len(self.names))
        return n + sum((w.left.status != 0) + (w.right.status != 0) for w in forces.wheelsets)

    def run(self, path, n, rate, t0, gc_off):
        """Round trips [s] of the answered ticks, the node's times for them [s], lost ticks, bad
        answers, late sends, wall time, the garbage collector's passes (GcPasses)."""
        # An untimed call opens the persistent connection (rospy opens it on the first call, with a
        # master lookup); the reset then gives a fresh time base and histories (the gap since the
        # last run is no dt > max_dt to reject).
        before = t0 - int(round(1e9 / rate))
        self.step(self.tick(0, self.rospy.Time(before // 10**9, before % 10**9)))
        self.reset()
        if path == "topic":
            self.link.listen()
        self.answers.clear()
        try:
            with collector_off() if gc_off else contextlib.nullcontext():
                with GcPasses() as passes:
                    return self.loop(path, n, rate, t0) + (passes,)
        finally:
            self.link.deaf()

    def loop(self, path, n, rate, t0):
        # the timed loop of run()
        rospy = self.rospy
        sent, trips, node, bad, late = {}, [], [], 0, 0
        start = time.perf_counter()
        for k in range(n):
            ns = t0 + k * int(round(1e9 / rate))
            stamp = rospy.Time(ns // 10**9, ns % 10**9)
            msg = self.tick(k, stamp)
            late += keep_schedule(start, k, rate)
            t = time.perf_counter()
            if path == "service":
                forces = self.step(msg).forces
                trips.append(time.perf_counter() - t)
                b, tick_time = self.summary(forces)
                bad += b
                node.append(tick_time)
                continue
            sent[ns] = t
            self.pub.publish(msg)
        wall = time.perf_counter() - start
        lost = 0
        if path == "topic":
            trips, kept, lost = self.answers.match(sent)
            bad += sum(b for b, _ in kept)
            node = [tick_time for _, tick_time in kept]
        return trips, node, lost, bad, late, wall


def main():
    args = parse_args()
    launch = None
    if args.launch:
        os.environ["ROS_MASTER_URI"] = "http://localhost:%d" % args.port
        launch = subprocess.Popen(
            ["roslaunch", "-p", str(args.port), "wheel_rail_contact", "wheelset.launch",
             "wheelsets:=4", "model:=" + args.model, "ns:=" + args.ns],
            stdout=subprocess.DEVNULL, stderr=subprocess.STDOUT)
    try:
        import rospy
        wait_for_master()
        rospy.init_node("wheelset_latency_py", anonymous=True, disable_signals=True)
        ns = "/" + args.ns.strip("/")
        client = Client(ns, wait_for_param(ns + "/wheelset_node/wheelsets"), args.sway,
                        args.offset)
        n = int(round(args.seconds * args.rate))
        ok = True
        for run in args.runs.split(","):
            t0 = time.time_ns()  # stamps from the wall clock: each run continues the time line
            trips, node, lost, bad, late, wall, gcp = client.run(run, n, args.rate, t0,
                                                                 args.gc == "off")
            stalls = sum(1 for t in trips if t > args.stall)
            transport = [t - c for t, c in zip(trips, node)]  # the round trip less the node's
            ms = lambda v, q: 1e3 * percentile(v, q)  # noqa: E731
            print("python %-7s %d wheelsets, %d ticks at %.0f Hz in %.2f s wall: round trip p50 "
                  "%.3f ms, p99 %.3f ms, max %.3f ms; lost %d, not ok %d, stalls > %.0f ms %d, "
                  "late sends %d; the node's steps per tick p50 %.3f ms, p99 %.3f ms; the "
                  "transport p50 %.3f ms, p99 %.3f ms, max %.3f ms; gc %s: %d passes, %d full, "
                  "longest %.1f ms (load average %.1f)" % (
                      run, len(client.names), n, args.rate, wall, ms(trips, 50), ms(trips, 99),
                      ms(trips, 100), lost, bad, 1e3 * args.stall, stalls, late, ms(node, 50),
                      ms(node, 99), ms(transport, 50), ms(transport, 99), ms(transport, 100),
                      args.gc, gcp.passes, gcp.full, 1e3 * gcp.longest, os.getloadavg()[0]),
                  flush=True)
            ok = ok and lost == 0 and bad == 0
        return 0 if ok else 1
    finally:
        if launch:
            launch.terminate()
            launch.wait(timeout=30)


if __name__ == "__main__":
    sys.exit(main())
