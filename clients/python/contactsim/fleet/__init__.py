"""Many worlds: fleets of contactsim servers on Ray (docs/fleet.md).

    from contactsim.fleet import Fleet, Job
    with Fleet(workers=2) as fleet:
        df = fleet.map([Job(scene="config/scenes/bounce.pbtxt", method="impulse",
                            params={"iterations": n}, steps=480) for n in (10, 20, 40)])

``Job`` and ``run_sequential`` need no Ray; ``Fleet`` does (an optional
dependency: ``pip install 'contactsim[fleet]'``).
"""
from .job import Job
from .pool import Fleet, run_sequential
from .compare import fork_compare

__all__ = ["Fleet", "Job", "run_sequential", "fork_compare"]
