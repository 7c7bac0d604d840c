"""``client.fork_compare``: a mixin of Client; the work is in
contactsim/fleet/compare.py, imported only when called (Ray is optional)."""


class ForkCommands:
    def fork_compare(self, methods, steps, **kwargs):
        """Snapshots this world and runs it forward ``steps`` steps under
        each of ``methods`` ("name", ("name", {params}) or "name:k=v,...")
        on a fleet; returns a pandas DataFrame, one row per method: max
        penetration, energy drift, ms per step, contacts, departure from the
        first method's trajectory (m). kwargs: fleet, workers, bodies, plot,
        progress (contactsim.fleet.compare.fork_compare)."""
        from .fleet.compare import fork_compare
        return fork_compare(self, methods, steps, **kwargs)
