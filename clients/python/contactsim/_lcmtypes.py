"""Makes the generated LCM message classes attributes of this package.

The LCM code generator writes ``<build>/lcmtypes/python/contactsim/<type>.py``; those modules
refer to each other as ``contactsim.<type>`` and expect that name to be the
*class* (the generator's own ``__init__`` does ``from .body_state_t import
body_state_t``). This package is also called ``contactsim``, so it appends the
generated folder to its ``__path__`` and binds every class under its name.

An installed wheel carries its own copy in ``contactsim/_generated`` (made
by lcm-gen when the wheel is built, clients/python/setup.py) and always uses
it: the classes then match the client they were built with. In the
repository (an editable install or PYTHONPATH) there is no such folder, and
the folder is ``$CONTACTSIM_BUILD_DIR/lcmtypes/python/contactsim`` when that
variable is set, else ``<repo>/build/lcmtypes/python/contactsim`` relative to
this file. The protocol's table (``protocol.toml``, read by
``contactsim.protocol``) lies beside the modules, in the wheel and the build
folder alike.
"""
import importlib
import os

# Nested types first: the containers' code looks them up as contactsim.<name>.
TYPE_NAMES = (
    "body_state_t",
    "contact_t",
    "body_cmd_t",
    "joint_command_t",
    "input_t",
    "scene_cmd_t",
    "joint_cmd_t",
    "model_cmd_t",
    "model_entry_t",
    "model_info_t",
    "reply_t",
    "state_t",
    "contacts_t",
    "status_t",
    "progress_t",
    "range_reading_t",
    "contact_reading_t",
    "sensors_t",
    "sensor_cmd_t",
    "ray_cast_t",
    "ray_hits_t",
    "actuator_cmd_t",
    "joint_state_t",
)
PROTOCOL_TABLE = "protocol.toml"


def packaged_dir():
    """The wheel's copy of the generated modules (absent in the repository)."""
    return os.path.join(os.path.dirname(os.path.abspath(__file__)), "_generated")


def generated_dir():
    """Folder holding the generated contactsim/*.py modules."""
    if os.path.isdir(packaged_dir()):
        return packaged_dir()
    build = os.environ.get("CONTACTSIM_BUILD_DIR")
    if build:
        return os.path.join(os.path.abspath(build), "lcmtypes", "python", "contactsim")
    repo = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(
        os.path.abspath(__file__)))))
    return os.path.join(repo, "build", "lcmtypes", "python", "contactsim")


def install(package):
    """Extends ``package.__path__`` and binds each generated class on it."""
    folder = generated_dir()
    missing = [f for f in [n + ".py" for n in TYPE_NAMES] + [PROTOCOL_TABLE]
               if not os.path.isfile(os.path.join(folder, f))]
    if missing:
        raise ImportError(
            "contactsim: generated LCM types not found in %s (missing %s). "
            "Run `make` in the repository (or `cmake --build build --target "
            "contactsim_lcmtypes_gen`), or set CONTACTSIM_BUILD_DIR to the build "
            "folder that holds lcmtypes/python/contactsim." % (folder, ", ".join(missing)))
    if folder not in package.__path__:
        package.__path__.append(folder)
    classes = {}
    for name in TYPE_NAMES:
        module = importlib.import_module(package.__name__ + "." + name)
        classes[name] = getattr(module, name)
        setattr(package, name, classes[name])
    # Importing a submodule may have rebound an earlier name to its module.
    for name, cls in classes.items():
        setattr(package, name, cls)
    return classes
