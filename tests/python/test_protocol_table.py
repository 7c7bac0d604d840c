"""The protocol's table (lcmtypes/protocol.toml and reply_t's codes) as the
Python client reads it, against the generated classes and a real server."""
import contactsim
from contactsim import protocol, reply_t

from conftest import REPO, method_names

DEFAULT_SCENE = REPO / "config" / "scenes" / "default.pbtxt"


# Verifies that every channel of the table carries a generated message class,
# that a channel is either incoming or outgoing, and that the client talks on
# the table's channels under its prefix.
def test_every_channel_carries_a_generated_message_class(fake_client):
    for name, channel in protocol.CHANNELS.items():
        assert protocol.message_class(name).__name__ == channel.type
    assert set(protocol.INCOMING) | set(protocol.OUTGOING) == set(protocol.CHANNELS)
    assert not set(protocol.INCOMING) & set(protocol.OUTGOING)
    assert fake_client.channels == {n: fake_client.prefix + "_" + n for n in protocol.CHANNELS}


# Verifies that the reply code names are reply_t's constants, one for one,
# and that CommandError names a code by them.
def test_reply_code_names_are_reply_ts_constants():
    assert contactsim.errors.CODE_NAMES is protocol.CODE_NAMES
    assert {getattr(reply_t, name): name for name in protocol.CODE_NAMES.values()} == protocol.CODE_NAMES
    assert protocol.CODE_NAMES[reply_t.OK] == "OK"
    assert contactsim.CommandError("bad", code=reply_t.NOT_FOUND).code_name == "NOT_FOUND"


# Verifies that the table's methods (which the viewer offers) are the
# server's, and that a default world, the shipped default scene plus bodies
# added with the server's default material, switches to each and steps
# under it.
def test_default_world_switches_to_every_method_the_table_names(launch):
    client = launch(scene=DEFAULT_SCENE).client
    assert tuple(method_names(client)) == protocol.METHODS
    client.add_sphere(0.1, position=(3, 0, 1))
    client.add_box((0.1, 0.1, 0.1), position=(3, 0, 2))
    client.add_plane((0, 0, 1), 0.0)
    for method in protocol.METHODS:  # a refusal raises CommandError
        client.set_contact_method(method)
        client.step(2)
