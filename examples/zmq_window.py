"""Times the pass window of a ZeroMQ protocol-2 add-on (CoppeliaSim 4.6+): a request sent at
the default idle fps 8 waits for a main-loop pass; a second one sent DELTA ms after its reply is
answered at once while that pass still polls (50 ms on 4.10), else one pass later. `same`
sends the second on the same connection, `new` on a new client (a new socket and uuid), whose
first request also costs the add-on a new client. Raw pyzmq and cbor2; prints first/second
latency in ms per try: what `docs/measurements.md` "A new client on 4.10" records.

    python examples/zmq_window.py PORT same|new DELTA,DELTA,... TRIES
"""
import time, sys, statistics, uuid
import zmq, cbor2
port = int(sys.argv[1])
ctx = zmq.Context()
class C:
    def __init__(s):
        s.sock = ctx.socket(zmq.REQ); s.sock.connect(f"tcp://127.0.0.1:{port}"); s.uuid = str(uuid.uuid4()); s.first = True
    def call(s, func, args):
        req = {'func': func, 'args': args, 'uuid': s.uuid, 'argsL': len(args)}
        if s.first: req.update({'ver': 2, 'lang': 'python'}); s.first = False
        t = time.perf_counter(); s.sock.send(cbor2.dumps(req)); rep = cbor2.loads(s.sock.recv()); return rep, (time.perf_counter() - t) * 1e3
    def end(s):
        s.sock.send(cbor2.dumps({'func': '_*end*_', 'args': [], 'uuid': s.uuid, 'argsL': 0})); s.sock.recv(); s.sock.close()
a = C(); a.call('zmqRemoteApi.require', ['sim'])
mode = sys.argv[2]  # same | new
for delta in [float(x) for x in sys.argv[3].split(',')]:
    res = []
    for rep in range(int(sys.argv[4])):
        time.sleep(0.3 + 0.125 * (rep % 3) / 3)   # land R1 at some phase of the pass grid
        _, l1 = a.call('sim.getSimulationState', [])
        time.sleep(delta / 1000)
        if mode == 'same':
            _, l2 = a.call('sim.getSimulationState', [])
        else:
            b = C(); _, l2 = b.call('zmqRemoteApi.require', ['sim']); b.end()
        res.append((l1, l2))
    print(f"delta {delta:5.1f} ms: " + " ".join(f"{l1:5.1f}/{l2:5.1f}" for l1, l2 in res), flush=True)
a.end()
