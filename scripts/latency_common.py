"""What scripts/vehicle_latency.py and scripts/wheelset_latency.py share: waiting for the master,
a parameter and a live topic link, the answers collected by stamp, the wall-clock schedule and the
percentiles. Imported from the scripts' own folder (installed beside them)."""
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


class Answers:
    """A node's answers on a topic, by stamp [ns] -> (perf_counter at receipt, message)."""

    def __init__(self):
        self.lock = threading.Condition()
        self.received = {}

    def on_answer(self, msg):
        t = time.perf_counter()
        with self.lock:
            self.received[msg.header.stamp.to_nsec()] = (t, msg)
            self.lock.notify_all()

    def clear(self):
        with self.lock:
            self.received.clear()

    def wait_for(self, stamp_ns, timeout):
        with self.lock:
            self.lock.wait_for(lambda: stamp_ns in self.received, timeout=timeout)

    def match(self, sent, timeout=2.0):
        """The answers to `sent` (stamp [ns] -> perf_counter just before sending) once all are in
        or `timeout` s have passed: the round trips [s] and the answers of the answered ones, and
        how many were lost."""
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
    RuntimeError naming `what` otherwise."""

    def __init__(self, what, ns, topics, types, queue_size, service_timeout):
        # topics: (input, answer, service) names under ns; types: their message/service classes
        import rospy
        input_topic, answer_topic, service = topics
        input_type, answer_type, service_type = types
        self.answers = Answers()
        self.pub = rospy.Publisher(ns + "/" + input_topic, input_type, queue_size=queue_size,
                                   tcp_nodelay=True)
        self.sub = rospy.Subscriber(ns + "/" + answer_topic, answer_type, self.answers.on_answer,
                                    queue_size=queue_size, tcp_nodelay=True)
        rospy.wait_for_service(ns + "/" + service, timeout=service_timeout)
        self.step = rospy.ServiceProxy(ns + "/" + service, service_type, persistent=True)
        end = time.monotonic() + 30.0
        while self.pub.get_num_connections() == 0 and time.monotonic() < end:
            time.sleep(0.01)
        if self.pub.get_num_connections() == 0 or not wait_for_link(
                rospy.resolve_name(ns + "/" + answer_topic), 30.0):
            raise RuntimeError(what + " not connected")


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
