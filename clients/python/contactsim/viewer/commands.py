"""Page commands -> contactsim.Client calls, so every command the viewer
sends is the client's own (signed when the client has a key)."""


def _params(text):
    """"key=value key=value" -> dict of text values (the server parses them)."""
    out = {}
    for item in (text or "").split():
        key, sep, value = item.partition("=")
        if not sep or not key:
            raise ValueError("parameter %r is not key=value" % item)
        out[key] = value
    return out


def _method(c, m):
    return c.set_contact_method(str(m["name"]), **_params(m.get("params", "")))


def _joint_target(c, m):
    """A joint's standing target_position (rad or m); its gains stay (docs/actuators.md)."""
    return c.set_joint_actuator(int(m["joint"]), target_position=float(m["position"]))


COMMANDS = {
    "pause": lambda c, m: c.pause(),
    "resume": lambda c, m: c.resume(),
    "step": lambda c, m: c.step(int(m.get("n", 1))),
    "method": _method,
    "reset": lambda c, m: c.reset(),
    "load": lambda c, m: c.load_scene(str(m["path"])),
    "snapshot": lambda c, m: c.snapshot(str(m.get("name") or "viewer")),
    "restore": lambda c, m: c.restore(str(m.get("name") or "viewer")),
    "rewind": lambda c, m: c.rewind(int(m["step"])),
    "joint_target": _joint_target,
}


def run_command(client, msg):
    """Runs msg = {"cmd": name, ...}; returns the reply's message. Raises
    KeyError for an unknown command, CommandError when the server refuses."""
    name = msg.get("cmd")
    if name not in COMMANDS:
        raise KeyError("unknown command %r (known: %s)" % (name, ", ".join(sorted(COMMANDS))))
    reply = COMMANDS[name](client, msg)
    return reply.message
