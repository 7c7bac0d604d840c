"""The first STATUS means the server is up: a command sent right after it is answered
(it once came before the server subscribed to its command channels)."""
import pytest

import contactsim


@pytest.mark.parametrize("attempt", range(5))
def test_first_command_after_first_status_is_answered(launch, attempt):
    s = launch()
    try:
        s.client.step(1)
    except contactsim.TimeoutError as e:
        pytest.fail("the command sent right after the first STATUS got no reply: the server "
                    "publishes STATUS before it subscribes to its command channels (%s)" % e)
