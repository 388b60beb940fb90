"""How close two vertices must be for CoppeliaSim to merge them when it makes a mesh: two
triangles whose corners lie GAP apart, made by `sim.createShape` (protocol 2, 4.6+) or
`sim.createMeshShape` (protocol 1), and the vertices `sim.getShapeMesh` gives back (6: kept
apart, 4: merged). What `docs/measurements.md` "Where posts spend their time" records; needs
`pip install coppeliasim-zmqremoteapi-client`.

    python examples/vertex_tolerance.py PORT PROTOCOL
"""
import sys

from coppeliasim_zmqremoteapi_client import RemoteAPIClient

c = RemoteAPIClient('127.0.0.1', int(sys.argv[1]))
sim = c.require('sim') if sys.argv[2] == '2' else c.getObject('sim')
create = sim.createShape if sys.argv[2] == '2' else sim.createMeshShape
print('gap m\tvertices kept')
for gap in (1e-3, 1e-4, 1e-5, 2e-6, 5e-7):
    vertices = [0, 0, 0, 1, 0, 0, 0, 1, 0, 1 + gap, 0, 0, 1, 1, 0, 0, 1 + gap, 0]
    h = create(0, 0.3, vertices, [0, 1, 2, 3, 4, 5])
    try:
        kept = sim.getShapeMesh(h)[0]
        print(f'{gap:g}\t{len(kept) // 3}')
    finally:
        sim.removeObjects([h])
