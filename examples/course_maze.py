"""The course's maze script, rewritten with ``vrep_maze``.

Task 5 of "Mobile Robot Control in V-REP with Python" draws a line maze into the course scene
(``v-rep-lab.ttt``: ``Floor``, the ``Maze`` dummy, a green ``Line``, a blue ``Start`` and a red
``End``) over the legacy remote API on port 19997. The original script walked at random, made
about 13 blocking calls per line and left gaps, overlaps and half-drawn mazes behind. This one
generates a real maze from a seed (the same maze on every run), shows it, keeps it as JSON,
and draws and verifies it in a handful of round trips; running it again replaces the maze.

Start CoppeliaSim with the course scene (simulation stopped), or the emulator, then run it::

    vrep-maze serve &                       # an emulated CoppeliaSim on 19997, if no real one
    python examples/course_maze.py --seed 42
    python examples/course_maze.py --seed 7 --algo prim --api zmq   # CoppeliaSim 4.3 and later
"""

import argparse
import sys

import vrep_maze


def main() -> int:
    """Generates the course maze, prints it and draws it; returns the exit status."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seed", type=int, help="the maze's seed [drawn, then printed]")
    parser.add_argument("--algo", default="dfs", help="generation algorithm [dfs]")
    parser.add_argument("--size", default="9x9", help="cells, WxH [9x9: the course's area]")
    parser.add_argument("--api", default="legacy", choices=["legacy", "zmq", "auto"])
    parser.add_argument("--host", default="127.0.0.1")
    parser.add_argument("--port", type=int, help="[19997 for legacy, 23000 for zmq]")
    parser.add_argument("--save", metavar="FILE", help="also write the layout JSON here")
    args = parser.parse_args()

    try:
        maze = vrep_maze.generate(seed=args.seed, algo=args.algo, size=args.size)
    except ValueError as error:  # the option's name, its value and what is allowed
        print(f"error: {error}", file=sys.stderr)
        return 2
    print(maze.render(solution=True))
    metrics = maze.metrics
    print(f"{maze.algorithm} seed {maze.seed}: from {maze.start} to {maze.end}, "
          f"{metrics['solution_cells']} cells and {metrics['solution_turns']} turns on the "
          f"way, {metrics['dead_ends']} dead ends; {len(maze.segments)} lines to draw")
    if args.save:
        maze.save(args.save)
        print(f"wrote {args.save}")

    try:
        report = vrep_maze.apply(maze, api=args.api, host=args.host, port=args.port)
    except vrep_maze.SimulatorError as error:  # with what to do about it, line by line
        print(f"error: {error}", file=sys.stderr)
        return 1
    except vrep_maze.Interrupted as error:  # Ctrl-C: stopped cleanly between two requests
        print(f"{error}; run the same command again to finish the maze", file=sys.stderr)
        return 130
    print(report)
    print("verified: every line, start and end in place")
    return 0


if __name__ == "__main__":
    sys.exit(main())
