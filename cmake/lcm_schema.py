"""Reads the protocol's declarations: lcmtypes/*.lcm and lcmtypes/protocol.toml.

The one reader of these files. The build's generators (lcm_wire_check.py,
protocol_gen.py) and scripts/lcm_wire.py (the garbage corpus) all take their
structs, constants and channels from here.

An .lcm file holds one struct (LCM's type specification): constants
``const T NAME = value;`` and fields ``T name[dim]...;`` in declaration
order, where a dimension is a number or the name of an earlier integer field.
"""
import re
from pathlib import Path

try:
    import tomllib
except ImportError:  # Python < 3.11
    import tomli as tomllib

FIELD = re.compile(r"^\s*([A-Za-z_][\w.]*)\s+([A-Za-z_]\w*)\s*((?:\[[^\]]+\]\s*)*)$")
CONSTANT = re.compile(r"^const\s+\w+\s+([A-Za-z_]\w*)\s*=\s*(-?\w+)$")


class LcmStruct:
    """One .lcm file: ``name``, ``fields`` [(type, name, [dims])] and
    ``constants`` [(name, int value)], both in declaration order, and its
    ``package`` (the C++ namespace of the generated class)."""

    def __init__(self, name, fields, constants, package="contactsim"):
        self.name, self.fields, self.constants = name, fields, constants
        self.package = package


def parse_lcm(path):
    """The LcmStruct of one .lcm file; raises ValueError on a statement it cannot read."""
    text = re.sub(r"//[^\n]*|/\*.*?\*/", "", Path(path).read_text(), flags=re.S)
    name = re.search(r"\bstruct\s+(\w+)", text).group(1)
    package = re.search(r"\bpackage\s+(\w+)\s*;", text)
    body = text[text.index("{") + 1:text.rindex("}")]
    fields, constants = [], []
    for stmt in (s.strip() for s in body.split(";")):
        if not stmt:
            continue
        if stmt.startswith("const "):
            m = CONSTANT.match(stmt)
            if not m:
                raise ValueError("%s: cannot parse constant %r" % (path, stmt))
            constants.append((m.group(1), int(m.group(2), 0)))
            continue
        m = FIELD.match(stmt)
        if not m:
            raise ValueError("%s: cannot parse field %r" % (path, stmt))
        dims = re.findall(r"\[\s*([^\]\s]+)\s*\]", m.group(3))
        fields.append((m.group(1).split(".")[-1], m.group(2), dims))  # package.type -> type
    return LcmStruct(name, fields, constants, package.group(1) if package else "contactsim")


def parse_folder(folder):
    """{struct name: LcmStruct} of every .lcm file in folder, by file name."""
    return {s.name: s for s in (parse_lcm(p) for p in sorted(Path(folder).glob("*.lcm")))}


class Channel:
    """One row of protocol.toml: ``name`` (the suffix after <prefix>_),
    ``type`` (its LCM struct), ``incoming`` (clients to server), ``replied``
    (incoming: every command is answered on REPLY) and ``published`` (outgoing:
    when the server sends it)."""

    def __init__(self, name, type, incoming, replied=False, published=""):  # noqa: A002 - the table's key
        self.name, self.type, self.incoming = name, type, incoming
        self.replied, self.published = replied, published


class Protocol:
    """protocol.toml: ``channels`` in table order (incoming first), ``methods``."""

    def __init__(self, channels, methods):
        self.channels, self.methods = channels, methods


def load_protocol(path, structs=None):
    """The Protocol of a protocol.toml; with ``structs`` (parse_folder), checks
    that every channel's type is one of them."""
    with open(path, "rb") as fh:
        table = tomllib.load(fh)
    channels = [Channel(incoming=True, **row) for row in table["incoming"]]
    channels += [Channel(incoming=False, **row) for row in table["outgoing"]]
    names = [c.name for c in channels]
    for c in channels:
        if names.count(c.name) > 1 or not re.fullmatch(r"[A-Z][A-Z0-9_]*", c.name):
            raise ValueError("%s: channel name %r is repeated or not UPPER_CASE" % (path, c.name))
        if structs is not None and c.type not in structs:
            raise ValueError("%s: channel %s carries %r, which no .lcm file declares" % (path, c.name, c.type))
    return Protocol(channels, list(table["methods"]))
