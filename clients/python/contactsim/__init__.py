"""Python client of the contactsim rigid-body contact co-simulation service.

    import contactsim
    with contactsim.Client() as c:
        c.wait_for_server()
        ball = c.add_sphere(0.1, position=(0, 0, 1), restitution=0.5)
        c.step(240)
        print(c.state().bodies[ball].position)

The generated LCM message classes (body_cmd_t, state_t, ...) are attributes
of this package; see _lcmtypes for where they are found.
"""
import sys as _sys

from . import _lcmtypes

_lcmtypes.install(_sys.modules[__name__])

from .errors import AuthKeyError, CommandError, TimeoutError  # noqa: E402
from .state import BodyState, Contact, Contacts, Reply, State, Status  # noqa: E402
from .client import DEFAULT_URL, Client, default_url  # noqa: E402
from .lockstep import Controller  # noqa: E402
from .models import Model  # noqa: E402
from .actuators import JointCommand, JointState  # noqa: E402

__version__ = "0.1.0"
__all__ = [
    "Client", "Controller", "AuthKeyError", "CommandError", "TimeoutError", "State", "BodyState", "Contact",
    "Contacts", "Status", "Reply", "DEFAULT_URL", "default_url",
    "body_cmd_t", "body_state_t", "contact_t", "contacts_t", "joint_cmd_t", "reply_t", "scene_cmd_t",
    "state_t", "status_t", "input_t", "model_cmd_t", "model_entry_t", "model_info_t", "Model",
    "joint_command_t", "actuator_cmd_t", "joint_state_t", "JointCommand", "JointState",
]
