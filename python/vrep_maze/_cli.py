"""The ``vrep-maze`` command installed by pip: the binary's code, run in this process."""

import signal
import sys

from ._vrep_maze import main as _run


def main() -> None:
    """Runs ``vrep-maze`` with ``sys.argv`` and exits with its status, as the binary does.

    Ctrl-C gets its default action back first (Python's handler would only raise
    ``KeyboardInterrupt`` once the command returned); the commands that stop cleanly
    (``apply``, ``clear``, ``batch``, ``serve``) install their own handler, as in the binary.
    """
    signal.signal(signal.SIGINT, signal.SIG_DFL)
    sys.exit(_run(sys.argv))
