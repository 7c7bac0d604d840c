"""The protocol's channels, reply codes and contact method names.

Channels and method names are the table in ``lcmtypes/protocol.toml``, read
from beside the generated message modules (``_lcmtypes.generated_dir``: a
wheel carries its own copy); the reply codes are reply_t's constants
(``lcmtypes/reply_t.lcm``). The server and the C++ client are generated from
the same two files, so a channel or a code is declared once.

    from contactsim import protocol
    protocol.CHANNELS["STATE"].type        # "state_t"
    protocol.channel_names("CONTACTSIM")   # {"BODY_CMD": "CONTACTSIM_BODY_CMD", ...}
"""
import os
from collections import namedtuple

try:
    import tomllib
except ImportError:  # Python < 3.11
    import tomli as tomllib

from . import _lcmtypes, reply_t

# incoming: clients to server; replied: every command is answered on REPLY;
# published: when the server sends an outgoing one
Channel = namedtuple("Channel", "name type incoming replied published")


def _load(path):
    with open(path, "rb") as fh:
        table = tomllib.load(fh)
    rows = [(row, True) for row in table["incoming"]] + [(row, False) for row in table["outgoing"]]
    channels = {row["name"]: Channel(row["name"], row["type"], incoming, row.get("replied", False),
                                     row.get("published", "")) for row, incoming in rows}
    return channels, tuple(table["methods"])


# name -> Channel, in the table's order (incoming first)
CHANNELS, METHODS = _load(os.path.join(_lcmtypes.generated_dir(), _lcmtypes.PROTOCOL_TABLE))
INCOMING = tuple(n for n, c in CHANNELS.items() if c.incoming)
OUTGOING = tuple(n for n, c in CHANNELS.items() if not c.incoming)
# reply_t code -> its name, e.g. 1 -> "INVALID_ARGUMENT"
CODE_NAMES = {value: name for name, value in vars(reply_t).items()
              if name.isupper() and isinstance(value, int) and not isinstance(value, bool)}


def channel_names(prefix):
    """{name: "<prefix>_<name>"} for every channel of the protocol."""
    return {name: "%s_%s" % (prefix, name) for name in CHANNELS}


def channel(prefix, name):
    """The full name of channel ``name``; KeyError if the protocol has none."""
    return "%s_%s" % (prefix, CHANNELS[name].name)


def message_class(name):
    """The generated class of the messages on channel ``name``."""
    import contactsim  # noqa: PLC0415 - the package binds the generated classes
    return getattr(contactsim, CHANNELS[name].type)
