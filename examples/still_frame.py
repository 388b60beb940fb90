"""Times three frames of the robot's camera taken on the stopped simulation, and counts their
non-zero bytes: the camera tagged for explicit handling, `sim.handleVisionSensor`,
`sim.getVisionSensorImg`, untagged again (what `drive --steer camera` does once before a
ZeroMQ run). What `docs/measurements.md` "A camera without a display" records: 4-5 s a frame
and all zeros on a real 4.10 started without `--display`. Needs a protocol-2 server with the
course robot (`sim.sh start 4.10.0 --robot [--display]`) and
`pip install coppeliasim-zmqremoteapi-client`.

    python examples/still_frame.py PORT
"""
import sys, time
from coppeliasim_zmqremoteapi_client import RemoteAPIClient
c = RemoteAPIClient('127.0.0.1', int(sys.argv[1]))
sim = c.require('sim')
cam = sim.getObject('/Robot/camera')
flag = sim.getExplicitHandling(cam)
for i in range(3):
    t = time.time()
    sim.setExplicitHandling(cam, 1)
    sim.handleVisionSensor(cam)
    img, res = sim.getVisionSensorImg(cam)
    sim.setExplicitHandling(cam, flag)
    nz = sum(1 for b in img if b)
    print('frame', i, 'resolution', res, 'non-zero bytes', nz, '%.1f ms' % ((time.time() - t) * 1000))
