#!/usr/bin/env python3
"""Round trip of vehicle_node driven by a Python (rospy) client: one VehicleInput per tick with
every contact, through the vehicle_input/vehicle_state topic pair and the vehicle_step service,
in sim-time lock-step (the next tick is sent when the previous answer is in; /clock is published
per tick, as a simulator owning time does) and at a wall-clock rate (ticks sent on a fixed
schedule, answers collected as they come). Prints one line per run and writes a CSV summary.

  scripts/vehicle_latency.py --launch --contacts 8 --seconds 10 --rate 1000 --csv out.csv

--launch starts `roslaunch wheel_rail_contact vehicle_contacts.launch use_sim_time:=true` on its own
master port (and stops it); without it the script uses the running master and --ns. Exit code 1
if a tick was lost or an entry came back with a status other than ok.
"""
import argparse
import math
import os
import subprocess
import sys
import time

from latency_common import NodeLink, keep_schedule, percentile, wait_for_master, wait_for_param


def parse_args():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--ns", default="vehicle", help="namespace of the vehicle node")
    p.add_argument("--contacts", type=int, default=8, choices=[4, 8],
                   help="with --launch: contacts of the launched vehicle")
    p.add_argument("--model", default="nss", help="with --launch: the contacts' model")
    p.add_argument("--seconds", type=float, default=10.0, help="simulated seconds per run")
    p.add_argument("--rate", type=float, default=1000.0, help="ticks per second [Hz]")
    p.add_argument("--runs", default="topic-lockstep,service-lockstep,topic-wall,service-wall",
                   help="comma-separated runs: {topic,service,steps}-{lockstep,wall}; steps = the\n"
                        "same contacts as separate contact_nodes (launch/vehicle.launch per\n"
                        "bogie), one `step` call per contact and tick, for comparison")
    p.add_argument("--launch", action="store_true", help="start the vehicle node (own master)")
    p.add_argument("--port", type=int, default=11460, help="with --launch: master port")
    p.add_argument("--csv", default="", help="write the summary here")
    return p.parse_args()


class Client:
    def __init__(self, ns, names):
        import rospy
        from rosgraph_msgs.msg import Clock
        from wheel_rail_contact.msg import ContactInput, VehicleInput, VehicleState
        from wheel_rail_contact.srv import VehicleStep
        self.rospy, self.ContactInput, self.VehicleInput = rospy, ContactInput, VehicleInput
        self.names = names
        self.clock = rospy.Publisher("/clock", Clock, queue_size=10)
        self.Clock = Clock
        self.link = NodeLink("vehicle node", ns, ("vehicle_input", "vehicle_state", "vehicle_step"),
                             (VehicleInput, VehicleState, VehicleStep), 10000, 30.0)
        self.pub, self.step, self.answers = self.link.pub, self.link.step, self.link.answers

    def tick(self, k, stamp):
        msg = self.VehicleInput()
        msg.header.stamp = stamp
        for i, name in enumerate(self.names):
            c = self.ContactInput()
            c.name = name
            c.velocity = 30.0
            c.longitudinal = 1e-3 * math.sin(0.01 * k + i)
            c.lateral = 5e-4 * math.cos(0.013 * k + i)
            c.spin = 0.2 * math.sin(0.007 * k)
            c.normal_force = 8e4 + 5e3 * math.sin(0.02 * k + i)
            msg.contacts.append(c)
        return msg

    def connect_contact_nodes(self):
        """The same contacts as contact_nodes of launch/vehicle.launch (bogie1, bogie2)."""
        from wheel_rail_contact.srv import Reset, Step
        self.Step = Step
        self.steps, self.resets = [], []
        for i in range(len(self.names)):
            ns = "/bogie%d/wheelset%d/%s" % (1 + i // 4, 1 + (i // 2) % 2, ("left", "right")[i % 2])
            self.rospy.wait_for_service(ns + "/step", timeout=30.0)
            self.steps.append(self.rospy.ServiceProxy(ns + "/step", Step, persistent=True))
            self.resets.append(self.rospy.ServiceProxy(ns + "/reset", Reset))

    def step_each(self, msg):
        """One tick as one `step` call per contact_node; returns the statuses."""
        statuses = []
        for proxy, c in zip(self.steps, msg.contacts):
            r = proxy(self.Step._request_class(
                stamp=msg.header.stamp, longitudinal=c.longitudinal, lateral=c.lateral,
                spin=c.spin, velocity=c.velocity, normal_force=c.normal_force))
            statuses.append(r.status)
        return statuses

    def run(self, path, timing, n, rate, t0):
        # t0: the first tick's stamp [ns]
        """Returns round trips [s] of the answered ticks, the lost ticks, bad entries, late sends."""
        rospy = self.rospy
        self.answers.clear()
        sent = {}
        trips, bad, late = [], 0, 0
        start = time.perf_counter()
        for k in range(n):
            ns = t0 + k * int(round(1e9 / rate))
            stamp = rospy.Time(ns // 10**9, ns % 10**9)
            msg = self.tick(k, stamp)
            if timing == "wall":
                late += keep_schedule(start, k, rate)
            else:
                self.clock.publish(self.Clock(clock=stamp))
            t = time.perf_counter()
            if path == "steps":
                statuses = self.step_each(msg)
                trips.append(time.perf_counter() - t)
                bad += sum(1 for st in statuses if st != 0)
                continue
            if path == "service":
                state = self.step(msg).state
                trips.append(time.perf_counter() - t)
                bad += sum(1 for c in state.contacts if c.status != 0)
                bad += abs(len(state.contacts) - len(self.names))
                continue
            sent[stamp.to_nsec()] = t
            self.pub.publish(msg)
            if timing == "lockstep":
                self.answers.wait_for(stamp.to_nsec(), timeout=1.0)
        lost = 0
        if path == "topic":
            trips, answers, lost = self.answers.match(sent)
            for state in answers:
                bad += sum(1 for c in state.contacts if c.status != 0)
                bad += abs(len(state.contacts) - len(self.names))
        return trips, lost, bad, late, time.perf_counter() - start


def main():
    args = parse_args()
    launches = []
    baseline = any(r.startswith("steps-") for r in args.runs.split(","))
    if args.launch:
        os.environ["ROS_MASTER_URI"] = "http://localhost:%d" % args.port
        launches.append(subprocess.Popen(
            ["roslaunch", "-p", str(args.port), "wheel_rail_contact", "vehicle_contacts.launch",
             "contacts:=%d" % args.contacts, "model:=" + args.model, "ns:=" + args.ns,
             "use_sim_time:=true"],
            stdout=subprocess.DEVNULL, stderr=subprocess.STDOUT))
        for bogie in range(1, args.contacts // 4 + 1) if baseline else []:
            wait_for_master()  # the first roslaunch starts the master
            launches.append(subprocess.Popen(
                ["roslaunch", "wheel_rail_contact", "vehicle.launch", "bogie:=bogie%d" % bogie,
                 "model:=" + args.model], stdout=subprocess.DEVNULL, stderr=subprocess.STDOUT))
    try:
        import rospy
        wait_for_master()
        rospy.init_node("vehicle_latency", anonymous=True, disable_signals=True)
        names = wait_for_param("/" + args.ns.strip("/") + "/vehicle_node/contacts")
        client = Client("/" + args.ns.strip("/"), names)
        from wheel_rail_contact.srv import Reset
        reset_vehicle = rospy.ServiceProxy("/" + args.ns.strip("/") + "/reset", Reset)
        if baseline:
            client.connect_contact_nodes()

        def reset():
            reset_vehicle()
            for r in client.resets if baseline else []:
                r()
        n = int(round(args.seconds * args.rate))
        rows = []
        t0 = 1000 * 10**9  # [ns]
        for run in args.runs.split(","):
            path, timing = run.split("-")
            reset()  # every run starts the contacts afresh at the same stamps
            trips, lost, bad, late, wall = client.run(path, timing, n, args.rate, t0)
            row = dict(run=run, contacts=len(names), ticks=n, answered=len(trips), lost=lost,
                       load_avg_1min=os.getloadavg()[0],
                       rejected_entries=bad, late_sends=late, wall_s=wall,
                       p50_ms=1e3 * percentile(trips, 50), p99_ms=1e3 * percentile(trips, 99),
                       max_ms=1e3 * max(trips) if trips else float("nan"))
            rows.append(row)
            print("%-17s %d contacts, %d ticks in %.2f s: p50 %.3f ms, p99 %.3f ms, max %.3f ms, "
                  "lost %d, rejected entries %d, late sends %d (load average %.1f)" % (
                      run, row["contacts"], n, wall, row["p50_ms"], row["p99_ms"], row["max_ms"],
                      lost, bad, late, row["load_avg_1min"]), flush=True)
        if args.csv:
            with open(args.csv, "w") as f:
                keys = list(rows[0].keys())
                f.write(",".join(keys) + "\n")
                for r in rows:
                    f.write(",".join(("%.4f" % r[k]) if isinstance(r[k], float) else str(r[k])
                                     for k in keys) + "\n")
        return 0 if all(r["lost"] == 0 and r["rejected_entries"] == 0 for r in rows) else 1
    finally:
        for launch in reversed(launches):
            launch.terminate()
            launch.wait(timeout=30)


if __name__ == "__main__":
    sys.exit(main())
