"""``python -m vrep_maze ...`` runs the ``vrep-maze`` command."""

from ._cli import main

main()
