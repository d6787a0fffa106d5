"""What scripts/vehicle_latency.py and scripts/wheelset_latency.py share: waiting for the master,
a parameter and a live topic link, the answers collected by stamp, the wall-clock schedule, the
garbage collector held off a timed loop and the percentiles. Imported from the scripts' own folder
(installed beside them)."""
import contextlib
import gc
import math
import threading
import time
import xmlrpc.client


def percentile(values, q):
    if not values:
        return float("nan")
    s = sorted(values)
    return s[min(len(s) - 1, max(0, int(math.ceil(q / 100.0 * len(s))) - 1))]


def wait_for_master(timeout=30.0):
    import rosgraph
    end = time.monotonic() + timeout
    while not rosgraph.is_master_online() and time.monotonic() < end:
        time.sleep(0.1)


def wait_for_param(name, timeout=30.0):
    """The parameter `name` once it is set (a node's list of names), waiting up to `timeout` s."""
    import rospy
    end = time.monotonic() + timeout
    while not rospy.has_param(name) and time.monotonic() < end:
        time.sleep(0.1)
    return rospy.get_param(name)


def wait_for_link(topic, timeout):
    """True once a publisher of `topic` lists a live connection to this node (getBusInfo): a
    subscriber counts a publisher before the publisher takes the connection, and what is
    published in between is lost."""
    import rosgraph.masterapi
    import rospy
    me = rospy.get_name()
    master = rosgraph.masterapi.Master(me)
    end = time.monotonic() + timeout
    while time.monotonic() < end and not rospy.is_shutdown():
        for node in dict(master.getSystemState()[0]).get(topic, []):
            rows = xmlrpc.client.ServerProxy(master.lookupNode(node)).getBusInfo(me)[2]
            if any(r[1] == me and r[2] == "o" and r[4] == topic for r in rows):
                return True
        time.sleep(0.01)  # poll the graph again
    return False


class GcPasses:
    """Python's garbage-collector passes while it is installed: how many, how many of the oldest
    generation (2), the longest [s]. A full pass walks every live container object, so a client
    that keeps its answers pauses for as long as its heap is large."""

    def __init__(self):
        self.passes, self.full, self.longest, self._start = 0, 0, 0.0, None

    def __call__(self, phase, info):
        now = time.perf_counter()
        if phase == "start":
            self._start = now
        elif self._start is not None:
            self.passes += 1
            self.full += info["generation"] == 2
            self.longest = max(self.longest, now - self._start)

    def __enter__(self):
        gc.callbacks.append(self)
        return self

    def __exit__(self, *exc):
        gc.callbacks.remove(self)


@contextlib.contextmanager
def collector_off():
    """No garbage-collector pass inside: collects once, freezes what lives (gc.freeze: later
    passes skip it), disables the collector, and on leaving enables it again. Safe for a loop of
    ROS messages: they hold no reference cycles, so reference counting frees each one at once
    and nothing piles up while the collector is off."""
    was_on = gc.isenabled()
    gc.collect()
    gc.freeze()
    gc.disable()
    try:
        yield
    finally:
        if was_on:
            gc.enable()
        gc.unfreeze()


class Answers:
    """A node's answers on a topic, by stamp [ns] -> (perf_counter at receipt, keep(message));
    `keep` (default: the message itself) says what of an answer to hold until the run ends: a
    summary keeps the heap small (see GcPasses)."""

    def __init__(self, keep=None):
        self.lock = threading.Condition()
        self.received = {}
        self.keep = keep or (lambda msg: msg)

    def on_answer(self, msg):
        t = time.perf_counter()
        kept = self.keep(msg)
        with self.lock:
            self.received[msg.header.stamp.to_nsec()] = (t, kept)
            self.lock.notify_all()

    def clear(self):
        with self.lock:
            self.received.clear()

    def wait_for(self, stamp_ns, timeout):
        with self.lock:
            self.lock.wait_for(lambda: stamp_ns in self.received, timeout=timeout)

    def match(self, sent, timeout=2.0):
        """The answers to `sent` (stamp [ns] -> perf_counter just before sending) once all are in
        or `timeout` s have passed: the round trips [s] and what was kept of the answered ones,
        and how many were lost."""
        with self.lock:
            self.lock.wait_for(lambda: len(self.received) >= len(sent), timeout=timeout)
            got = dict(self.received)
        trips, answers = [], []
        for s, t in sent.items():
            if s in got:
                trips.append(got[s][0] - t)
                answers.append(got[s][1])
        return trips, answers, len(sent) - len(trips)


class NodeLink:
    """A node's input publisher (pub), its answers' subscriber (into answers, an Answers) and its
    step service (step, persistent), connected: waits up to `service_timeout` s for the service,
    then 30 s each for the node's subscription and for the answers' link to this node; raises
    RuntimeError naming `what` otherwise. With listen=False the answers' subscriber is made only
    by listen() and dropped by deaf(): a client that calls the service only need not receive and
    decode every answer a second time from the topic (rospy does that on its own thread, which
    takes the interpreter from the calls)."""

    def __init__(self, what, ns, topics, types, queue_size, service_timeout, keep=None,
                 listen=True):
        # topics: (input, answer, service) names under ns; types: their message/service classes
        import rospy
        input_topic, answer_topic, service = topics
        input_type, self.answer_type, service_type = types
        self.what, self.queue_size = what, queue_size
        self.answer_topic = ns + "/" + answer_topic
        self.answers = Answers(keep)
        self.sub = None
        self.pub = rospy.Publisher(ns + "/" + input_topic, input_type, queue_size=queue_size,
                                   tcp_nodelay=True)
        rospy.wait_for_service(ns + "/" + service, timeout=service_timeout)
        self.step = rospy.ServiceProxy(ns + "/" + service, service_type, persistent=True)
        end = time.monotonic() + 30.0
        while self.pub.get_num_connections() == 0 and time.monotonic() < end:
            time.sleep(0.01)
        if self.pub.get_num_connections() == 0:
            raise RuntimeError(what + " not connected")
        if listen:
            self.listen()

    def listen(self):
        """Subscribes to the answers (tcp_nodelay) and waits up to 30 s for the link."""
        import rospy
        if self.sub is None:
            self.sub = rospy.Subscriber(self.answer_topic, self.answer_type,
                                        self.answers.on_answer, queue_size=self.queue_size,
                                        tcp_nodelay=True)
        if not wait_for_link(rospy.resolve_name(self.answer_topic), 30.0):
            raise RuntimeError(self.what + " not connected")

    def deaf(self):
        """Drops the answers' subscriber (listen() makes it again)."""
        if self.sub is not None:
            self.sub.unregister()
            self.sub = None


def keep_schedule(start, k, rate):
    """Sleeps until tick `k` of a schedule at `rate` Hz from `start` (perf_counter) is due; 1 if
    it is already more than a tick late (a late send), else 0."""
    due = start + k / rate
    now = time.perf_counter()
    if now < due:
        time.sleep(due - now)
    elif now > due + 1.0 / rate:
        return 1
    return 0
