"""Keeps Python's full garbage collections out of the control cycle.

A full collection traverses every object the process holds. Once a planner has imported JAX
and compiled (the learned controller: about 106 000 objects), one takes about 50 ms on this
project's 2-core test machine: a whole 20 Hz control period, stolen from every robot of a
batch at once, every few thousand cycles (in the host serving 160 robots, 50 000 objects: 45
ms). What exists once a session is configured (modules, compiled functions, weights), or once
the host serves, lives as long as the process, so it is moved out of the collector's sight
(``gc.freeze``): the collections that still run see only what the cycles allocate.

The cost: frozen objects that later become garbage in a reference cycle are not reclaimed
until the next full collection (an ended session's share of what its configure allocated;
objects without cycles are freed as always): about 6 KB per configure (the learned controller:
1.7 MB over 300 configure-cleanup rounds). A peer that configures without end (a hostile one
did, 1 to 3 times a second) would grow the worker for ever, so once the frozen objects have
grown by REGROW since the last full collection, the next settle unfreezes them first: what
replaced sessions left is collected then, at configure time, never in a control cycle.
"""

from __future__ import annotations

import gc

#: A full collection (the frozen objects too) once they have grown by this factor since the
#: last one: memory stays within this factor of what the live sessions hold, and the full
#: collections' cost (~50 ms with 100 000 objects) comes once per many configures.
REGROW = 1.5
_frozen_after_full = 0  # how many objects the last full collection left frozen


def settle_heap() -> None:
    """After a configure, or start-up: collect what it left as garbage, freeze the rest."""
    global _frozen_after_full
    full = gc.get_freeze_count() > REGROW * _frozen_after_full
    if full:
        gc.unfreeze()  # the garbage replaced sessions left among them is collected now
    gc.collect()
    gc.freeze()
    if full:
        _frozen_after_full = gc.get_freeze_count()
